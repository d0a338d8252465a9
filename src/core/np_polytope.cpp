// Polytope pairs (box and hull) by the separating-axis test, then contact generation.
// Candidate axes are the face normals of both shapes and the cross products of edge pairs.
// Box–box uses the classic 15 axes (3 + 3 face normals, 9 edge crosses). For hulls, an edge
// pair is tested only when its arcs cross on the Gauss map, i.e. it builds a face of the
// Minkowski difference (Gregorius, "The Separating Axis Test between Convex Polyhedra", GDC
// 2013); its axis is then oriented away from A's centroid. The least separated axis decides:
// a face axis clips the most anti-parallel (incident) face of the other shape against the side
// planes of the reference face (4 points face–face, 2 edge–face); an edge axis gives the closest
// points of the two edges (1 point). Faces are preferred by a small margin so the reference
// does not flicker in resting contact.
#include <algorithm>
#include <cmath>
#include <limits>

#include "np_common.hpp"
#include "np_polytope.hpp"

namespace ragdoll_sim {
namespace np {

constexpr int Poly::kBoxFaces[6][4];

namespace {

constexpr double kFaceBias = 5e-4;  // B's face must beat A's by this to be the reference
constexpr double kEdgeBias = 1e-3;  // an edge axis must beat both faces by this

struct Query {
  double sep = -std::numeric_limits<double>::infinity();
  int ia = 0, ib = 0;  // face of the queried shape, or the two edges of an edge query
  Vec3 axis = Vec3::UnitZ();
};

// `rf` of `ref` (at xr) is the reference face, the incident face of `inc` (at xi) is clipped.
void faceContact(const Poly& ref, const Transform& xr, const Poly& inc, const Transform& xi,
                 int rf, bool ref_is_b, double spec, Manifold& out) {
  const Transform rel = xr.inverse() * xi;
  const Vec3 n = ref.normal(rf);
  const int incf = inc.bestFace(-(rel.q.conjugate() * n));
  ClipPoly poly;
  for (int k = 0; k < inc.faceSize(incf); ++k) {
    const int v = inc.faceVert(incf, k);
    poly.push(rel.apply(inc.vertex(v)), uint16_t(v), uint8_t(k));
  }
  Vec3 rv[ClipPoly::kCap];
  const int m = std::min(ref.faceSize(rf), int(ClipPoly::kCap));
  for (int k = 0; k < m; ++k) rv[k] = ref.vertex(ref.faceVert(rf, k));
  clipToPrism(poly, rv, m, n);
  if (poly.n == 0) {  // incident face entirely off the reference face: keep its deepest vertex
    const int v = inc.support(rel.q.conjugate() * -n);
    poly.push(rel.apply(inc.vertex(v)), uint16_t(v), 0);
  }

  const Vec3 nw = xr.q * n;
  const Vec3 normal = ref_is_b ? Vec3(-nw) : nw;
  Candidates cs;
  for (int k = 0; k < poly.n; ++k) {
    const double sep = n.dot(poly.v[k].p) - ref.offset(rf);
    const Vec3 p = xr.apply(poly.v[k].p);
    cs.add(ref_is_b ? Vec3(p - sep * nw) : p, normal, sep, contactId(rf, incf, ref_is_b, poly.v[k].id));
  }
  reduce(normal, cs, spec, out);
}

// Closest points of edge ea of a and edge eb of b; axis (a's frame) points from a to b.
void edgeContact(const Poly& a, const Transform& xa, const Poly& b, const Transform& xb, int ea,
                 int eb, const Vec3& axis, double spec, Manifold& out) {
  const Transform rel = xa.inverse() * xb;
  int a0, a1, b0, b1, f0, f1;
  a.edge(ea, a0, a1, f0, f1);
  b.edge(eb, b0, b1, f0, f1);
  const Vec3 p1 = a.vertex(a0), d1 = a.vertex(a1) - p1;
  const Vec3 p2 = rel.apply(b.vertex(b0)), d2 = rel.apply(b.vertex(b1)) - p2;
  double s, t;
  closestSegmentParams(p1, d1, p2, d2, s, t);
  const Vec3 c1 = p1 + s * d1, c2 = p2 + t * d2;
  const Vec3 normal = xa.q * axis;
  Candidates cs;
  cs.add(xa.apply(c2), normal, (c2 - c1).dot(axis), 0x40000000u | uint32_t(ea) << 12 | uint32_t(eb));
  reduce(normal, cs, spec, out);
}

void finish(const Poly& pa, const Transform& xa, const Poly& pb, const Transform& xb,
            const Query& fa, const Query& fb, const Query& edge, double spec, Manifold& out) {
  if (edge.sep > std::max(fa.sep, fb.sep) + kEdgeBias)
    edgeContact(pa, xa, pb, xb, edge.ia, edge.ib, edge.axis, spec, out);
  else if (fb.sep > fa.sep + kFaceBias)
    faceContact(pb, xb, pa, xa, fb.ia, true, spec, out);
  else
    faceContact(pa, xa, pb, xb, fa.ia, false, spec, out);
}

// Most separating face of p against q; rel places q in p's frame.
Query faceQuery(const Poly& p, const Poly& q, const Transform& rel) {
  Query best;
  for (int f = 0; f < p.numFaces(); ++f) {
    const Vec3 n = p.normal(f);
    const double s = n.dot(rel.apply(q.vertex(q.support(rel.q.conjugate() * -n)))) - p.offset(f);
    if (s > best.sep) best.sep = s, best.ia = f;
  }
  return best;
}

bool isMinkowskiFace(const Vec3& a, const Vec3& b, const Vec3& bxa, const Vec3& c,
                     const Vec3& d, const Vec3& dxc) {
  const double cba = c.dot(bxa), dba = d.dot(bxa), adc = a.dot(dxc), bdc = b.dot(dxc);
  return cba * dba < 0 && adc * bdc < 0 && cba * bdc > 0;
}

}  // namespace

void collideBoxBox(const Geometry& a, const Transform& xa, const Geometry& b,
                   const Transform& xb, double spec, Manifold& out) {
  out.count = 0;
  const Transform rel = xa.inverse() * xb;
  const Mat3 r = rel.q.toRotationMatrix();
  const Mat3 abs_r = r.cwiseAbs().array() + 1e-12;
  const Vec3& t = rel.p;
  const Vec3 &ha = a.half_extents, &hb = b.half_extents;
  Query fa, fb, edge;
  for (int i = 0; i < 3; ++i) {
    const double s = std::abs(t[i]) - ha[i] - abs_r.row(i).dot(hb);
    if (s > fa.sep) fa.sep = s, fa.ia = 2 * i + (t[i] < 0 ? 1 : 0);
    const double tb = t.dot(r.col(i));
    const double sb = std::abs(tb) - abs_r.col(i).dot(ha) - hb[i];
    if (sb > fb.sep) fb.sep = sb, fb.ia = 2 * i + (tb > 0 ? 1 : 0);
  }
  out.gap = std::max(fa.sep, fb.sep);
  if (out.gap > spec) return;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      Vec3 l = Vec3::Unit(i).cross(r.col(j));
      const double len = l.norm();
      if (len < 1e-6) continue;
      l /= len;
      if (l.dot(t) < 0) l = -l;
      const Vec3 lb = r.transpose() * l;
      const double s = l.dot(t) - l.cwiseAbs().dot(ha) - lb.cwiseAbs().dot(hb);
      if (s > spec) {
        out.gap = s;
        return;
      }
      if (s > edge.sep) {
        const int ja = (i + 1) % 3, ka = (i + 2) % 3, jb = (j + 1) % 3, kb = (j + 2) % 3;
        edge.sep = s;
        edge.axis = l;
        edge.ia = 4 * i + (l[ja] > 0 ? 1 : 0) + (l[ka] > 0 ? 2 : 0);
        edge.ib = 4 * j + (lb[jb] < 0 ? 1 : 0) + (lb[kb] < 0 ? 2 : 0);
      }
    }
  finish(Poly(a), xa, Poly(b), xb, fa, fb, edge, spec, out);
}

void collidePolytopes(const Geometry& a, const Transform& xa, const Geometry& b,
                      const Transform& xb, double spec, Manifold& out) {
  out.count = 0;
  const Poly pa(a), pb(b);
  const Transform rel = xa.inverse() * xb;
  const Query fa = faceQuery(pa, pb, rel);
  out.gap = fa.sep;
  if (fa.sep > spec) return;
  const Query fb = faceQuery(pb, pa, rel.inverse());
  out.gap = fb.sep;
  if (fb.sep > spec) return;

  Query edge;
  const Vec3 ca = pa.centroid();
  for (int eb = 0; eb < pb.numEdges(); ++eb) {
    int b0, b1, g0, g1;
    pb.edge(eb, b0, b1, g0, g1);
    const Vec3 p2 = rel.apply(pb.vertex(b0)), e2 = rel.apply(pb.vertex(b1)) - p2;
    const Vec3 c = -(rel.q * pb.normal(g0)), d = -(rel.q * pb.normal(g1));
    const Vec3 dxc = d.cross(c);
    for (int ea = 0; ea < pa.numEdges(); ++ea) {
      int a0, a1, f0, f1;
      pa.edge(ea, a0, a1, f0, f1);
      const Vec3 na = pa.normal(f0), nb = pa.normal(f1);
      if (!isMinkowskiFace(na, nb, nb.cross(na), c, d, dxc)) continue;
      const Vec3 p1 = pa.vertex(a0), e1 = pa.vertex(a1) - p1;
      Vec3 l = e1.cross(e2);
      const double len = l.norm();
      if (len < 1e-6 * e1.norm() * e2.norm()) continue;
      l /= len;
      if (l.dot(p1 - ca) < 0) l = -l;
      const double s = l.dot(p2 - p1);
      if (s > spec) {
        out.gap = s;
        return;
      }
      if (s > edge.sep) edge.sep = s, edge.ia = ea, edge.ib = eb, edge.axis = l;
    }
  }
  finish(pa, xa, pb, xb, fa, fb, edge, spec, out);
}

}  // namespace np
}  // namespace ragdoll_sim
