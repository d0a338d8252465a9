// Narrowphase entry point and the analytic pairs.
// Pairs are dispatched in a canonical type order (plane < sphere < capsule < box < cylinder <
// hull); the swapped order only negates the normal. Planes test the other shape's extreme
// points (box and hull vertices, capsule ends, cylinder rim samples plus the exact deepest
// rim point). Spheres and capsules are segment cores plus a radius, so their pairs reduce to
// segment closest points; near-parallel capsules clip one core to the other's slab for two
// points. Sphere–box and sphere–cylinder use the closest point on the solid (with the
// shallowest face when the centre is inside). Everything else is in np_polytope.cpp (SAT) and
// np_convex.cpp (GJK/EPA + feature clipping).
#include <cmath>

#include "np_common.hpp"

namespace ragdoll_sim {

using np::Candidates;

namespace {

void planeVsShape(const Geometry& a, const Transform& xa, const Geometry& b,
                  const Transform& xb, double spec, Manifold& out) {
  const Vec3 n = xa.q * a.normal;
  const double off = a.offset + n.dot(xa.p);
  Candidates cs;
  // x is a point of B's core, r the core's radius.
  auto add = [&](const Vec3& x, double r, uint32_t id) {
    cs.add(x - r * n, n, n.dot(x) - off - r, id);
  };
  switch (b.type) {
    case ShapeType::Sphere: add(xb.p, b.radius, 0); break;
    case ShapeType::Capsule: {
      const Vec3 w = xb.q * Vec3(0, 0, b.half_height);
      add(xb.p + w, b.radius, 0);
      add(xb.p - w, b.radius, 1);
      break;
    }
    case ShapeType::Box:
      for (int i = 0; i < 8; ++i) {
        const Vec3& h = b.half_extents;
        add(xb.apply(Vec3(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(), i & 4 ? h.z() : -h.z())),
            0, i);
      }
      break;
    case ShapeType::Cylinder: {
      // Per cap: 4 fixed rim points (a stable support when standing) and the deepest rim point.
      const Vec3 nl = xb.q.conjugate() * n;
      Eigen::Vector2d u(-nl.x(), -nl.y());
      const bool tilted = u.norm() > 1e-9;
      if (tilted) u.normalize();
      const Eigen::Vector2d dirs[4] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
      for (int k = 0; k < 2; ++k) {
        const double z = k == 0 ? b.half_height : -b.half_height;
        for (int j = 0; j < 4; ++j)
          if (!tilted || dirs[j].dot(u) < 1.0 - 1e-9)
            add(xb.apply(Vec3(b.radius * dirs[j].x(), b.radius * dirs[j].y(), z)), 0, k * 8 + j);
        if (tilted) add(xb.apply(Vec3(b.radius * u.x(), b.radius * u.y(), z)), 0, k * 8 + 4);
      }
      break;
    }
    case ShapeType::ConvexHull:
      for (size_t i = 0; i < b.hull->vertices.size(); ++i) add(xb.apply(b.hull->vertices[i]), 0, i);
      break;
    case ShapeType::Plane: break;
  }
  np::reduce(n, cs, spec, out);
}

// Capsule-like cores: segments pa + s da (radius ra) and pb + t db (radius rb).
void segmentPair(const Vec3& pa, const Vec3& da, double ra, const Vec3& pb, const Vec3& db,
                 double rb, double spec, Manifold& out) {
  double s, t;
  np::closestSegmentParams(pa, da, pb, db, s, t);
  const Vec3 ca = pa + s * da, cb = pb + t * db;
  const Vec3 centre_dir = (pb + 0.5 * db) - (pa + 0.5 * da);
  Vec3 n = cb - ca;
  const double dist = n.norm();
  if (dist > 1e-12) {
    n /= dist;
  } else {  // cores touch: normal of the plane through both axes, else across one axis
    const Vec3 axis = da.squaredNorm() > 1e-24 ? da : db;
    n = da.cross(db);
    if (n.squaredNorm() < 1e-24 && axis.squaredNorm() > 1e-24)
      n = centre_dir - centre_dir.dot(axis) / axis.squaredNorm() * axis;
    if (n.squaredNorm() < 1e-24)
      n = axis.squaredNorm() > 1e-24 ? anyPerpendicular(axis.normalized()) : Vec3(Vec3::UnitZ());
    n.normalize();
    if (n.dot(centre_dir) < 0) n = -n;
  }
  const double sep = dist - ra - rb;
  out.count = 0;
  out.normal = n;
  out.gap = sep;
  if (sep >= spec) return;

  Candidates cs;
  np::parallelSegments(pa, da, ra, pb, db, rb, n, cs);
  if (cs.n == 0) cs.add(cb - rb * n, n, sep, 0);
  np::reduce(n, cs, spec, out);
}

// Core of shape g (sphere or capsule) as a world segment p + s d.
void coreSegment(const Geometry& g, const Transform& x, Vec3& p, Vec3& d) {
  if (g.type == ShapeType::Capsule) {
    const Vec3 w = x.q * Vec3(0, 0, g.half_height);
    p = x.p - w;
    d = 2 * w;
  } else {
    p = x.p;
    d.setZero();
  }
}

void roundPair(const Geometry& a, const Transform& xa, const Geometry& b, const Transform& xb,
               double spec, Manifold& out) {
  Vec3 pa, da, pb, db;
  coreSegment(a, xa, pa, da);
  coreSegment(b, xb, pb, db);
  segmentPair(pa, da, a.radius, pb, db, b.radius, spec, out);
}

// Sphere a against a solid whose closest surface point q (local) and outward normal nl at q
// are given, with `inside` when the centre c (local) is in the solid.
void sphereVsClosest(const Geometry& a, const Transform& xb, const Vec3& c, const Vec3& q,
                     Vec3 nl, bool inside, double spec, Manifold& out) {
  double dist = (c - q).norm();
  if (!inside && dist > 1e-12) nl = (c - q) / dist;
  if (inside) dist = -dist;
  const Vec3 n = -(xb.q * nl);  // sphere -> solid
  const double sep = dist - a.radius;
  out.count = 0;
  out.normal = n;
  out.gap = sep;
  if (sep >= spec) return;
  Candidates cs;
  cs.add(xb.apply(q), n, sep, 0);
  np::reduce(n, cs, spec, out);
}

void sphereBox(const Geometry& a, const Transform& xa, const Geometry& b, const Transform& xb,
               double spec, Manifold& out) {
  const Vec3 c = xb.applyInverse(xa.p);
  const Vec3& h = b.half_extents;
  Vec3 q = c.cwiseMax(-h).cwiseMin(h);
  Vec3 nl = Vec3::UnitZ();
  const bool inside = q == c;
  if (inside) {  // push out through the nearest face
    int axis;
    (h - c.cwiseAbs()).minCoeff(&axis);
    const double sign = c[axis] < 0 ? -1.0 : 1.0;
    q[axis] = sign * h[axis];
    nl = sign * Vec3::Unit(axis);
  }
  sphereVsClosest(a, xb, c, q, nl, inside, spec, out);
}

void sphereCylinder(const Geometry& a, const Transform& xa, const Geometry& b,
                    const Transform& xb, double spec, Manifold& out) {
  const Vec3 c = xb.applyInverse(xa.p);
  const double r = b.radius, h = b.half_height;
  const double rho = std::hypot(c.x(), c.y());
  const Vec3 radial = rho > 1e-12 ? Vec3(c.x() / rho, c.y() / rho, 0) : Vec3(Vec3::UnitX());
  const bool inside = rho <= r && std::abs(c.z()) <= h;
  Vec3 q, nl = Vec3::UnitZ();
  if (!inside) {
    q = Vec3(0, 0, std::min(h, std::max(-h, c.z()))) + std::min(rho, r) * radial;
  } else if (h - std::abs(c.z()) < r - rho) {
    nl = c.z() < 0 ? Vec3(-Vec3::UnitZ()) : Vec3(Vec3::UnitZ());
    q = Vec3(c.x(), c.y(), nl.z() * h);
  } else {
    nl = radial;
    q = Vec3(0, 0, c.z()) + r * radial;
  }
  sphereVsClosest(a, xb, c, q, nl, inside, spec, out);
}

int rank(ShapeType t) {
  switch (t) {
    case ShapeType::Plane: return 0;
    case ShapeType::Sphere: return 1;
    case ShapeType::Capsule: return 2;
    case ShapeType::Box: return 3;
    case ShapeType::Cylinder: return 4;
    case ShapeType::ConvexHull: return 5;
  }
  return 0;
}

bool isRound(ShapeType t) { return t == ShapeType::Sphere || t == ShapeType::Capsule; }
bool isPolytope(ShapeType t) { return t == ShapeType::Box || t == ShapeType::ConvexHull; }

// a comes first in the canonical order.
void collideOrdered(const Geometry& a, const Transform& xa, const Geometry& b,
                    const Transform& xb, double spec, Manifold& out, const Vec3* guess) {
  if (a.type == ShapeType::Plane) {
    if (b.type != ShapeType::Plane) planeVsShape(a, xa, b, xb, spec, out);
  } else if (isRound(a.type) && isRound(b.type)) {
    roundPair(a, xa, b, xb, spec, out);
  } else if (a.type == ShapeType::Sphere && b.type == ShapeType::Box) {
    sphereBox(a, xa, b, xb, spec, out);
  } else if (a.type == ShapeType::Sphere && b.type == ShapeType::Cylinder) {
    sphereCylinder(a, xa, b, xb, spec, out);
  } else if (a.type == ShapeType::Box && b.type == ShapeType::Box) {
    np::collideBoxBox(a, xa, b, xb, spec, out);
  } else if (isPolytope(a.type) && isPolytope(b.type)) {
    np::collidePolytopes(a, xa, b, xb, spec, out);
  } else {
    np::collideConvex(a, xa, b, xb, spec, out, guess);
  }
}

}  // namespace

void collide(const Geometry& a, const Transform& xa, const Geometry& b, const Transform& xb,
             double speculative_distance, Manifold& out, const Vec3* normal_guess) {
  out.count = 0;
  out.gap = 0.0;
  if ((a.type == ShapeType::ConvexHull && !a.hull) || (b.type == ShapeType::ConvexHull && !b.hull))
    return;
  if (rank(a.type) <= rank(b.type)) {
    collideOrdered(a, xa, b, xb, speculative_distance, out, normal_guess);
  } else {
    const Vec3 flipped = normal_guess ? Vec3(-*normal_guess) : Vec3::Zero();
    collideOrdered(b, xb, a, xa, speculative_distance, out, normal_guess ? &flipped : nullptr);
    out.normal = -out.normal;
  }
}

}  // namespace ragdoll_sim
