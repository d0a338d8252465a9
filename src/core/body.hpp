// Body storage, split three ways (Box2D v3 style):
//  - Body:        bookkeeping (definition, shapes), touched when building or querying;
//  - BodyMotion:  integration state between steps (COM position, rotation, velocities, forces);
//  - SolverBody:  what the constraint loops read and write during one step (v, w, the position
//                 and rotation deltas accumulated over the substeps, inverse mass properties).
// Constraints index the solver-body array directly; a static body is an identity solver body
// (zero inverse mass, zero velocity), so constraint code needs no branch on body type.
#pragma once

#include <vector>

#include "ragdoll_sim/body.hpp"
#include "ragdoll_sim/shape.hpp"

namespace ragdoll_sim {

struct Body {
  BodyDef def;
  std::vector<ShapeDef> shapes;
  std::vector<int> shape_ids;  // world shape indices
};

struct BodyMotion {
  Vec3 x = Vec3::Zero();   // centre of mass, world
  Quat q = Quat::Identity();
  Vec3 v = Vec3::Zero();
  Vec3 w = Vec3::Zero();
  Vec3 force = Vec3::Zero();
  Vec3 torque = Vec3::Zero();
  Vec3 local_com = Vec3::Zero();
  Mat3 inertia_local = Mat3::Identity();      // about the COM, link axes
  Mat3 inv_inertia_local = Mat3::Zero();
  double inv_mass = 0.0;
  double linear_damping = 0.0, angular_damping = 0.0, gravity_scale = 1.0;
  double extent = 0.0;      // farthest shape point from the COM (sleep speed = max(|v|, extent |w|))
  double sleep_time = 0.0;  // how long the body has been slow
  bool awake = false;       // static and sleeping bodies are not awake

  Transform linkPose() const { return {x - q * local_com, q}; }
};

// One cache line holds what every constraint row reads and writes (v, w, inverse mass): a
// row touches one line per body, and a body at the cut of a split island moves one line
// between the cores per sweep (scene c: +2 %).
struct alignas(64) SolverBody {
  Vec3 v = Vec3::Zero();
  Vec3 w = Vec3::Zero();
  double inv_mass = 0.0;
  Quat dq = Quat::Identity();    // rotation since the start of the step (world, left-multiplied)
  Vec3 dp = Vec3::Zero();        // COM displacement since the start of the step
  Mat3 inv_inertia = Mat3::Zero();  // world, frozen at the start of the step
};

}  // namespace ragdoll_sim
