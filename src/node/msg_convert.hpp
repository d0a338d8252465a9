// Conversions between the core's Eigen types and geometry_msgs, shared by the node's files.
#pragma once

#include <geometry_msgs/Point.h>
#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Transform.h>
#include <geometry_msgs/Vector3.h>

#include "ragdoll_sim/math.hpp"

namespace ragdoll_sim {
namespace node {

inline void toMsg(const Vec3& v, geometry_msgs::Vector3* m) {
  m->x = v.x();
  m->y = v.y();
  m->z = v.z();
}

inline geometry_msgs::Point toPoint(const Vec3& v) {
  geometry_msgs::Point p;
  p.x = v.x();
  p.y = v.y();
  p.z = v.z();
  return p;
}

inline void toMsg(const Transform& t, geometry_msgs::Pose* m) {
  m->position = toPoint(t.p);
  m->orientation.x = t.q.x();
  m->orientation.y = t.q.y();
  m->orientation.z = t.q.z();
  m->orientation.w = t.q.w();
}

inline void toMsg(const Transform& t, geometry_msgs::Transform* m) {
  toMsg(t.p, &m->translation);
  m->rotation.x = t.q.x();
  m->rotation.y = t.q.y();
  m->rotation.z = t.q.z();
  m->rotation.w = t.q.w();
}

inline Vec3 toVec(const geometry_msgs::Vector3& v) { return Vec3(v.x, v.y, v.z); }
inline Vec3 toVec(const geometry_msgs::Point& v) { return Vec3(v.x, v.y, v.z); }

}  // namespace node
}  // namespace ragdoll_sim
