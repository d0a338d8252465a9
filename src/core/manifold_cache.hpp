// Manifold cache: a touching pair whose relative pose has barely moved since its manifold was
// computed keeps that manifold instead of running the narrowphase again (Jolt's body pair
// cache). The manifold is stored in the shapes' own frames: the normal n_A in A's frame and,
// per point, the surface points a_i (on A, in A's frame) and b_i (on B, in B's frame), with
// a_i = p_i - n s_i / 2 and b_i = p_i + n s_i / 2 for the world midpoint p_i and separation s_i.
// Reuse at the poses xa, xb carries the features along rigidly:
//   n = qa n_A,   a = xa a_i,   b = xb b_i,   s = (b - a) . n,   p = (a + b) / 2,
// with the feature ids unchanged (the warm start matches every point).
// When: the reference is the relative pose R = xm^-1 xo at the last narrowphase call (m: the
// bounded shape whose frame is kept, o the other; not last step's pose, so the error cannot
// accumulate). Since then every point of the moving shape o has moved in m's frame by at most
//   |dp| + 2 |v| r_o      (dq = (w, v) = R^-1 R_now turns a point at radius r by the chord
//                          2 r sin(theta / 2) = 2 r |v|; r_o: the farthest point of o from
//                          its origin).
// While that bound is within `distance`:
// - a vertex or rim point keeps its exact separation (plane contacts are all such points);
// - a curved surface errs by O(distance^2 / radius) (1 mm on a 5 cm cylinder: 0.01 mm);
// - a point where a tilted face was clipped by the other face's side rides along with its body
//   instead of sliding along the edge: its separation errs by the tilt times the slide (a box
//   tilted 0.02 rad on another: up to 0.36 mm at 1 mm, test_manifold_cache.cpp), less than
//   the linear slop (0.5 mm) that the solver leaves anyway;
// - a feature that was outside the speculative band is still at least (band - distance) away,
//   so it cannot touch within the step while the bodies move less than that per step
//   (world.cpp checks it).
// A separated pair (no manifold, both shapes bounded) is kept the same way with its clearance
// gap - band, gap the lower bound on the distance that the narrowphase found: the distance
// shrinks by at most the motion bound, so while that stays within the clearance the pair is
// still beyond the band, exactly (no approximation: the narrowphase would find nothing).
#pragma once

#include <algorithm>
#include <cmath>

#include "narrowphase.hpp"

namespace ragdoll_sim {

struct ManifoldCache {
  Transform reference;                 // xm^-1 xo when the manifold was computed
  Vec3 normal_a = Vec3::UnitZ();       // normal in A's frame
  Vec3 point_a[Manifold::kMaxPoints];  // surface point on A, A's frame
  Vec3 point_b[Manifold::kMaxPoints];  // surface point on B, B's frame
  double lever = 0.0;                  // r_o: farthest point of o from its origin
  double clearance = 0.0;              // > 0: a separated pair, this far beyond the band
  bool b_moves = true;                 // o = B (m = A), else o = A (B is the unbounded one)
  bool valid = false;

  // Keeps `m` (computed at xa, xb with speculative distance `band`) for reuse: a manifold when
  // `touching` is allowed (the cache distance is on), a separation whenever the narrowphase
  // gave a gap beyond the band between bounded shapes. a, b: the shapes' geometries (a plane's
  // frame is kept, the other shape moves in it).
  void store(const Manifold& m, const Geometry& a, const Transform& xa, const Geometry& b,
             const Transform& xb, double band, bool touching) {
    clearance = m.count == 0 && !isUnbounded(a) && !isUnbounded(b) ? m.gap - band : 0.0;
    valid = m.count > 0 ? touching : clearance > 0.0;
    if (!valid) return;
    b_moves = !isUnbounded(b);
    lever = boundingRadius(b_moves ? b : a);
    reference = relative(xa, xb);
    if (m.count == 0) return;
    normal_a = xa.q.conjugate() * m.normal;
    for (int i = 0; i < m.count; ++i) {
      const Vec3 half = (0.5 * m.points[i].separation) * m.normal;
      point_a[i] = xa.applyInverse(m.points[i].point - half);
      point_b[i] = xb.applyInverse(m.points[i].point + half);
    }
  }

  // True when no point of the moving shape has moved more than `distance` relative to the
  // other since the manifold was computed; a separated pair is tested against its clearance
  // instead (distance is ignored).
  bool holds(const Transform& xa, const Transform& xb, double distance) const {
    if (!valid) return false;
    const Transform now = relative(xa, xb);
    const Quat dq = reference.q.conjugate() * now.q;
    const double chord = 2.0 * dq.vec().norm() * lever;
    return (now.p - reference.p).norm() + chord <= (separated() ? clearance : distance);
  }

  bool separated() const { return clearance > 0.0; }

  // Rebuilds `m` (same count and feature ids as when stored) at the poses xa, xb.
  void apply(const Transform& xa, const Transform& xb, Manifold& m) const {
    m.normal = xa.q * normal_a;
    for (int i = 0; i < m.count; ++i) {
      const Vec3 a = xa.apply(point_a[i]), b = xb.apply(point_b[i]);
      m.points[i].separation = (b - a).dot(m.normal);
      m.points[i].point = 0.5 * (a + b);
    }
  }

 private:
  Transform relative(const Transform& xa, const Transform& xb) const {
    return b_moves ? xa.inverse() * xb : xb.inverse() * xa;
  }
};

}  // namespace ragdoll_sim
