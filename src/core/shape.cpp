// Shape factories, mass properties and world bounding boxes.
// Mass properties are closed forms; a capsule is a cylinder plus two hemispheres moved by the
// parallel-axis theorem (hemisphere centroid 3r/8 from its flat face); a hull sums signed
// tetrahedra (origin, face-fan triangle), whose second moment is V/20 (sum v v^T + s s^T).
#include <cmath>
#include <limits>

#include "narrowphase.hpp"
#include "ragdoll_sim/range_check.hpp"
#include "ragdoll_sim/shape.hpp"

namespace ragdoll_sim {

const char* shapeTypeName(ShapeType t) {
  switch (t) {
    case ShapeType::Sphere: return "sphere";
    case ShapeType::Capsule: return "capsule";
    case ShapeType::Box: return "box";
    case ShapeType::Cylinder: return "cylinder";
    case ShapeType::ConvexHull: return "convex_hull";
    case ShapeType::Plane: return "plane";
  }
  return "unknown";
}

Geometry Geometry::sphere(double r) {
  Geometry g;
  g.type = ShapeType::Sphere;
  g.radius = r;
  return g;
}

Geometry Geometry::capsule(double r, double half_height) {
  Geometry g;
  g.type = ShapeType::Capsule;
  g.radius = r;
  g.half_height = half_height;
  return g;
}

Geometry Geometry::box(const Vec3& half_extents) {
  Geometry g;
  g.type = ShapeType::Box;
  g.half_extents = half_extents;
  return g;
}

Geometry Geometry::cylinder(double r, double half_height) {
  Geometry g;
  g.type = ShapeType::Cylinder;
  g.radius = r;
  g.half_height = half_height;
  return g;
}

Geometry Geometry::plane(const Vec3& n, double offset) {
  Geometry g;
  g.type = ShapeType::Plane;
  const double len = n.norm();
  g.normal = len > 0 ? Vec3(n / len) : Vec3::UnitZ();
  g.offset = len > 0 ? offset / len : offset;
  return g;
}

Geometry Geometry::convexHull(const std::vector<Vec3>& points) {
  Geometry g;
  g.type = ShapeType::ConvexHull;
  g.hull = HullData::build(points);
  return g;
}

std::string geometryError(const Geometry& g) {
  const std::string type = shapeTypeName(g.type);
  std::string e;
  switch (g.type) {
    case ShapeType::Sphere: e = lengthError(type + " radius", g.radius, true); break;
    case ShapeType::Capsule:
      if ((e = lengthError(type + " radius", g.radius)).empty())
        e = lengthError(type + " half_height", g.half_height, true);
      break;
    case ShapeType::Cylinder:
      if ((e = lengthError(type + " radius", g.radius)).empty())
        e = lengthError(type + " half_height", g.half_height);
      break;
    case ShapeType::Box:
      for (int i = 0; i < 3 && e.empty(); ++i)
        e = lengthError(type + " half_extents." + "xyz"[i], g.half_extents[i]);
      break;
    case ShapeType::Plane:
      if (!g.normal.allFinite() || std::abs(g.normal.norm() - 1.0) > 1e-9)
        e = "plane normal must be a finite unit vector";
      else
        e = rangeError("plane offset", g.offset, -kWorldRange, kWorldRange);
      break;
    case ShapeType::ConvexHull:
      if (!g.hull)
        e = "convex_hull has no hull (its points were degenerate: fewer than 4 not in a plane)";
      else
        for (const Vec3& v : g.hull->vertices)
          if (!(e = worldPointError("convex_hull vertices", v)).empty()) break;
      break;
  }
  return e;
}

namespace {

constexpr double kPi = 3.14159265358979323846;

// Sum over the hull's fan triangles of f(a, b, c) for the tetrahedron (origin, a, b, c).
template <class F>
void forEachTetra(const HullData& h, F&& f) {
  for (const auto& face : h.faces) {
    const Vec3& a = h.vertices[face.verts[0]];
    for (size_t k = 1; k + 1 < face.verts.size(); ++k)
      f(a, h.vertices[face.verts[k]], h.vertices[face.verts[k + 1]]);
  }
}

}  // namespace

double Geometry::volume() const {
  switch (type) {
    case ShapeType::Sphere: return 4.0 / 3.0 * kPi * radius * radius * radius;
    case ShapeType::Capsule:
      return kPi * radius * radius * (2.0 * half_height + 4.0 / 3.0 * radius);
    case ShapeType::Box: return 8.0 * half_extents.prod();
    case ShapeType::Cylinder: return 2.0 * kPi * radius * radius * half_height;
    case ShapeType::ConvexHull: {
      if (!hull) return 0.0;
      double v = 0.0;
      forEachTetra(*hull, [&](const Vec3& a, const Vec3& b, const Vec3& c) {
        v += a.dot(b.cross(c)) / 6.0;
      });
      return v;
    }
    case ShapeType::Plane: return 0.0;
  }
  return 0.0;
}

Mat3 Geometry::unitInertia() const {
  const double r2 = radius * radius;
  const double m = volume();
  switch (type) {
    case ShapeType::Sphere: return Mat3::Identity() * (0.4 * m * r2);
    case ShapeType::Box: {
      const Vec3 s = (2.0 * half_extents).cwiseAbs2();
      return (m / 12.0 * Vec3(s.y() + s.z(), s.x() + s.z(), s.x() + s.y())).asDiagonal();
    }
    case ShapeType::Cylinder: {
      const double len = 2.0 * half_height;
      const double ixx = m * (3.0 * r2 + len * len) / 12.0;
      return Vec3(ixx, ixx, 0.5 * m * r2).asDiagonal();
    }
    case ShapeType::Capsule: {
      const double h = half_height, len = 2.0 * h;
      const double mc = kPi * r2 * len;                  // cylinder
      const double ms = 4.0 / 3.0 * kPi * r2 * radius;   // both hemispheres
      const double ixx = mc * (3.0 * r2 + len * len) / 12.0 +
                         ms * (0.4 * r2 + h * h + 0.75 * h * radius);
      const double izz = 0.5 * mc * r2 + 0.4 * ms * r2;
      return Vec3(ixx, ixx, izz).asDiagonal();
    }
    case ShapeType::ConvexHull: {
      Mat3 c = Mat3::Zero();  // second moment: integral of x x^T
      if (hull)
        forEachTetra(*hull, [&](const Vec3& a, const Vec3& b, const Vec3& d) {
          const double v = a.dot(b.cross(d)) / 6.0;
          const Vec3 s = a + b + d;
          c += v / 20.0 * (a * a.transpose() + b * b.transpose() + d * d.transpose() +
                           s * s.transpose());
        });
      return Mat3::Identity() * c.trace() - c;
    }
    case ShapeType::Plane: return Mat3::Zero();
  }
  return Mat3::Zero();
}

Aabb computeAabb(const Geometry& g, const Transform& x) {
  const Mat3 rot = x.q.toRotationMatrix();
  Vec3 ext = Vec3::Zero();
  switch (g.type) {
    case ShapeType::Sphere: ext.setConstant(g.radius); break;
    case ShapeType::Capsule:
      ext = g.half_height * rot.col(2).cwiseAbs() + Vec3::Constant(g.radius);
      break;
    case ShapeType::Box: ext = rot.cwiseAbs() * g.half_extents; break;
    case ShapeType::Cylinder: {
      const Vec3 w = rot.col(2);
      for (int i = 0; i < 3; ++i)
        ext[i] = g.half_height * std::abs(w[i]) +
                 g.radius * std::sqrt(std::max(0.0, 1.0 - w[i] * w[i]));
      break;
    }
    case ShapeType::ConvexHull: {
      if (!g.hull || g.hull->vertices.empty()) return {x.p, x.p};
      Aabb box{Vec3::Constant(std::numeric_limits<double>::max()),
               Vec3::Constant(std::numeric_limits<double>::lowest())};
      for (const Vec3& v : g.hull->vertices) {
        const Vec3 w = rot * v;
        box.lo = box.lo.cwiseMin(w);
        box.hi = box.hi.cwiseMax(w);
      }
      return {box.lo + x.p, box.hi + x.p};
    }
    case ShapeType::Plane: {
      const double big = 1e30;
      return {Vec3::Constant(-big), Vec3::Constant(big)};
    }
  }
  return {x.p - ext, x.p + ext};
}

double boundingRadius(const Geometry& g) {
  switch (g.type) {
    case ShapeType::Sphere: return g.radius;
    case ShapeType::Capsule: return g.radius + g.half_height;
    case ShapeType::Box: return g.half_extents.norm();
    case ShapeType::Cylinder: return std::hypot(g.radius, g.half_height);
    case ShapeType::ConvexHull: {
      double r = 0;
      for (const Vec3& v : g.hull->vertices) r = std::max(r, v.norm());
      return r;
    }
    case ShapeType::Plane: break;
  }
  return 0;
}

double maxExtent(const Geometry& g, const Transform& x, const Vec3& point) {
  const Vec3 c = x.p - point;
  const Vec3 axis = x.q * Vec3::UnitZ();
  switch (g.type) {
    case ShapeType::Sphere: return c.norm() + g.radius;
    case ShapeType::Capsule:
      return std::max((c + g.half_height * axis).norm(), (c - g.half_height * axis).norm()) + g.radius;
    case ShapeType::Cylinder: {
      // farthest rim point: the end-cap centre farther away, plus the radius across the axis
      double best = 0.0;
      for (const double s : {1.0, -1.0}) {
        const Vec3 e = c + s * g.half_height * axis;
        const double along = e.dot(axis), across = (e - along * axis).norm() + g.radius;
        best = std::max(best, std::sqrt(along * along + across * across));
      }
      return best;
    }
    case ShapeType::Box: {
      double best = 0.0;
      for (int k = 0; k < 8; ++k) {
        const Vec3 corner(k & 1 ? g.half_extents.x() : -g.half_extents.x(),
                          k & 2 ? g.half_extents.y() : -g.half_extents.y(),
                          k & 4 ? g.half_extents.z() : -g.half_extents.z());
        best = std::max(best, (c + x.q * corner).norm());
      }
      return best;
    }
    case ShapeType::ConvexHull: {
      double best = c.norm();
      if (g.hull)
        for (const Vec3& v : g.hull->vertices) best = std::max(best, (c + x.q * v).norm());
      return best;
    }
    case ShapeType::Plane: return 0.0;
  }
  return 0.0;
}

}  // namespace ragdoll_sim
