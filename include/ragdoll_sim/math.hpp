// Small math vocabulary shared by the core, the loader and the node (Eigen, double precision).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace ragdoll_sim {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

// m: the World keeps centres of mass on a grid of 2^-32 m within this distance of the origin
// (src/core/body.hpp, snapPosition). A shape size or offset, or a joint frame offset, beyond it
// cannot belong to such a world: geometryError and poseError refuse them, since the poses and
// anchor errors computed from it would overflow.
constexpr double kWorldRange = 1048576.0;  // 2^20 m

// A point the World can hold: finite, every coordinate within kWorldRange (a body whose centre
// of mass leaves it is a BodyFault, world.hpp).
inline bool withinWorldRange(const Vec3& p) {
  return p.allFinite() && p.cwiseAbs().maxCoeff() <= kWorldRange;
}

// Rigid transform: x_parent = q * x_child + p.
struct Transform {
  Vec3 p = Vec3::Zero();
  Quat q = Quat::Identity();

  Transform() = default;
  Transform(const Vec3& p_, const Quat& q_) : p(p_), q(q_) {}

  Vec3 apply(const Vec3& x) const { return q * x + p; }
  Vec3 applyInverse(const Vec3& x) const { return q.conjugate() * (x - p); }
  Transform operator*(const Transform& b) const { return {q * b.p + p, (q * b.q).normalized()}; }
  Transform inverse() const {
    Quat qi = q.conjugate();
    return {-(qi * p), qi};
  }
};

// Cross-product matrix: skew(a) * b == a.cross(b).
inline Mat3 skew(const Vec3& a) {
  Mat3 m;
  m << 0, -a.z(), a.y(), a.z(), 0, -a.x(), -a.y(), a.x(), 0;
  return m;
}

// URDF / ROS roll-pitch-yaw (fixed axes X, then Y, then Z): R = Rz(yaw) Ry(pitch) Rx(roll).
inline Quat quatFromRpy(double roll, double pitch, double yaw) {
  return (Eigen::AngleAxisd(yaw, Vec3::UnitZ()) * Eigen::AngleAxisd(pitch, Vec3::UnitY()) *
          Eigen::AngleAxisd(roll, Vec3::UnitX()))
      .normalized();
}

// Any unit vector perpendicular to the unit vector n.
inline Vec3 anyPerpendicular(const Vec3& n) {
  Vec3 t = std::abs(n.x()) < 0.57735 ? Vec3::UnitX() : Vec3::UnitY();
  return n.cross(t).normalized();
}

inline bool allFinite(const Vec3& v) { return v.allFinite(); }

}  // namespace ragdoll_sim
