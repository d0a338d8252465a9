// Generic convex pair: GJK/EPA on the cores gives the normal, the separation and the deepest
// (witness) point; a stable multi-point manifold then comes from the two support features
// along that normal. A feature is a face polygon (box/hull face, cylinder cap sampled as a
// 12-gon) when the normal is within ~18 degrees of its face normal, a segment (capsule core,
// box edge, cylinder side line) when the normal is within ~17 degrees of perpendicular to it,
// else a point. The most aligned polygon becomes the reference: the other feature is clipped to
// its prism and measured from its plane, and the normal snaps to its face normal (exact for
// resting flat contact). Two near-parallel segments clip one to the other's slab. The witness
// is added when the features miss the deepest point (curved rims, tilted caps) or give nothing.
#include <algorithm>
#include <cmath>
#include <limits>

#include "gjk.hpp"
#include "np_common.hpp"
#include "np_polytope.hpp"

namespace ragdoll_sim {
namespace np {

namespace {

constexpr double kFaceCos = 0.95;
constexpr double kEdgeSin = 0.3;
constexpr int kRimPoints = 12;
constexpr double kWitnessTol = 1e-5;
constexpr uint32_t kWitnessId = 0xFFFFFFFFu;

struct Feature {
  int n = 0;  // 1 point, 2 segment, >= 3 polygon
  Vec3 p[ClipPoly::kCap];
  uint16_t id[ClipPoly::kCap];
  Vec3 normal = Vec3::UnitZ();  // outward, for a polygon
  int index = 0;                // face / segment index, for contact ids
  void push(const Vec3& x, int i) {
    if (n < ClipPoly::kCap) p[n] = x, id[n++] = uint16_t(i);
  }
};

// Support feature of g (placed at x) along the world unit direction d.
void supportFeature(const Geometry& g, const Transform& x, const Vec3& d, Feature& f) {
  const Vec3 l = x.q.conjugate() * d;
  const double h = g.half_height;
  switch (g.type) {
    case ShapeType::Capsule:
      if (std::abs(l.z()) < kEdgeSin) {
        f.push(x.apply(Vec3(0, 0, -h)), 0);
        f.push(x.apply(Vec3(0, 0, h)), 1);
        return;
      }
      f.push(x.apply(Vec3(0, 0, l.z() > 0 ? h : -h)), l.z() > 0);
      return;
    case ShapeType::Cylinder: {
      if (std::abs(l.z()) >= kFaceCos) {  // cap, counter-clockwise about its outward normal
        const double sz = l.z() > 0 ? 1.0 : -1.0;
        f.index = l.z() > 0 ? 0 : 1;
        f.normal = x.q * Vec3(0, 0, sz);
        for (int k = 0; k < kRimPoints; ++k) {
          const double ang = sz * 2 * 3.14159265358979323846 * k / kRimPoints;
          f.push(x.apply(Vec3(g.radius * std::cos(ang), g.radius * std::sin(ang), sz * h)), k);
        }
        return;
      }
      const double rho = std::sqrt(l.x() * l.x() + l.y() * l.y());  // as in ConvexCore::support
      const Vec3 u(g.radius * l.x() / rho, g.radius * l.y() / rho, 0);
      if (std::abs(l.z()) <= kEdgeSin) {  // side line
        f.index = 2;
        f.push(x.apply(u - Vec3(0, 0, h)), 0);
        f.push(x.apply(u + Vec3(0, 0, h)), 1);
        return;
      }
      f.push(x.apply(u + Vec3(0, 0, l.z() > 0 ? h : -h)), 0);
      return;
    }
    case ShapeType::Box:
    case ShapeType::ConvexHull: {
      const Poly poly(g);
      const int face = poly.bestFace(l);
      if (l.dot(poly.normal(face)) >= kFaceCos) {
        f.index = face;
        f.normal = x.q * poly.normal(face);
        for (int k = 0; k < poly.faceSize(face); ++k)
          f.push(x.apply(poly.vertex(poly.faceVert(face, k))), poly.faceVert(face, k));
        return;
      }
      const int v = poly.support(l);
      int axis;
      l.cwiseAbs().minCoeff(&axis);
      if (!poly.hull && std::abs(l[axis]) < kEdgeSin) {  // box edge along `axis`
        f.index = 6 + axis;
        f.push(x.apply(poly.vertex(v & ~(1 << axis))), v & ~(1 << axis));
        f.push(x.apply(poly.vertex(v | 1 << axis)), v | 1 << axis);
        return;
      }
      f.push(x.apply(poly.vertex(v)), v);
      return;
    }
    case ShapeType::Sphere:
    case ShapeType::Plane: f.push(x.p, 0); return;
  }
}

}  // namespace

void collideConvex(const Geometry& a, const Transform& xa, const Geometry& b,
                   const Transform& xb, double spec, Manifold& out, const Vec3* guess) {
  out.count = 0;
  out.gap = (xb.p - xa.p).norm() - boundingRadius(a) - boundingRadius(b);
  if (out.gap > spec) return;
  const ConvexCore ca{&a, xa}, cb{&b, xb};
  const double ra = ca.radius(), rb = cb.radius();
  // Farther apart than the speculative distance: GJK may stop at its first lower bound beyond.
  const CoreDistance cd = coreDistance(ca, cb, guess, spec + ra + rb);
  const double sep = cd.distance - ra - rb;
  const Vec3 n = cd.normal;
  out.normal = n;
  out.gap = sep;
  if (sep >= spec) return;

  Feature fa, fb;
  supportFeature(a, xa, n, fa);
  supportFeature(b, xb, -n, fb);
  Candidates cs;
  Vec3 normal = n;
  if (fa.n >= 3 || fb.n >= 3) {
    const bool ref_is_b = fb.n >= 3 && (fa.n < 3 || -fb.normal.dot(n) > fa.normal.dot(n));
    const Feature& ref = ref_is_b ? fb : fa;
    const Feature& inc = ref_is_b ? fa : fb;
    const double r_inc = ref_is_b ? ra : rb;
    const Vec3& nr = ref.normal;
    normal = ref_is_b ? Vec3(-nr) : nr;
    ClipPoly poly;
    for (int k = 0; k < inc.n; ++k) poly.push(inc.p[k], inc.id[k], uint8_t(k));
    clipToPrism(poly, ref.p, ref.n, nr);
    for (int k = 0; k < poly.n; ++k) {
      const Vec3 q = poly.v[k].p - r_inc * nr;  // on the incident surface
      const double s = nr.dot(q - ref.p[0]);
      cs.add(ref_is_b ? Vec3(q - s * nr) : q, normal, s,
             contactId(ref.index, inc.index, ref_is_b, poly.v[k].id));
    }
  } else if (fa.n == 2 && fb.n == 2) {
    parallelSegments(fa.p[0], fa.p[1] - fa.p[0], ra, fb.p[0], fb.p[1] - fb.p[0], rb, n, cs);
  }
  double deepest = std::numeric_limits<double>::infinity();
  for (int k = 0; k < cs.n; ++k) deepest = std::min(deepest, cs.c[k].separation);
  if (cs.n == 0 || sep < deepest - kWitnessTol) cs.add(cd.pb - rb * n, n, sep, kWitnessId);
  reduce(normal, cs, spec, out);
}

}  // namespace np
}  // namespace ragdoll_sim
