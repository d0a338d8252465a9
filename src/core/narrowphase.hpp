// Narrowphase: contact manifolds between two placed geometries.
#pragma once

#include <cstdint>

#include "ragdoll_sim/shape.hpp"

namespace ragdoll_sim {

struct ManifoldPoint {
  Vec3 point = Vec3::Zero();  // world, midway between the two surfaces
  double separation = 0.0;    // signed distance along the normal (negative = penetration)
  uint32_t id = 0;            // feature id, stable across steps while the same features touch
};

struct Manifold {
  static constexpr int kMaxPoints = 4;
  Vec3 normal = Vec3::UnitZ();  // world, pointing from shape A to shape B
  int count = 0;
  // count == 0: a lower bound on the shapes' distance that proved them beyond the speculative
  // distance (the separating-axis, bounding-sphere or GJK bound that stopped the search); 0
  // where none was computed (planes, a hull without vertices).
  double gap = 0.0;
  ManifoldPoint points[kMaxPoints];
};

// Fills `out` with up to 4 points whose separation is below `speculative_distance`; out.count
// is 0 when the shapes are farther apart. Works for every pair of shape types except
// plane-plane; the order of the arguments only flips the normal. normal_guess (A to B, e.g.
// last step's normal of the pair) or null: where GJK runs, its first search direction.
void collide(const Geometry& a, const Transform& xa, const Geometry& b, const Transform& xb,
             double speculative_distance, Manifold& out, const Vec3* normal_guess = nullptr);

// World-space axis-aligned bounding box; planes are unbounded (see isUnbounded).
struct Aabb {
  Vec3 lo, hi;
  // Written out: the broadphase tests thousands of pairs per step and stops at the first axis.
  bool overlaps(const Aabb& o) const {
    return lo.x() <= o.hi.x() && o.lo.x() <= hi.x() && lo.y() <= o.hi.y() && o.lo.y() <= hi.y() &&
           lo.z() <= o.hi.z() && o.lo.z() <= hi.z();
  }
  // o lies inside this box (false when a bound is NaN).
  bool contains(const Aabb& o) const {
    return lo.x() <= o.lo.x() && lo.y() <= o.lo.y() && lo.z() <= o.lo.z() && o.hi.x() <= hi.x() &&
           o.hi.y() <= hi.y() && o.hi.z() <= hi.z();
  }
};
Aabb computeAabb(const Geometry& g, const Transform& x);
inline bool isUnbounded(const Geometry& g) { return g.type == ShapeType::Plane; }
// Distance from `point` to the farthest point of the shape at pose x (0 for a plane).
double maxExtent(const Geometry& g, const Transform& x, const Vec3& point);
// Distance from the shape's origin to its farthest point (0 for a plane): maxExtent at the
// identity pose about the origin, in closed form (the narrowphase and its cache use it per pair).
double boundingRadius(const Geometry& g);
// Radius a shape rolls on (sphere, capsule, cylinder); 0 for shapes that tip over edges.
inline double rollingRadius(const Geometry& g) {
  return g.type == ShapeType::Sphere || g.type == ShapeType::Capsule || g.type == ShapeType::Cylinder
             ? g.radius
             : 0.0;
}

}  // namespace ragdoll_sim
