// Joint settings and joint targets of the node, ROS-free (unit-tested in test/scene):
//   - AxisTable: every joint angle of a RagdollDef by the name joint_states gives it (a hinge's
//     URDF name; a ball chain's three source revolute joints; a 2-joint chain's locked third
//     axis "<ball name>_2"), with its limits;
//   - JointSettings / applyJointSettings: ~joint_defaults and ~joints (config/joints.yaml):
//     anchor spring, break force and motor gains per joint, resolved onto the RagdollDef
//     (springs, applied when it is spawned) and per-axis motor gains;
//   - checkTargetPose / AxisTarget / targetMotor: ~target_pose (sensor_msgs/JointState) checked
//     and turned into joint motors.
#pragma once

#include <optional>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "ragdoll_sim/joint.hpp"
#include "ragdoll_sim/ragdoll.hpp"
#include "ragdoll_sim/scene.hpp"

namespace ragdoll_sim {
namespace scene {

// Range checks of MotorGains; "" when valid, else a message starting with `where`.
std::string validateMotorGains(const MotorGains& g, const std::string& where);

// Range checks of the fields present; "" when valid, else a message starting with `where`.
std::string validateJointSettings(const JointSettings& s, const std::string& where);

// `base` with the cone / twist that `s` sets.
SwingTwistLimits swingTwistOver(SwingTwistLimits base, const JointSettings& s);

struct AxisInfo {
  std::string name;   // as published in joint_states
  int joint = -1;     // RagdollDef::joints index
  int axis = 0;       // hinge: 0; ball: Euler axis 0..2
  bool limited = false;
  double lower = 0.0, upper = 0.0;  // rad, when limited
};

class AxisTable {
 public:
  AxisTable() = default;
  explicit AxisTable(const RagdollDef& def);
  const std::vector<AxisInfo>& axes() const { return axes_; }
  int size() const { return static_cast<int>(axes_.size()); }
  const AxisInfo& operator[](int i) const { return axes_[static_cast<size_t>(i)]; }
  int find(const std::string& name) const;       // axis index or -1
  int first(int joint) const { return first_.at(static_cast<size_t>(joint)); }  // first axis of a joint
  int count(int joint) const;                      // 1 (hinge) or 3 (ball)

 private:
  std::vector<AxisInfo> axes_;
  std::vector<int> first_;
  std::unordered_map<std::string, int> index_;
};

struct JointSettingsResult {
  std::string error;                  // "" or a conflict naming both entries
  std::vector<std::string> warnings;  // entries naming no joint (ignored)
  std::vector<MotorGains> gains;      // per axis of the AxisTable
};

// Resolves `entries` (joint name -> settings) over `defaults` (springs) and
// `motor` (gains) and writes the springs into def->joints[*].spring. An entry's name is a
// RagdollDef joint name (a hinge's URDF name or a ball's "<a>+<b>+<c>": the whole joint) or an
// AxisTable name (one axis; for a ball its spring fields apply to the whole ball joint).
// Motor gains: `motor` < defaults < whole-joint entry < axis entry. Two entries setting the
// same spring field (or cone, or twist) of one joint are an error. cone / twist set the
// joint's swing-twist limits (over the URDF's); on a joint that is not a ball, an error.
// Values must have passed validateJointSettings.
JointSettingsResult applyJointSettings(RagdollDef* def, const AxisTable& axes,
                                       const JointSettings& defaults,
                                       const std::vector<std::pair<std::string, JointSettings>>& entries,
                                       const MotorGains& motor);

// A target of one axis from ~target_pose.
struct AxisTarget {
  bool active = false;
  bool has_position = false;  // false: velocity motor at `velocity`
  double position = 0.0;      // rad, at sim time `since`
  double velocity = 0.0;      // rad/s; with a position the target moves at this rate
  double since = 0.0;         // s of sim time when it was set
};

struct TargetPoseCheck {
  bool ok = false;
  std::string error;                 // names the problem when !ok
  std::string problem;               // the rule that failed (fixed short name, a throttle key)
  std::vector<int> axes;             // per name: AxisTable index
  std::vector<std::string> clamped;  // names whose position lies outside the joint's limits
};

// Rules: at least one name; every name in the AxisTable, none twice; `position` and `velocity`
// each empty or one per name, not both empty; every value finite. Positions outside a limited
// joint's range are allowed (clamped by targetPosition) and listed in `clamped`.
TargetPoseCheck checkTargetPose(const TargetPoseCommand& cmd, const AxisTable& axes);

// The per-axis targets of a checked command, set at sim time `now`.
std::vector<std::pair<int, AxisTarget>> toAxisTargets(const TargetPoseCommand& cmd,
                                                      const TargetPoseCheck& check, double now);

// Target angle at sim time t: position + velocity (t - since), clamped to the axis limits.
double targetPosition(const AxisTarget& t, const AxisInfo& axis, double now);

// The motor of an axis with a target: a position motor (gains) at targetPosition, or a velocity
// motor at target.velocity, keeping the passive motor's viscous damping (its friction motor is
// replaced while a target is active).
JointMotor targetMotor(const AxisTarget& t, const AxisInfo& axis, const MotorGains& gains,
                       const JointMotor& passive, double now);

// The motor that holds an axis at angle `angle` (gains), with the passive damping.
JointMotor holdMotor(double angle, const MotorGains& gains, const JointMotor& passive);

}  // namespace scene
}  // namespace ragdoll_sim
