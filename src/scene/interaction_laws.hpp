// The ROS-free laws behind poking and dragging a ragdoll from rviz (src/node/interaction.*):
// which link a clicked point picks, the poke impulse, and the drag spring-damper force.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "ragdoll_sim/world.hpp"
#include "ragdoll_view.hpp"
#include "rviz_settings.hpp"

namespace ragdoll_sim {
namespace scene {

// Signed distance from a world point to one shape of a body at `body_pose` (negative inside).
// Exact for spheres, capsules, boxes and cylinders; for a convex hull the largest face-plane
// distance (exact inside and in front of a face, a lower bound near edges and corners). Planes
// give +inf: a ground-like shape is never picked.
double shapeDistance(const ShapeDef& shape, const Transform& body_pose, const Vec3& point);

struct LinkPick {
  int ragdoll = -1;  // index into the RagdollView list; -1: nothing within max_distance
  int link = -1;     // index into RagdollDef::links
  double distance = std::numeric_limits<double>::infinity();  // to its nearest shape
  bool valid() const { return ragdoll >= 0; }
};

// The link of any ragdoll whose collision shapes come nearest to `point` (the deepest when the
// point is inside several), if that distance is at most `max_distance`. The nearest distance
// found is reported even when it is too far (for the warning).
LinkPick pickNearestLink(const World& world, const std::vector<RagdollView>& ragdolls,
                         const Vec3& point, double max_distance);

// The impulse of size `magnitude` at `point` towards `com`; zero when the two coincide (no
// direction).
Vec3 pokeImpulse(const Vec3& point, const Vec3& com, double magnitude);

// Spring-damper pull of a grabbed point at `point` moving at `velocity` towards `target`:
// stiffness (target - point) - damping velocity, its length capped at `max_force`.
Vec3 dragForce(const Vec3& point, const Vec3& velocity, const Vec3& target,
               const DragSettings& s, double max_force);

// The link the drag handle holds: `name` ("" = "torso" if the model has one, else the root
// link). -1 when a non-empty `name` is not a link of the model.
int dragLink(const RagdollDef& def, const std::string& name);

}  // namespace scene
}  // namespace ragdoll_sim
