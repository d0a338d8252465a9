// GJK and EPA on the Minkowski difference M = A - B of two convex cores.
// GJK: keep a simplex of support points of M, replace it by the sub-simplex nearest the origin
// (Voronoi-region tests, Ericson 5.1), search along -v until the support point no longer gets
// closer; the barycentric weights give the witness points on A and B. A support point w with
// v . w > 0 is a separating plane: once one was seen, a later "origin inside" from a flat
// tetrahedron is round-off, and the last proper simplex is kept instead of running EPA.
// EPA (when the origin is inside M): grow the simplex to a tetrahedron around the origin, then
// repeatedly push out the face nearest the origin through the support point along its normal
// until the support adds nothing; that face gives depth, normal (from A to B) and witnesses.
// All storage is fixed-size: no heap.
#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <limits>

#include "gjk.hpp"

namespace ragdoll_sim {
namespace np {

Vec3 ConvexCore::support(const Vec3& d) const {
  const Vec3 l = x.q.conjugate() * d;
  Vec3 s = Vec3::Zero();
  switch (g->type) {
    case ShapeType::Capsule: s.z() = l.z() >= 0 ? g->half_height : -g->half_height; break;
    case ShapeType::Box:
      for (int i = 0; i < 3; ++i) s[i] = l[i] >= 0 ? g->half_extents[i] : -g->half_extents[i];
      break;
    case ShapeType::Cylinder: {
      // sqrt, not hypot: l is a direction (no overflow), and hypot's care is slow on this hot
      // path.
      const double rho = std::sqrt(l.x() * l.x() + l.y() * l.y());
      if (rho > 1e-12) s.head<2>() = g->radius / rho * l.head<2>();
      s.z() = l.z() >= 0 ? g->half_height : -g->half_height;
      break;
    }
    case ShapeType::ConvexHull: {
      double best = -std::numeric_limits<double>::infinity();
      for (const Vec3& v : g->hull->vertices)
        if (v.dot(l) > best) best = v.dot(l), s = v;
      break;
    }
    case ShapeType::Sphere:
    case ShapeType::Plane: break;
  }
  return x.apply(s);
}

double ConvexCore::radius() const {
  return g->type == ShapeType::Sphere || g->type == ShapeType::Capsule ? g->radius : 0.0;
}

namespace {

struct SV {
  Vec3 w, a, b;  // w = a - b
};

SV supportM(const ConvexCore& A, const ConvexCore& B, const Vec3& d) {
  const Vec3 a = A.support(d), b = B.support(-d);
  return {a - b, a, b};
}

// Keeps the listed vertices of the simplex with the given weights.
void keep(SV* s, int& n, double* lam, std::initializer_list<int> idx,
          std::initializer_list<double> w) {
  SV tmp[4];
  int k = 0;
  for (int i : idx) tmp[k++] = s[i];
  k = 0;
  for (double x : w) lam[k++] = x;
  for (int i = 0; i < k; ++i) s[i] = tmp[i];
  n = k;
}

double safeRatio(double num, double den) { return std::abs(den) > 1e-300 ? num / den : 0.0; }

void solve2(SV* s, int& n, double* lam) {
  const Vec3 ab = s[1].w - s[0].w;
  const double t = safeRatio(-s[0].w.dot(ab), ab.squaredNorm());
  if (t <= 0) return keep(s, n, lam, {0}, {1.0});
  if (t >= 1) return keep(s, n, lam, {1}, {1.0});
  keep(s, n, lam, {0, 1}, {1 - t, t});
}

void solve3(SV* s, int& n, double* lam) {
  const Vec3 &a = s[0].w, &b = s[1].w, &c = s[2].w;
  const Vec3 ab = b - a, ac = c - a;
  const double d1 = -ab.dot(a), d2 = -ac.dot(a);
  if (d1 <= 0 && d2 <= 0) return keep(s, n, lam, {0}, {1.0});
  const double d3 = -ab.dot(b), d4 = -ac.dot(b);
  if (d3 >= 0 && d4 <= d3) return keep(s, n, lam, {1}, {1.0});
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double t = safeRatio(d1, d1 - d3);
    return keep(s, n, lam, {0, 1}, {1 - t, t});
  }
  const double d5 = -ab.dot(c), d6 = -ac.dot(c);
  if (d6 >= 0 && d5 <= d6) return keep(s, n, lam, {2}, {1.0});
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double t = safeRatio(d2, d2 - d6);
    return keep(s, n, lam, {0, 2}, {1 - t, t});
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    const double t = safeRatio(d4 - d3, (d4 - d3) + (d5 - d6));
    return keep(s, n, lam, {1, 2}, {1 - t, t});
  }
  const double den = va + vb + vc;
  if (den <= 1e-300) {  // degenerate (collinear) triangle: the longest edge carries it
    SV e[2] = {s[0], (b - a).squaredNorm() > (c - a).squaredNorm() ? s[1] : s[2]};
    int m = 2;
    solve2(e, m, lam);
    s[0] = e[0], s[1] = e[1], n = m;
    return;
  }
  const double v = vb / den, w = vc / den;
  lam[0] = 1 - v - w, lam[1] = v, lam[2] = w;
}

Vec3 combine(const SV* s, int n, const double* lam, Vec3 SV::*m) {
  Vec3 r = Vec3::Zero();
  for (int i = 0; i < n; ++i) r += lam[i] * (s[i].*m);
  return r;
}

// n == 4 afterwards means the origin is inside the tetrahedron.
void solve4(SV* s, int& n, double* lam) {
  static const int kFaces[4][4] = {{0, 1, 2, 3}, {0, 2, 3, 1}, {0, 3, 1, 2}, {1, 3, 2, 0}};
  double best = std::numeric_limits<double>::infinity();
  SV best_s[3];
  double best_lam[3];
  int best_n = 0;
  for (const auto& f : kFaces) {
    const Vec3& p = s[f[0]].w;
    const Vec3 nrm = (s[f[1]].w - p).cross(s[f[2]].w - p);
    const double so = nrm.dot(s[f[3]].w - p), sp = -nrm.dot(p);
    const bool flat = std::abs(so) <= 1e-12 * nrm.norm() * (s[f[3]].w - p).norm();
    if (!flat && sp * so >= 0) continue;  // origin on the inner side of this face
    SV t[3] = {s[f[0]], s[f[1]], s[f[2]]};
    int m = 3;
    double l[3];
    solve3(t, m, l);
    const double d = combine(t, m, l, &SV::w).squaredNorm();
    if (d < best) {
      best = d, best_n = m;
      for (int i = 0; i < m; ++i) best_s[i] = t[i], best_lam[i] = l[i];
    }
  }
  if (best_n == 0) return;
  n = best_n;
  for (int i = 0; i < n; ++i) s[i] = best_s[i], lam[i] = best_lam[i];
}

Vec3 solve(SV* s, int& n, double* lam) {
  if (n == 1) lam[0] = 1;
  if (n == 2) solve2(s, n, lam);
  if (n == 3) solve3(s, n, lam);
  if (n == 4) solve4(s, n, lam);
  return n == 4 ? Vec3(Vec3::Zero()) : combine(s, n, lam, &SV::w);
}

CoreDistance fallback(const ConvexCore& A, const ConvexCore& B, const SV& s) {
  Vec3 d = B.x.p - A.x.p;
  d = d.squaredNorm() > 1e-24 ? Vec3(d.normalized()) : Vec3(Vec3::UnitZ());
  return {d, 0.0, s.a, s.b};
}

CoreDistance epa(const ConvexCore& A, const ConvexCore& B, SV* s, int n) {
  double scale = 0;
  for (int i = 0; i < n; ++i) scale = std::max(scale, s[i].w.norm());
  const double eps = 1e-10 + 1e-9 * scale;
  // Blow the simplex up to a tetrahedron.
  if (n == 1) {
    for (int k = 0; k < 6 && n == 1; ++k) {
      const SV w = supportM(A, B, (k & 1 ? -1.0 : 1.0) * Vec3::Unit(k / 2));
      if ((w.w - s[0].w).norm() > eps) s[n++] = w;
    }
  }
  if (n == 2) {
    const Vec3 d = (s[1].w - s[0].w).normalized(), e1 = anyPerpendicular(d), e2 = d.cross(e1);
    for (int k = 0; k < 6 && n == 2; ++k) {
      const double ang = k * 3.14159265358979323846 / 3;
      const SV w = supportM(A, B, std::cos(ang) * e1 + std::sin(ang) * e2);
      if ((w.w - s[0].w).cross(d).norm() > eps) s[n++] = w;
    }
  }
  if (n == 3) {
    const Vec3 nrm = (s[1].w - s[0].w).cross(s[2].w - s[0].w).normalized();
    for (int k = 0; k < 2 && n == 3; ++k) {
      const SV w = supportM(A, B, k == 0 ? nrm : Vec3(-nrm));
      if (std::abs(nrm.dot(w.w - s[0].w)) > eps) s[n++] = w;
    }
  }
  if (n < 4) return fallback(A, B, s[0]);

  constexpr int kMaxV = 128, kMaxF = 256;
  struct Face {
    int v[3];
    Vec3 n;
    double d;
  };
  SV vert[kMaxV];
  Face faces[kMaxF];
  int nv = 4, nf = 0;
  for (int i = 0; i < 4; ++i) vert[i] = s[i];
  auto addFace = [&](int i, int j, int k) {
    Vec3 nrm = (vert[j].w - vert[i].w).cross(vert[k].w - vert[i].w);
    const double len = nrm.norm();
    const bool ok = len > 1e-300;
    nrm = ok ? Vec3(nrm / len) : Vec3(Vec3::Zero());
    if (nf < kMaxF) faces[nf++] = {{i, j, k}, nrm, ok ? nrm.dot(vert[i].w) : 1e300};
  };
  const Vec3 centre = 0.25 * (vert[0].w + vert[1].w + vert[2].w + vert[3].w);
  static const int kTet[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  for (const auto& t : kTet) {
    const Vec3 nrm = (vert[t[1]].w - vert[t[0]].w).cross(vert[t[2]].w - vert[t[0]].w);
    if (nrm.dot(vert[t[0]].w - centre) >= 0)
      addFace(t[0], t[1], t[2]);
    else
      addFace(t[0], t[2], t[1]);
  }

  int best = 0;
  for (int iter = 0; iter < 64; ++iter) {
    best = 0;
    for (int f = 1; f < nf; ++f)
      if (faces[f].d < faces[best].d) best = f;
    const Face& fb = faces[best];
    const SV w = supportM(A, B, fb.n);
    if (w.w.dot(fb.n) - fb.d <= eps || nv == kMaxV) break;
    // Remove the faces w sees; the edges used once by them form the horizon.
    int edges[3 * kMaxF][2];
    int ne = 0, kept = 0;
    for (int f = 0; f < nf; ++f) {
      const Face& g = faces[f];
      if (g.n.dot(w.w - vert[g.v[0]].w) <= 1e-14 * (1 + scale)) {
        faces[kept++] = g;
        continue;
      }
      for (int k = 0; k < 3; ++k) {
        const int a = g.v[k], b = g.v[(k + 1) % 3];
        int found = -1;
        for (int e = 0; e < ne && found < 0; ++e)
          if (edges[e][0] == b && edges[e][1] == a) found = e;
        if (found >= 0) {
          edges[found][0] = edges[ne - 1][0], edges[found][1] = edges[ne - 1][1], --ne;
        } else {
          edges[ne][0] = a, edges[ne][1] = b, ++ne;
        }
      }
    }
    nf = kept;
    vert[nv] = w;
    for (int e = 0; e < ne; ++e) addFace(edges[e][0], edges[e][1], nv);
    ++nv;
  }
  best = 0;
  for (int f = 1; f < nf; ++f)
    if (faces[f].d < faces[best].d) best = f;
  const Face& f = faces[best];
  if (f.d > 1e299) return fallback(A, B, s[0]);
  // Barycentric coordinates of the origin's projection d n on the face.
  const SV &a = vert[f.v[0]], &b = vert[f.v[1]], &c = vert[f.v[2]];
  const Vec3 v0 = b.w - a.w, v1 = c.w - a.w, v2 = f.d * f.n - a.w;
  const double d00 = v0.dot(v0), d01 = v0.dot(v1), d11 = v1.dot(v1);
  const double d20 = v2.dot(v0), d21 = v2.dot(v1), den = d00 * d11 - d01 * d01;
  const double lv = safeRatio(d11 * d20 - d01 * d21, den), lw = safeRatio(d00 * d21 - d01 * d20, den);
  const double lu = 1 - lv - lw;
  return {f.n, -f.d, lu * a.a + lv * b.a + lw * c.a, lu * a.b + lv * b.b + lw * c.b};
}

}  // namespace

CoreDistance coreDistance(const ConvexCore& A, const ConvexCore& B, const Vec3* guess,
                          double far) {
  // The point of A - B nearest the origin is its support along the normal (A to B); without a
  // guess, the centres' offset starts on the far side and costs extra iterations.
  Vec3 d = guess ? *guess : Vec3(A.x.p - B.x.p);
  if (d.squaredNorm() < 1e-24) d = Vec3::UnitX();
  SV s[4] = {supportM(A, B, d)};
  int n = 1;
  double lam[4] = {1, 0, 0, 0};
  Vec3 v;
  SV prev_s[4];
  int prev_n = 0;
  double prev_lam[4];
  bool separated = false;
  for (int iter = 0;; ++iter) {
    v = solve(s, n, lam);
    if (n == 4 || v.squaredNorm() < 1e-24) {
      if (!separated || prev_n == 0) return epa(A, B, s, n);
      // Round-off: a plane separated M earlier, so the origin is outside it; near-duplicate
      // points on a curved core made a flat tetrahedron "contain" the origin. Keep the
      // simplex before it.
      n = prev_n;
      for (int i = 0; i < n; ++i) s[i] = prev_s[i], lam[i] = prev_lam[i];
      v = combine(s, n, lam, &SV::w);
      break;
    }
    const SV w = supportM(A, B, -v);
    const double vv = v.squaredNorm(), vw = v.dot(w.w);
    // vw / |v| <= distance <= |v|: vw > 0 proves separation; stop when the bounds agree to
    // 1e-7 m (or relatively to 5e-9), far below the slops (0.5 mm). A curved core converges
    // only linearly, and iterating to round-off piles up near-duplicate points.
    separated |= vw > 0.0;
    if (vw > 0.0 && vw * vw > far * far * vv) {  // the lower bound is beyond `far`
      const double len = std::sqrt(vv);
      return {-v / len, vw / len, combine(s, n, lam, &SV::a), combine(s, n, lam, &SV::b)};
    }
    if (vv - vw <= std::max(5e-9 * vv, 1e-7 * std::sqrt(vv)) || iter == 64) break;
    bool dup = false;
    for (int i = 0; i < n; ++i) dup |= (s[i].w - w.w).squaredNorm() < 1e-24;
    if (dup) break;
    prev_n = n;
    for (int i = 0; i < n; ++i) prev_s[i] = s[i], prev_lam[i] = lam[i];
    s[n++] = w;
  }
  const Vec3 pa = combine(s, n, lam, &SV::a), pb = combine(s, n, lam, &SV::b);
  const double dist = v.norm();
  return {-v / dist, dist, pa, pb};
}

}  // namespace np
}  // namespace ragdoll_sim
