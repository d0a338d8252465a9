// Joint definitions. Every joint is placed by a joint frame fixed in body A (frame_a, in A's
// link frame) and one fixed in body B (frame_b); at zero angles the two frames coincide.
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <string>

#include "ragdoll_sim/body.hpp"

namespace ragdoll_sim {

struct JointId {
  int32_t index = -1;
  bool valid() const { return index >= 0; }
  bool operator==(JointId o) const { return index == o.index; }
};

enum class JointType : uint8_t { Ball, Hinge, Fixed, Prismatic };

// Optional elasticity of a joint's anchor: with stiffness > 0 the anchors are held by a Hooke
// spring F = -k x - c v instead of rigidly. The joint breaks (and stays broken: the bodies fly
// apart with their momentum) once the force in it passes break_force: k |x| for a spring, the
// constraint force for a rigid anchor.
struct JointSpring {
  double stiffness = 0.0;  // N/m, 0 = rigid
  double damping = 0.0;    // N s/m
  double break_force = std::numeric_limits<double>::infinity();  // N
  // Fixed joints: N m in the rotation lock. Past it the weld breaks (a lock transmits at most
  // this torque, like the anchor and break_force).
  double break_torque = std::numeric_limits<double>::infinity();
};

// Joint motor on each angle: drives it towards `target` (rad) as a soft constraint of natural
// frequency `hertz` and damping ratio `damping_ratio`, or, with hertz = 0, its rate towards
// `target_velocity` (rad/s); the torque is capped at max_torque (N m). Joint friction is a
// velocity motor with target 0 and max_torque = the friction torque; viscous damping is the
// `damping` term, applied implicitly.
struct JointMotor {
  bool enabled = false;
  double target = 0.0;
  double target_velocity = 0.0;
  double hertz = 0.0;
  double damping_ratio = 1.0;
  double max_torque = 0.0;
  double damping = 0.0;  // N m s/rad, viscous joint damping (applied even when !enabled)
};

// How a ball joint's limits (enable_limits) are expressed.
enum class BallLimitMode : uint8_t {
  Euler,      // lower / upper on the three Euler angles about `axes`
  SwingTwist  // a cone around the twist axis axes[0] and a range of twist about it
};

// Ball joint: anchors coincide. Optional limits on the Euler angles of B's joint frame relative
// to A's, decomposed about three orthonormal joint-frame axes in the order given (the meaning
// of a chain of three revolute joints with coincident origins: R = R(a0,t0) R(a1,t1) R(a2,t2)),
// or, with limit_mode SwingTwist, on the swing-twist decomposition R = R_swing R(t, twist):
// t = axes[0] (joint frame) is the twist axis, swing is the angle between t carried by frame A
// and t carried by frame B, held within the cone, and twist (about t, in (-pi, pi]) within
// [twist_lower, twist_upper]. The cone is circular with half-angle swing_cone_angle (> 0), or,
// with swing_cone_angle_2 > 0, elliptical: the swing rotation vector's components sw1, sw2
// about axes[1] and axes[2] (made perpendicular to t) stay within
// (sw1 / swing_cone_angle)^2 + (sw2 / swing_cone_angle_2)^2 <= 1 (both half-angles <= pi).
// Motors stay on the Euler angles in both modes.
struct BallJointDef {
  BodyId body_a, body_b;
  Transform frame_a, frame_b;
  std::array<Vec3, 3> axes = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  bool enable_limits = false;
  BallLimitMode limit_mode = BallLimitMode::Euler;
  std::array<double, 3> lower = {0, 0, 0};  // Euler mode
  std::array<double, 3> upper = {0, 0, 0};
  double swing_cone_angle = 0.0;            // SwingTwist mode, rad (half-angle of the cone)
  double swing_cone_angle_2 = 0.0;          // rad, about axes[2]; 0 = circular cone
  double twist_lower = 0.0, twist_upper = 0.0;  // SwingTwist mode, rad
  std::array<JointMotor, 3> motors;  // one per Euler axis
  JointSpring spring;
  bool collide_connected = false;
};

// Hinge: anchors coincide and B rotates relative to A about `axis` (joint frame, unit).
// The angle is positive by the right-hand rule about the axis, 0 when the frames coincide.
struct HingeJointDef {
  BodyId body_a, body_b;
  Transform frame_a, frame_b;
  Vec3 axis = Vec3::UnitZ();
  bool enable_limit = false;
  double lower = 0.0, upper = 0.0;
  JointMotor motor;
  JointSpring spring;
  bool collide_connected = false;
};

// Fixed (weld): anchors coincide and the joint frames keep the same orientation. The spring
// acts on the anchor only (stiffness > 0: Hooke spring, the rotation stays locked rigidly);
// break_force caps the anchor force (the rotation lock has no torque limit).
struct FixedJointDef {
  BodyId body_a, body_b;
  Transform frame_a, frame_b;
  JointSpring spring;
  bool collide_connected = false;
};

// Prismatic (slider): the joint frames keep the same orientation and anchor B moves only along
// `axis` (joint frame of A, unit). The position is s = axis . (anchor B - anchor A), 0 when the
// frames coincide. The motor is read as linear: target (m), target_velocity (m/s), max_torque
// is the force cap (N), damping is N s/m. Only spring.break_force is used (off-axis force
// plus axial limit / motor force); a spring stiffness is rejected.
struct PrismaticJointDef {
  BodyId body_a, body_b;
  Transform frame_a, frame_b;
  Vec3 axis = Vec3::UnitX();
  bool enable_limit = false;
  double lower = 0.0, upper = 0.0;  // m
  JointMotor motor;
  JointSpring spring;
  bool collide_connected = false;
};

// "" when the World can simulate the def, else what is wrong with the first field that it
// cannot, named as in the struct ("spring.break_force must be > 0 (or inf), got nan"): frames
// finite, axes finite and not zero, enabled limits with lower <= upper (infinite ends allowed),
// springs and motors with finite gains >= 0 (max_torque and break forces may be infinite).
// The World's create*Joint and setJointMotor throw std::invalid_argument with it
// (src/core/joint_def.cpp).
std::string jointSpringError(const JointSpring& spring);
std::string jointMotorError(const JointMotor& motor);
std::string jointDefError(const BallJointDef& def);
std::string jointDefError(const HingeJointDef& def);
std::string jointDefError(const FixedJointDef& def);
std::string jointDefError(const PrismaticJointDef& def);

}  // namespace ragdoll_sim
