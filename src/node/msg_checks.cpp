#include "msg_checks.hpp"

#include <cmath>
#include <sstream>

namespace ragdoll_sim {
namespace node {

namespace {

// How far a quaternion's length may be from 1 and still be taken (normalized): hand-typed
// values rounded to 3 digits, e.g. (0.707, 0, 0, 0.707), pass; a rotation vector or a
// half-filled message does not.
constexpr double kUnitQuatTolerance = 0.01;

}  // namespace

std::string poseFromMsg(const geometry_msgs::Pose& m, double max_position, Transform* t,
                        std::string* problem) {
  const Vec3 p(m.position.x, m.position.y, m.position.z);
  Quat q(m.orientation.w, m.orientation.x, m.orientation.y, m.orientation.z);
  std::ostringstream e;
  const double n = q.norm();
  if (!p.allFinite()) {
    *problem = "position not finite";
    e << "the position (" << p.x() << ", " << p.y() << ", " << p.z() << ") is not finite";
  } else if (p.norm() > max_position) {
    *problem = "position above cap";
    e << "the position (" << p.x() << ", " << p.y() << ", " << p.z() << ") is " << p.norm()
      << " m from the origin, more than ~max_position = " << max_position << " m";
  } else if (!q.coeffs().allFinite()) {
    *problem = "orientation not finite";
    e << "the orientation is not finite";
  } else if (n == 0.0) {
    q = Quat::Identity();
  } else if (std::abs(n - 1.0) > kUnitQuatTolerance) {
    *problem = "orientation not unit";
    e << "the orientation (w " << q.w() << ", x " << q.x() << ", y " << q.y() << ", z " << q.z()
      << ") has length " << n << ", not a unit quaternion (within " << kUnitQuatTolerance
      << "; all zeros = identity)";
  }
  if (!e.str().empty()) return e.str();
  *t = Transform(p, q.normalized());
  return "";
}

std::string twistFromMsg(const geometry_msgs::Twist& m, double max_linear, double max_angular,
                         Vec3* v, Vec3* w, std::string* problem) {
  *v = Vec3(m.linear.x, m.linear.y, m.linear.z);
  *w = Vec3(m.angular.x, m.angular.y, m.angular.z);
  std::ostringstream e;
  if (!v->allFinite() || !w->allFinite()) {
    *problem = "bad twist";
    e << "the twist is not finite (linear (" << v->x() << ", " << v->y() << ", " << v->z()
      << "), angular (" << w->x() << ", " << w->y() << ", " << w->z() << "))";
  } else if (v->norm() > max_linear || w->norm() > max_angular) {
    *problem = "twist above cap";
    e << "|linear| = " << v->norm() << " m/s or |angular| = " << w->norm()
      << " rad/s exceeds ~max_linear_speed = " << max_linear << " m/s / ~max_angular_speed = "
      << max_angular << " rad/s";
  }
  return e.str();
}

}  // namespace node
}  // namespace ragdoll_sim
