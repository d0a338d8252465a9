// Distance or penetration between two convex cores given by support mappings.
#pragma once

#include <limits>

#include "ragdoll_sim/shape.hpp"

namespace ragdoll_sim {
namespace np {

// The core of a placed shape: a sphere's centre, a capsule's segment, or the whole solid for
// a box, cylinder or hull. The shape is the core grown by radius().
struct ConvexCore {
  const Geometry* g;
  Transform x;
  Vec3 support(const Vec3& d) const;  // world point of the core farthest along d (world)
  double radius() const;
};

struct CoreDistance {
  Vec3 normal;      // unit, from A to B
  double distance;  // signed: negative is the penetration depth of the cores
  Vec3 pa, pb;      // witness points on the cores (pb - pa == distance * normal)
};

// GJK for separated cores; EPA on the Minkowski difference when they overlap. guess: a likely
// normal from A to B (last step's), or null; GJK then starts on the near side of A - B.
// far: GJK stops as soon as it proves the cores farther apart than this, and returns that
// lower bound as the distance (the normal is the current search direction, a separating axis).
CoreDistance coreDistance(const ConvexCore& a, const ConvexCore& b, const Vec3* guess = nullptr,
                          double far = std::numeric_limits<double>::infinity());

}  // namespace np
}  // namespace ragdoll_sim
