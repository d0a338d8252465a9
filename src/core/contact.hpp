// Persistent contacts: one per overlapping shape pair, keyed by the ordered shape pair, with
// the accumulated impulses of each manifold point kept by feature id for warm starting.
#pragma once

#include <cstdint>
#include <vector>

#include "narrowphase.hpp"

namespace ragdoll_sim {

struct Contact {
  uint64_t key = 0;          // (shape_a << 32) | shape_b, shape_a < shape_b
  int shape_a = -1, shape_b = -1;
  int body_a = -1, body_b = -1;
  Manifold manifold;      // points relative to `origin`, normal in world axes
  Vec3 origin = Vec3::Zero();  // world: the centre of the pair's first dynamic body (on the grid)
  double normal_impulse[Manifold::kMaxPoints] = {};
  Vec3 friction_impulse[Manifold::kMaxPoints] = {Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};  // world, re-projected on new tangents
  double static_friction = 0.0, kinetic_friction = 0.0, restitution = 0.0;
  double rolling = 0.0;  // m: rolling_resistance * rolling radius (max of the two shapes)
  // The pair's compliance (Material::contact_hertz, its damping ratio); 0 Hz: rigid.
  double contact_hertz = 0.0, contact_damping_ratio = 1.0;
  Vec3 rolling_impulse = Vec3::Zero();  // N m s, world, in the tangent plane (warm start)
  double impulse_h = 0.0;  // s: the substep the impulses were accumulated over (0: none yet)
  // Separating-axis cache: the last narrowphase found the shapes apart along this world axis
  // (A to B). While their projections on it stay farther apart than the speculative
  // distance, the pair is skipped (a projection gap is a lower bound on the distance).
  Vec3 sep_axis = Vec3::Zero();
  bool sep_valid = false;
};

// What impulse tracking (World::setContactImpulseTracking) kept of a contact's last step, per
// manifold point: the normal impulse summed over the substeps and restitution, the largest
// substep force, and the approach speed before the step.
struct ContactTrack {
  uint64_t key = 0;  // the contact's key; 0: the last step did not solve it
  double step_impulse[Manifold::kMaxPoints] = {};
  double peak_force[Manifold::kMaxPoints] = {};
  double closing_speed[Manifold::kMaxPoints] = {};
};

inline uint64_t pairKey(int shape_a, int shape_b) {
  return (uint64_t(uint32_t(shape_a)) << 32) | uint32_t(shape_b);
}

// Carries the impulses of `old` points to the points of `fresh` with the same feature id.
inline void matchImpulses(const Contact& old, Contact& fresh) {
  fresh.rolling_impulse = old.rolling_impulse;
  fresh.impulse_h = old.impulse_h;
  for (int i = 0; i < fresh.manifold.count; ++i) {
    fresh.normal_impulse[i] = 0.0;
    fresh.friction_impulse[i].setZero();
    for (int k = 0; k < old.manifold.count; ++k) {
      if (old.manifold.points[k].id == fresh.manifold.points[i].id) {
        fresh.normal_impulse[i] = old.normal_impulse[k];
        fresh.friction_impulse[i] = old.friction_impulse[k];
        break;
      }
    }
  }
}

}  // namespace ragdoll_sim
