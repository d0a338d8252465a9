// What the last World::step did, for users who study it: the contact forces of each touching
// shape pair, the constraint wrench and axis efforts of each joint, and the velocities of
// chosen bodies at the end of every substep (an accelerometer's samples). World fills them on
// request (world.hpp); src/core/world_reports.cpp derives them.
#pragma once

#include <array>
#include <vector>

#include "ragdoll_sim/body.hpp"
#include "ragdoll_sim/math.hpp"

namespace ragdoll_sim {

// One point of a touching shape pair after the last step. Forces are the last substep's
// accumulated impulses divided by its length (the force that held during it; in the step of a
// bounce the rigid restitution impulse is in it too). The point and depth are those of the
// step's collide (the poses at its start).
struct ContactPointReport {
  Vec3 point = Vec3::Zero();           // world, midway between the surfaces
  double depth = 0.0;                  // m, > 0 when the surfaces overlap
  double normal_force = 0.0;           // N, on B along the normal (>= 0)
  Vec3 friction_force = Vec3::Zero();  // N, on B, world, in the tangent plane
  // Over the whole step (World::setContactImpulseTracking on; else 0): the normal impulse
  // summed over the substeps and restitution (N s), the largest substep normal force (N), and
  // the approach speed v_c = (v_a - v_b).n at the point before the step (m/s, > 0 approaching).
  double step_impulse = 0.0;
  double peak_force = 0.0;
  double closing_speed = 0.0;
  double separating_speed = 0.0;  // m/s, (v_b - v_a).n at the point after the step
};

// A touching shape pair: at least one point overlaps or carried a normal impulse in the step
// (speculative points that stayed apart are left out, as are pairs that only came near).
struct ContactReport {
  BodyId body_a, body_b;
  int shape_a = -1, shape_b = -1;  // indices in bodyShapes of each body
  Vec3 normal = Vec3::UnitZ();     // world, unit, from A to B
  int count = 0;                   // points used in `points`
  std::array<ContactPointReport, 4> points;
  // Sums over the points (normal + friction force, and rolling resistance torque): world axes,
  // each torque about that body's centre of mass; force_a = -force_b.
  Vec3 force_a = Vec3::Zero(), torque_a = Vec3::Zero();
  Vec3 force_b = Vec3::Zero(), torque_b = Vec3::Zero();
};

// The wrench a joint's constraint parts (anchor, locks, limits, motors with their damping)
// put on body B over the last substep; body A takes the opposite. World axes; the torque is
// about B's anchor point (the joint origin), so the anchor force adds none to it.
struct JointWrench {
  Vec3 force = Vec3::Zero();   // N
  Vec3 torque = Vec3::Zero();  // N m
};

// Velocities of a tracked body (World::trackBody) at the end of each substep of the last step:
// sample k - sample k-1 over h is the mean acceleration in substep k. The last sample is the
// velocity the body ends the step with (restitution included). A tracked body the step did
// not solve (asleep, static) gets `substeps` equal samples of its velocity.
struct SubstepVelocities {
  double h = 0.0;  // s, substep length (the rest substeps' for a resting island)
  Vec3 start_linear = Vec3::Zero(), start_angular = Vec3::Zero();  // before the step (COM)
  std::vector<Vec3> linear, angular;  // centre of mass velocity, angular velocity (world)
};

}  // namespace ragdoll_sim
