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
// - a rolling point is not a feature: the point of a sphere or capsule below its core (centre,
//   segment point) along the normal, or a cylinder's point on its side or rim below an axis
//   point, where the normal leaves the axis. Carried along with its body it trails a rolling
//   shape (up to the cache distance), and the normal force there drives the roll, so a ball
//   or a lying ragdoll's head would roll ever faster. Such a point keeps its core point instead:
//     sphere, capsule: x = core + sigma r n;   cylinder: x = core + sigma r u,
//     u = the unit part of n across the axis (sigma = +1 on A, -1 on B: A's surface faces n),
//   exact for a rolling sphere and a capsule or cylinder rolling about its axis. The other
//   side's point, where it does not roll, is where the rolling one meets it along n (carried,
//   a face's point would trail the same way), so the contact point is p = x - sigma s n / 2,
//   with s = (b - a) . n, exact for a flat feature. A plane's point is always such a foot:
//   against a plane, p is found from the other side's point, rolling or a vertex (a box
//   sliding on the ground keeps its points under its corners). With both sides round (sphere,
//   capsule) the normal is the direction between the first point's cores; with only A
//   rolling it is kept in B's frame (a plane's normal stays the plane's).
// A separated pair (no manifold, both shapes bounded) is kept the same way with its clearance
// gap - band, gap the lower bound on the distance that the narrowphase (or the gap of the
// shapes' projections on last step's separating axis, collide.cpp) found: the distance
// shrinks by at most the motion bound, so while that stays within the clearance the pair is
// still beyond the band, exactly (no approximation: the narrowphase would find nothing).
#pragma once

#include <algorithm>
#include <cmath>

#include "narrowphase.hpp"

namespace ragdoll_sim {

struct ManifoldCache {
  Transform reference;                 // xm^-1 xo when the manifold was computed
  Vec3 normal_a = Vec3::UnitZ();       // normal in A's frame (B's when normalInB())
  Vec3 point_a[Manifold::kMaxPoints];  // surface point on A, A's frame
  Vec3 point_b[Manifold::kMaxPoints];  // surface point on B, B's frame
  // Rolling points: bit i set when point i of that side keeps its core point (shape frame) in
  // point_a / point_b instead of its surface point.
  uint8_t rolls_a = 0, rolls_b = 0;
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
    for (int i = 0; i < m.count; ++i) {
      const Vec3 half = (0.5 * m.points[i].separation) * m.normal;
      point_a[i] = xa.applyInverse(m.points[i].point - half);
      point_b[i] = xb.applyInverse(m.points[i].point + half);
    }
    rolls_a = toCores(a, xa, 1.0, m.normal, m.count, point_a);
    rolls_b = toCores(b, xb, -1.0, m.normal, m.count, point_b);
    normal_a = (normalInB() ? xb : xa).q.conjugate() * m.normal;
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

  // Rebuilds `m` (same count and feature ids as when stored) for the shapes a, b (those given
  // to store) at the poses xa, xb.
  void apply(const Geometry& ga, const Transform& xa, const Geometry& gb, const Transform& xb,
             Manifold& m) const {
    const bool cyl_a = ga.type == ShapeType::Cylinder, cyl_b = gb.type == ShapeType::Cylinder;
    m.normal = (normalInB() ? xb : xa).q * normal_a;
    if (m.count > 0 && (rolls_a & rolls_b & 1) && !cyl_a && !cyl_b) {
      const Vec3 d = xb.apply(point_b[0]) - xa.apply(point_a[0]);
      if (d.norm() > 1e-9) m.normal = d.normalized();
    }
    // Core-to-surface offsets, the same for every rolling point of a side.
    const Vec3 off_a = rolls_a ? Vec3(ga.radius * outward(xa, cyl_a, 1.0, m.normal)) : Vec3::Zero();
    const Vec3 off_b = rolls_b ? Vec3(gb.radius * outward(xb, cyl_b, -1.0, m.normal)) : Vec3::Zero();
    const bool plane_a = isUnbounded(ga), plane_b = isUnbounded(gb);
    for (int i = 0; i < m.count; ++i) {
      const bool ra = rolls_a >> i & 1, rb = rolls_b >> i & 1;
      const Vec3 a = ra ? Vec3(xa.apply(point_a[i]) + off_a) : xa.apply(point_a[i]);
      const Vec3 b = rb ? Vec3(xb.apply(point_b[i]) + off_b) : xb.apply(point_b[i]);
      const double s = (b - a).dot(m.normal);
      m.points[i].separation = s;
      m.points[i].point = plane_a || (rb && !ra)  ? Vec3(b - 0.5 * s * m.normal)
                          : plane_b || (ra && !rb) ? Vec3(a + 0.5 * s * m.normal)
                                                   : Vec3(0.5 * (a + b));
    }
  }

 private:
  // Only A rolls: the normal is kept in B's frame (a plane's normal stays the plane's).
  bool normalInB() const { return rolls_a != 0 && rolls_b == 0; }

  // Unit direction, world, from a rolling point's core to its surface point: sigma n, or for a
  // cylinder sigma times n's part across the axis (zero when n runs along the axis).
  static Vec3 outward(const Transform& x, bool cylinder, double sigma, const Vec3& n) {
    if (!cylinder) return sigma * n;
    const Vec3 axis = x.q * Vec3::UnitZ();
    const Vec3 across = n - n.dot(axis) * axis;
    const double len = across.norm();
    return len > 1e-3 ? Vec3((sigma / len) * across) : Vec3(Vec3::Zero());
  }
  // Replaces the rolling points of a shape g at x (sigma as above) by their core points and
  // returns their mask: a sphere's or capsule's points below a core point, a cylinder's below
  // an axis point, found by going back from each point and checking that it lands on the core.
  static uint8_t toCores(const Geometry& g, const Transform& x, double sigma, const Vec3& n,
                         int count, Vec3* points) {
    const double r = rollingRadius(g);
    if (r == 0.0) return 0;
    const Vec3 out = x.q.conjugate() * outward(x, g.type == ShapeType::Cylinder, sigma, n);
    if (out.isZero(0.0)) return 0;
    const double half = g.type == ShapeType::Sphere ? 0.0 : g.half_height;
    const double tol = 1e-9 + 1e-6 * r;
    uint8_t mask = 0;
    for (int i = 0; i < count; ++i) {
      const Vec3 core = points[i] - r * out;
      // squared, not hypot: its overflow care is a libm call on every stored round manifold
      if (core.x() * core.x() + core.y() * core.y() <= tol * tol &&
          std::abs(core.z()) <= half + tol) {
        points[i] = Vec3(0.0, 0.0, core.z());
        mask |= uint8_t(1u << i);
      }
    }
    return mask;
  }

  // xm^-1 xo, without Transform's normalisation (a root and four divisions for every kept pair
  // every step): unit to rounding, far below what holds' bound resolves.
  Transform relative(const Transform& xa, const Transform& xb) const {
    const Transform& m = b_moves ? xa : xb;
    const Transform& o = b_moves ? xb : xa;
    const Quat mi = m.q.conjugate();
    return {mi * (o.p - m.p), mi * o.q};
  }
};

}  // namespace ragdoll_sim
