// The ranges of the joint defs (joint.hpp), in one place: the World's create*Joint and
// setJointMotor throw with these messages, so a NaN or a reversed limit never reaches the
// solver (where it would reset the bodies as faults every step).

#include <cmath>

#include "ragdoll_sim/joint.hpp"
#include "ragdoll_sim/range_check.hpp"

namespace ragdoll_sim {

namespace {

std::string axisError(const std::string& name, const Vec3& a) {
  if (a.allFinite() && a.norm() > 0.0) return "";
  return name + " must be a finite, non-zero vector";
}

std::string commonError(const Transform& frame_a, const Transform& frame_b,
                        const JointSpring& spring) {
  std::string e = firstError({poseError("frame_a", frame_a), poseError("frame_b", frame_b)});
  if (!e.empty()) return e;
  if (!(e = jointSpringError(spring)).empty()) return "spring." + e;
  return "";
}

template <class Def>
std::string axisJointError(const Def& d) {
  std::string e = commonError(d.frame_a, d.frame_b, d.spring);
  if (e.empty()) e = axisError("axis", d.axis);
  if (e.empty() && d.enable_limit) e = orderError("lower", d.lower, "upper", d.upper);
  if (e.empty() && !(e = jointMotorError(d.motor)).empty()) e = "motor." + e;
  return e;
}

}  // namespace

std::string jointSpringError(const JointSpring& s) {
  return firstError({nonNegativeError("stiffness", s.stiffness),
                     nonNegativeError("damping", s.damping),
                     positiveOrInfError("break_force", s.break_force),
                     positiveOrInfError("break_torque", s.break_torque)});
}

std::string jointMotorError(const JointMotor& m) {
  return firstError({finiteError("target", m.target),
                     finiteError("target_velocity", m.target_velocity),
                     nonNegativeError("hertz", m.hertz),
                     nonNegativeError("damping_ratio", m.damping_ratio),
                     nonNegativeOrInfError("max_torque", m.max_torque),
                     nonNegativeError("damping", m.damping)});
}

std::string jointDefError(const BallJointDef& d) {
  std::string e = commonError(d.frame_a, d.frame_b, d.spring);
  for (int k = 0; k < 3 && e.empty(); ++k)
    e = axisError("axes[" + std::to_string(k) + "]", d.axes[k]);
  if (e.empty() && d.enable_limits) {
    if (d.limit_mode == BallLimitMode::Euler) {
      for (int k = 0; k < 3 && e.empty(); ++k) {
        const std::string i = "[" + std::to_string(k) + "]";
        e = orderError("lower" + i, d.lower[k], "upper" + i, d.upper[k]);
      }
    } else {
      e = firstError({positiveOrInfError("swing_cone_angle", d.swing_cone_angle),
                      orderError("twist_lower", d.twist_lower, "twist_upper", d.twist_upper)});
      // An elliptical cone needs two finite half-angles (its boundary is ab / sqrt(...)).
      if (e.empty() && d.swing_cone_angle_2 != 0.0)
        e = firstError({rangeError("swing_cone_angle_2", d.swing_cone_angle_2, 0.0, M_PI),
                        rangeError("swing_cone_angle", d.swing_cone_angle, 0.0, M_PI)});
    }
  }
  for (int k = 0; k < 3 && e.empty(); ++k)
    if (!(e = jointMotorError(d.motors[k])).empty())
      e = "motors[" + std::to_string(k) + "]." + e;
  return e;
}

std::string jointDefError(const HingeJointDef& d) { return axisJointError(d); }

std::string jointDefError(const FixedJointDef& d) {
  return commonError(d.frame_a, d.frame_b, d.spring);
}

std::string jointDefError(const PrismaticJointDef& d) {
  std::string e = axisJointError(d);
  if (e.empty() && d.spring.stiffness > 0.0)
    e = "spring.stiffness must be 0 (a prismatic joint has no anchor spring)";
  return e;
}

}  // namespace ragdoll_sim
