#include "interaction_laws.hpp"

#include <algorithm>
#include <cmath>

namespace ragdoll_sim {
namespace scene {

namespace {

// Signed distance to the segment [-h, h] on z, rounded by r (capsule core).
double capsuleDistance(const Vec3& p, double r, double h) {
  const Vec3 closest(0.0, 0.0, std::clamp(p.z(), -h, h));
  return (p - closest).norm() - r;
}

double boxDistance(const Vec3& p, const Vec3& half) {
  const Vec3 q = p.cwiseAbs() - half;
  const double outside = q.cwiseMax(0.0).norm();
  const double inside = std::min(q.maxCoeff(), 0.0);
  return outside + inside;
}

double cylinderDistance(const Vec3& p, double r, double h) {
  const double dr = std::hypot(p.x(), p.y()) - r;
  const double dz = std::abs(p.z()) - h;
  const double outside = std::hypot(std::max(dr, 0.0), std::max(dz, 0.0));
  return outside + std::min(std::max(dr, dz), 0.0);
}

}  // namespace

double shapeDistance(const ShapeDef& shape, const Transform& body_pose, const Vec3& point) {
  const Vec3 p = (body_pose * shape.local).applyInverse(point);
  const Geometry& g = shape.geometry;
  switch (g.type) {
    case ShapeType::Sphere: return p.norm() - g.radius;
    case ShapeType::Capsule: return capsuleDistance(p, g.radius, g.half_height);
    case ShapeType::Box: return boxDistance(p, g.half_extents);
    case ShapeType::Cylinder: return cylinderDistance(p, g.radius, g.half_height);
    case ShapeType::ConvexHull: {
      if (!g.hull || g.hull->faces.empty()) break;
      double d = -std::numeric_limits<double>::infinity();
      for (const HullData::Face& f : g.hull->faces) d = std::max(d, f.normal.dot(p) - f.offset);
      return d;
    }
    case ShapeType::Plane: break;
  }
  return std::numeric_limits<double>::infinity();
}

LinkPick pickNearestLink(const World& world, const std::vector<RagdollView>& ragdolls,
                         const Vec3& point, double max_distance) {
  LinkPick best;
  for (size_t r = 0; r < ragdolls.size(); ++r) {
    const Ragdoll* rd = ragdolls[r].ragdoll;
    if (!rd) continue;
    for (size_t l = 0; l < rd->bodies.size(); ++l) {
      const BodyId body = rd->bodies[l];
      if (!world.isValid(body)) continue;
      const Transform pose = world.bodyPose(body);
      for (const ShapeDef& s : world.bodyShapes(body)) {
        const double d = shapeDistance(s, pose, point);
        if (d < best.distance) {
          best.distance = d;
          best.ragdoll = static_cast<int>(r);
          best.link = static_cast<int>(l);
        }
      }
    }
  }
  if (!(best.distance <= max_distance)) {
    best.ragdoll = -1;
    best.link = -1;
  }
  return best;
}

Vec3 pokeImpulse(const Vec3& point, const Vec3& com, double magnitude) {
  const Vec3 d = com - point;
  const double n = d.norm();
  if (!(n > 1e-9)) return Vec3::Zero();
  return d * (magnitude / n);
}

Vec3 dragForce(const Vec3& point, const Vec3& velocity, const Vec3& target, const DragSettings& s,
               double max_force) {
  Vec3 f = s.stiffness * (target - point) - s.damping * velocity;
  const double cap = std::min(s.max_force, max_force);
  const double n = f.norm();
  if (n > cap) f *= cap / n;
  return f;
}

int dragLink(const RagdollDef& def, const std::string& name) {
  if (!name.empty()) return def.findLink(name);
  const int torso = def.findLink("torso");
  if (torso >= 0) return torso;
  return def.links.empty() ? -1 : def.root;
}

}  // namespace scene
}  // namespace ragdoll_sim
