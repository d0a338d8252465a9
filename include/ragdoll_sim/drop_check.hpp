// Drop test of a RagdollDef (ROS-free): spawn it just above a ground plane, let it fall and
// measure how well the solver holds it together. Used by ragdoll_check and the URDF zoo test;
// measureDrop takes the measurements in a World that someone else builds and steps (a Scene with
// a world file: ragdoll_check --world).
#pragma once

#include <functional>

#include "ragdoll_sim/ragdoll.hpp"

namespace ragdoll_sim {

struct DropSettings {
  double seconds = 3.0;      // sim time
  double dt = 1e-3;          // s, physics step (the node's default rate)
  int substeps = SolverSettings().substeps;  // the node's default
  double clearance = 0.05;   // m between the lowest shape point and the ground at spawn
};

struct DropReport {
  bool finite = true;            // every body state stayed finite (no NaN / inf)
  double spawn_z = 0;            // m, root link height at spawn (rest pose, upright)
  double max_penetration = 0;    // m, deepest contact of the ragdoll (ground, obstacle or self) over the run
  double max_anchor_error = 0;   // m, largest joint anchor separation over the run
  double rest_height = 0;        // m, root link origin z at the end
  double lowest_point = 0;       // m, lowest shape point at the end
  double min_lowest_point = 0;   // m, lowest shape point over the run
  double final_speed = 0;        // m/s, fastest body (COM speed + angular speed x 0.1 m) at the end
  // As final_speed, over the bodies that touch something at the end (a contact within 1 mm):
  // a limb left hanging in the air swings on without joint damping, a body lying on the
  // ground or on another limb must be still.
  double final_contact_speed = 0;
  // J, mechanical energy (kinetic + gravity) at the end minus that 2 s before (half the run
  // when shorter): a solver that pumps energy into resting contacts makes it positive.
  double late_energy_change = 0;
  double seconds = 0;            // sim time actually run (less when a state went non-finite)
};

// Lowest world z of a shape (planes: +inf) whose body frame is at `body_pose`.
double lowestPoint(const ShapeDef& shape, const Transform& body_pose);
// Highest world z of a shape (planes: -inf).
double highestPoint(const ShapeDef& shape, const Transform& body_pose);
// Lowest z of the model's shapes in its rest pose with the root link at the origin (0 without
// shapes).
double restLowestPoint(const RagdollDef& def);

DropReport dropTest(const RagdollDef& def, const DropSettings& settings = DropSettings());

// The metrics of ragdoll `r` (spawned from `def`) in `world` while `step` advances the world by
// settings.dt, for settings.seconds of sim time or until a body state of the ragdoll goes
// non-finite. Only the ragdoll's bodies and contacts count (other objects may share the world);
// spawn_z is left to the caller.
DropReport measureDrop(const World& world, const Ragdoll& r, const RagdollDef& def,
                       const std::function<void()>& step, const DropSettings& settings);

}  // namespace ragdoll_sim
