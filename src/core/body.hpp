// Body storage, split three ways (Box2D v3 style):
//  - Body:        bookkeeping (definition, shapes), touched when building or querying;
//  - BodyMotion:  integration state between steps (COM position, rotation, velocities, forces);
//  - SolverBody:  what the constraint loops read and write during one step (v, w, the position
//                 and rotation deltas accumulated over the substeps, inverse mass properties).
// Constraints index the solver-body array directly; a static body is an identity solver body
// (zero inverse mass, zero velocity), so constraint code needs no branch on body type.
#pragma once

#include <cmath>
#include <vector>

#include "ragdoll_sim/body.hpp"
#include "ragdoll_sim/shape.hpp"

namespace ragdoll_sim {

struct Body {
  BodyDef def;
  std::vector<ShapeDef> shapes;
  std::vector<int> shape_ids;  // world shape indices
  // Bodies of higher index that this one never collides with (World's setCollides; a pair is
  // listed once, under its lower body), sorted: a ragdoll link's few neighbours, so the
  // broadphase's filter scans a short list instead of missing the cache in a hash set.
  std::vector<int> no_collide;
  bool alive = true;  // false once destroyed: the slot stays so that other ids keep their index
};

// Translation invariance: centres of mass sit on a grid of 2^-32 m (0.23 nm) within 2^20 m
// (1048 km) of the origin, where the grid's points are doubles and sums and differences of
// them are exact. Every step moves a body by its displacement rounded to the grid (the
// remainder is carried into the next step's, so a steady motion does not drift), hence
// x_B - x_A, and x - o for any other centre o, do not depend on where the pair is: the
// solver and the narrowphase work from such differences (joint centres, contact origins),
// and a scene moved by any grid vector gives the same motion bit for bit, so copies of one
// ragdoll placed apart behave alike instead of diverging by round-off.
constexpr double kPositionGrid = 4294967296.0;  // 2^32 steps per metre
inline double snapPosition(double x) {
  return std::abs(x) < kWorldRange ? std::nearbyint(x * kPositionGrid) / kPositionGrid : x;
}
inline Vec3 snapPosition(const Vec3& x) {
  return {snapPosition(x.x()), snapPosition(x.y()), snapPosition(x.z())};
}

struct BodyMotion {
  Vec3 x = Vec3::Zero();   // centre of mass, world, on the grid (snapPosition)
  Vec3 x_carry = Vec3::Zero();  // displacement not yet on the grid (|.| <= 2^-33 m)
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
  // It sped up while its island took the rest substeps (SleepDef::rest_substeps): its islands
  // take the full substeps until it sleeps.
  bool rest_failed = false;

  Transform linkPose() const { return {x - q * local_com, q}; }
};

// x_B - x_A with the carried remainders: joints hold their anchors to this (a rigid row would
// otherwise chase up to 2^-33 m between the grid points, ~1e-8 m/s for ever in zero gravity);
// exact grid difference plus a tiny invariant one, so it is as position-free as x_B - x_A.
inline Vec3 centerOffset(const BodyMotion& A, const BodyMotion& B) {
  return (B.x - A.x) + (B.x_carry - A.x_carry);
}

// One cache line holds what every constraint row reads and writes (v, w, inverse mass): a
// row touches one line per body, and a body at the cut of a split island moves only one line
// between the cores per sweep.
struct alignas(64) SolverBody {
  Vec3 v = Vec3::Zero();
  Vec3 w = Vec3::Zero();
  double inv_mass = 0.0;
  // The last position sweep of the step (numbered from 1) that moved it: a projection whose
  // bodies have not moved since its last look, and which moved nothing then, is skipped
  // (unchangedSince, solver_context.hpp). In the padding before dq: the struct stays 192 bytes.
  int moved_sweep = 0;
  Quat dq = Quat::Identity();    // rotation since the start of the step (world, left-multiplied)
  Vec3 dp = Vec3::Zero();        // COM displacement since the start of the step
  Mat3 inv_inertia = Mat3::Zero();  // world, frozen at the start of the step
};
static_assert(sizeof(SolverBody) == 3 * 64, "SolverBody grew past its three cache lines");

}  // namespace ragdoll_sim
