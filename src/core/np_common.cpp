// Shared narrowphase helpers.
// reduce(): keep the deepest point (it carries the most penetration), then the point farthest
// from it, then the one giving the largest triangle, then the one adding the most area outside
// that triangle — the support polygon a resting body needs (as in Bullet's manifold reduction).
// Distance and areas are weighted by depth, w = speculative - separation (Jolt weighs its
// pruning by penetration too): unweighted, a cylinder lying on the ground can keep a raised rim
// sample and drop the bottom of its other cap, so the caps take turns sinking and the body
// rocks instead of sleeping.
// closestSegmentParams(): Ericson, Real-Time Collision Detection 5.1.9.
// clipToPrism(): Sutherland–Hodgman against the side planes (edge x normal) of the reference
// polygon; a segment is clipped parametrically so it never duplicates its cut points.
#include <algorithm>
#include <cmath>

#include "np_common.hpp"

namespace ragdoll_sim {
namespace np {

void reduce(const Vec3& normal, const Candidates& cs, double speculative, Manifold& out) {
  out.normal = normal;
  out.count = 0;
  int idx[Candidates::kCap];
  int k = 0;
  for (int i = 0; i < cs.n; ++i)
    if (cs.c[i].separation < speculative) idx[k++] = i;
  auto emit = [&](int i) {
    const Candidate& c = cs.c[i];
    out.points[out.count++] = {c.point, c.separation, c.id};
  };
  if (k <= Manifold::kMaxPoints) {
    for (int i = 0; i < k; ++i) emit(idx[i]);
    return;
  }
  // Work in the contact plane: 2D coordinates along two tangents.
  const Vec3 t1 = anyPerpendicular(normal), t2 = normal.cross(t1);
  Eigen::Vector2d p[Candidates::kCap];
  for (int i = 0; i < k; ++i) p[i] = {t1.dot(cs.c[idx[i]].point), t2.dot(cs.c[idx[i]].point)};
  auto area = [&](int a, int b, int c) {
    const Eigen::Vector2d u = p[b] - p[a], v = p[c] - p[a];
    return u.x() * v.y() - u.y() * v.x();
  };
  int i0 = 0;
  for (int i = 1; i < k; ++i)
    if (cs.c[idx[i]].separation < cs.c[idx[i0]].separation) i0 = i;
  double w[Candidates::kCap];  // > 0: every kept candidate lies below `speculative`
  for (int i = 0; i < k; ++i) w[i] = speculative - cs.c[idx[i]].separation;
  int i1 = -1;
  double best = -1;
  for (int i = 0; i < k; ++i) {
    const double d = (p[i] - p[i0]).norm() * w[i];
    if (i != i0 && d > best) best = d, i1 = i;
  }
  int i2 = -1;
  best = -1;
  for (int i = 0; i < k; ++i) {
    const double s = std::abs(area(i0, i1, i)) * w[i];
    if (i != i0 && i != i1 && s > best) best = s, i2 = i;
  }
  if (area(i0, i1, i2) < 0) std::swap(i1, i2);
  int i3 = -1;
  best = 0;
  const int tri[3] = {i0, i1, i2};
  for (int i = 0; i < k; ++i)
    for (int e = 0; e < 3; ++e) {
      const double outside = -area(tri[e], tri[(e + 1) % 3], i) * w[i];
      if (outside > best) best = outside, i3 = i;
    }
  emit(idx[i0]);
  emit(idx[i1]);
  emit(idx[i2]);
  if (i3 >= 0) emit(idx[i3]);
}

void closestSegmentParams(const Vec3& p1, const Vec3& d1, const Vec3& p2, const Vec3& d2,
                          double& s, double& t) {
  const double eps = 1e-24;
  const Vec3 r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  auto clamp01 = [](double x) { return std::min(1.0, std::max(0.0, x)); };
  if (a <= eps && e <= eps) {
    s = t = 0;
    return;
  }
  if (a <= eps) {
    s = 0;
    t = clamp01(f / e);
    return;
  }
  const double c = d1.dot(r);
  if (e <= eps) {
    t = 0;
    s = clamp01(-c / a);
    return;
  }
  const double b = d1.dot(d2), denom = a * e - b * b;
  s = denom > 1e-12 * a * e ? clamp01((b * f - c * e) / denom) : 0.0;
  t = (b * s + f) / e;
  if (t < 0) {
    t = 0;
    s = clamp01(-c / a);
  } else if (t > 1) {
    t = 1;
    s = clamp01((b - c) / a);
  }
}

void parallelSegments(const Vec3& pa, const Vec3& da, double ra, const Vec3& pb, const Vec3& db,
                      double rb, const Vec3& n, Candidates& cs) {
  const double la2 = da.squaredNorm(), lb2 = db.squaredNorm();
  if (la2 < 1e-24 || lb2 < 1e-24 || da.cross(db).squaredNorm() > 1e-4 * la2 * lb2) return;
  // Parameters on B where its projection crosses A's ends.
  const double t0 = (pa - pb).dot(da) / db.dot(da), t1 = (pa + da - pb).dot(da) / db.dot(da);
  double lo = 0, hi = 1;
  uint32_t id_lo = 1, id_hi = 2;  // B's own ends 1, 2; cut at A's ends 3, 4
  if (std::min(t0, t1) > lo) lo = std::min(t0, t1), id_lo = t0 < t1 ? 3 : 4;
  if (std::max(t0, t1) < hi) hi = std::max(t0, t1), id_hi = t0 < t1 ? 4 : 3;
  if (hi <= lo + 1e-9) return;
  for (int k = 0; k < 2; ++k) {
    const Vec3 q = pb + (k == 0 ? lo : hi) * db;
    const double s = std::min(1.0, std::max(0.0, (q - pa).dot(da) / la2));
    cs.add(q - rb * n, n, (q - (pa + s * da)).dot(n) - ra - rb, k == 0 ? id_lo : id_hi);
  }
}

namespace {

void clipSegment(ClipPoly& seg, const Vec3* ref, int m, const Vec3& n) {
  const Vec3 p0 = seg.v[0].p, p1 = seg.v[1].p;
  double t0 = 0, t1 = 1;
  uint16_t id0 = seg.v[0].id, id1 = seg.v[1].id;
  for (int j = 0; j < m; ++j) {
    const Vec3 side = (ref[(j + 1) % m] - ref[j]).cross(n);
    const double d0 = side.dot(p0 - ref[j]), d1 = side.dot(p1 - ref[j]);
    if (d0 > 0 && d1 > 0) {
      seg.n = 0;
      return;
    }
    if (d0 > 0 && d0 / (d0 - d1) > t0) t0 = d0 / (d0 - d1), id0 = uint16_t(0x8000 | j);
    if (d1 > 0 && d0 / (d0 - d1) < t1) t1 = d0 / (d0 - d1), id1 = uint16_t(0x8100 | j);
  }
  seg.n = 0;
  if (t0 > t1) return;
  seg.push(p0 + t0 * (p1 - p0), id0, 0);
  if (t1 > t0) seg.push(p0 + t1 * (p1 - p0), id1, 0);
}

}  // namespace

void clipToPrism(ClipPoly& poly, const Vec3* ref, int m, const Vec3& n) {
  if (poly.n == 2) return clipSegment(poly, ref, m, n);
  ClipPoly tmp;
  ClipPoly* in = &poly;
  ClipPoly* out = &tmp;
  for (int j = 0; j < m && in->n > 0; ++j) {
    const Vec3 side = (ref[(j + 1) % m] - ref[j]).cross(n);
    out->n = 0;
    for (int k = 0; k < in->n; ++k) {
      const ClipPoly::Vert& a = in->v[k];
      const ClipPoly::Vert& b = in->v[(k + 1) % in->n];
      const double da = side.dot(a.p - ref[j]), db = side.dot(b.p - ref[j]);
      if (da <= 0) out->push(a.p, a.id, a.label);
      if ((da <= 0) != (db <= 0)) {
        const uint16_t id = uint16_t(0x8000 | a.label << 7 | (j & 0x7F));
        out->push(a.p + da / (da - db) * (b.p - a.p), id, da <= 0 ? uint8_t(0x80 | j) : a.label);
      }
    }
    std::swap(in, out);
  }
  if (in != &poly) poly = *in;
}

}  // namespace np
}  // namespace ragdoll_sim
