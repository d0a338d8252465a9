#include "joint_control.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "names.hpp"

namespace ragdoll_sim {
namespace scene {

namespace {

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

}  // namespace

std::string validateMotorGains(const MotorGains& g, const std::string& where) {
  if (!(std::isfinite(g.hertz) && g.hertz > 0.0))
    return where + "/hertz must be a finite number > 0 (Hz), got " + num(g.hertz);
  if (!(std::isfinite(g.damping_ratio) && g.damping_ratio >= 0.0))
    return where + "/damping_ratio must be a finite number >= 0, got " + num(g.damping_ratio);
  if (!(std::isfinite(g.max_torque) && g.max_torque > 0.0))
    return where + "/max_torque must be a finite number > 0 (N m), got " + num(g.max_torque);
  return "";
}

std::string validateJointSettings(const JointSettings& s, const std::string& where) {
  if (s.stiffness && !(std::isfinite(*s.stiffness) && *s.stiffness >= 0.0))
    return where + "/stiffness must be a finite number >= 0 (N/m), got " + num(*s.stiffness);
  if (s.damping && !(std::isfinite(*s.damping) && *s.damping >= 0.0))
    return where + "/damping must be a finite number >= 0 (N s/m), got " + num(*s.damping);
  if (s.break_force && !(*s.break_force > 0.0))
    return where + "/break_force must be a number > 0 (N) or .inf, got " + num(*s.break_force);
  if (s.break_torque && !(*s.break_torque > 0.0))
    return where + "/break_torque must be a number > 0 (N m) or .inf, got " + num(*s.break_torque);
  if (s.hertz && !(std::isfinite(*s.hertz) && *s.hertz > 0.0))
    return where + "/motor/hertz must be a finite number > 0 (Hz), got " + num(*s.hertz);
  if (s.damping_ratio && !(std::isfinite(*s.damping_ratio) && *s.damping_ratio >= 0.0))
    return where + "/motor/damping_ratio must be a finite number >= 0, got " + num(*s.damping_ratio);
  if (s.max_torque && !(std::isfinite(*s.max_torque) && *s.max_torque > 0.0))
    return where + "/motor/max_torque must be a finite number > 0 (N m), got " + num(*s.max_torque);
  if (s.cone || s.twist) {
    const std::string names[4] = {where + "/cone[0]", where + "/cone[1]", where + "/twist[0]",
                                  where + "/twist[1]"};
    const std::string e = swingTwistLimitsError(
        swingTwistOver(SwingTwistLimits(), s),
        {names[0].c_str(), names[1].c_str(), names[2].c_str(), names[3].c_str()});
    if (!e.empty()) return e;
  }
  return "";
}

SwingTwistLimits swingTwistOver(SwingTwistLimits base, const JointSettings& s) {
  if (s.cone) {
    base.cone_1 = (*s.cone)[0];
    base.cone_2 = (*s.cone)[1];
  }
  if (s.twist) {
    base.twist_lower = (*s.twist)[0];
    base.twist_upper = (*s.twist)[1];
  }
  return base;
}

// ------------------------------------------------------------------------------------------

AxisTable::AxisTable(const RagdollDef& def) {
  for (size_t j = 0; j < def.joints.size(); ++j) {
    const RagdollJointDef& jd = def.joints[j];
    first_.push_back(static_cast<int>(axes_.size()));
    const size_t n = static_cast<size_t>(jointAxisCount(jd.kind));
    for (size_t k = 0; k < n; ++k) {
      AxisInfo a;
      if (k < jd.source_joints.size()) a.name = jd.source_joints[k];
      else a.name = n == 1 ? jd.name : jd.name + "_" + std::to_string(k);
      a.joint = static_cast<int>(j);
      a.axis = static_cast<int>(k);
      a.limited = jd.limited && k < jd.lower.size() && k < jd.upper.size();
      if (a.limited) {
        a.lower = jd.lower[k];
        a.upper = jd.upper[k];
      }
      index_.emplace(a.name, static_cast<int>(axes_.size()));
      axes_.push_back(a);
    }
  }
}

int AxisTable::find(const std::string& name) const {
  auto it = index_.find(name);
  return it == index_.end() ? -1 : it->second;
}

int AxisTable::count(int joint) const {
  const size_t j = static_cast<size_t>(joint);
  const int end = j + 1 < first_.size() ? first_[j + 1] : size();
  return end - first_.at(j);
}

// ------------------------------------------------------------------------------------------

JointSettingsResult applyJointSettings(RagdollDef* def, const AxisTable& axes,
                                       const JointSettings& defaults,
                                       const std::vector<std::pair<std::string, JointSettings>>& entries,
                                       const MotorGains& motor) {
  JointSettingsResult r;
  auto gainsOf = [](MotorGains g, const JointSettings& s) {
    if (s.hertz) g.hertz = *s.hertz;
    if (s.damping_ratio) g.damping_ratio = *s.damping_ratio;
    if (s.max_torque) g.max_torque = *s.max_torque;
    return g;
  };
  const MotorGains base = gainsOf(motor, defaults);
  r.gains.assign(static_cast<size_t>(axes.size()), base);

  JointSpring spring_default;
  if (defaults.stiffness) spring_default.stiffness = *defaults.stiffness;
  if (defaults.damping) spring_default.damping = *defaults.damping;
  if (defaults.break_force) spring_default.break_force = *defaults.break_force;
  if (defaults.break_torque) spring_default.break_torque = *defaults.break_torque;
  for (RagdollJointDef& j : def->joints) j.spring = spring_default;

  // Which entry set which spring field of which joint (for conflicts).
  std::vector<std::array<std::string, 4>> set_by(def->joints.size());
  std::vector<std::array<std::string, 2>> limit_set_by(def->joints.size());  // cone, twist
  // Motor gains: whole-joint entries first, then per-axis entries on top.
  std::vector<const JointSettings*> joint_level(def->joints.size(), nullptr);
  std::vector<const JointSettings*> axis_level(static_cast<size_t>(axes.size()), nullptr);

  for (const auto& [name, s] : entries) {
    int joint = -1, axis = -1;
    for (size_t k = 0; k < def->joints.size() && joint < 0; ++k)
      if (def->joints[k].name == name) joint = static_cast<int>(k);
    if (joint < 0) {
      axis = axes.find(name);
      if (axis >= 0) joint = axes[axis].joint;
    }
    if (joint < 0) {
      r.warnings.push_back("~joints/" + name + " names no joint of the ragdoll; ignored");
      continue;
    }
    // A hinge's name is both the joint and its only axis: treat it as the joint.
    if (axis >= 0 && axes.count(joint) == 1) axis = -1;
    RagdollJointDef& jd = def->joints[static_cast<size_t>(joint)];
    const std::optional<double>* fields[4] = {&s.stiffness, &s.damping, &s.break_force,
                                              &s.break_torque};
    const char* field_names[4] = {"stiffness", "damping", "break_force", "break_torque"};
    double* targets[4] = {&jd.spring.stiffness, &jd.spring.damping, &jd.spring.break_force,
                          &jd.spring.break_torque};
    for (int f = 0; f < 4; ++f) {
      if (!*fields[f]) continue;
      std::string& who = set_by[static_cast<size_t>(joint)][static_cast<size_t>(f)];
      if (!who.empty()) {
        r.error = "~joints/" + who + " and ~joints/" + name + " both set " + field_names[f] +
                  " of joint " + quoted(jd.name);
        return r;
      }
      who = name;
      *targets[f] = **fields[f];
    }
    if (s.cone || s.twist) {
      if (jd.kind != RagdollJointKind::Ball) {
        r.error = "~joints/" + name + ": cone and twist apply to ball joints only, " +
                  quoted(jd.name) + " is a " + jointKindName(jd.kind);
        return r;
      }
      const bool sets[2] = {bool(s.cone), bool(s.twist)};
      const char* limit_names[2] = {"cone", "twist"};
      for (int f = 0; f < 2; ++f) {
        if (!sets[f]) continue;
        std::string& who = limit_set_by[static_cast<size_t>(joint)][static_cast<size_t>(f)];
        if (!who.empty()) {
          r.error = "~joints/" + who + " and ~joints/" + name + " both set " + limit_names[f] +
                    " of joint " + quoted(jd.name);
          return r;
        }
        who = name;
      }
      jd.swing_twist = swingTwistOver(jd.swing_twist.value_or(SwingTwistLimits()), s);
    }
    if (axis >= 0) axis_level[static_cast<size_t>(axis)] = &s;
    else joint_level[static_cast<size_t>(joint)] = &s;
  }
  for (int i = 0; i < axes.size(); ++i) {
    MotorGains& g = r.gains[static_cast<size_t>(i)];
    if (const JointSettings* s = joint_level[static_cast<size_t>(axes[i].joint)]) g = gainsOf(g, *s);
    if (const JointSettings* s = axis_level[static_cast<size_t>(i)]) g = gainsOf(g, *s);
  }
  return r;
}

// ------------------------------------------------------------------------------------------

TargetPoseCheck checkTargetPose(const TargetPoseCommand& cmd, const AxisTable& axes) {
  TargetPoseCheck c;
  const size_t n = cmd.names.size();
  if (n == 0) {
    c.problem = "no names";
    c.error = "target pose with no joint names";
    return c;
  }
  if (!cmd.position.empty() && cmd.position.size() != n) {
    c.problem = "positions length";
    c.error = "target pose has " + std::to_string(n) + " names but " +
              std::to_string(cmd.position.size()) + " positions";
    return c;
  }
  if (!cmd.velocity.empty() && cmd.velocity.size() != n) {
    c.problem = "velocities length";
    c.error = "target pose has " + std::to_string(n) + " names but " +
              std::to_string(cmd.velocity.size()) + " velocities";
    return c;
  }
  if (cmd.position.empty() && cmd.velocity.empty()) {
    c.problem = "no values";
    c.error = "target pose has neither positions nor velocities";
    return c;
  }
  std::vector<bool> seen(static_cast<size_t>(axes.size()), false);
  for (size_t i = 0; i < n; ++i) {
    const std::string& name = cmd.names[i];
    const int a = axes.find(name);
    if (a < 0) {
      c.problem = "unknown joint";
      c.error = "target pose names unknown joint " + quoted(name);
      return c;
    }
    if (seen[static_cast<size_t>(a)]) {
      c.problem = "repeated joint";
      c.error = "target pose names joint " + quoted(name) + " twice";
      return c;
    }
    seen[static_cast<size_t>(a)] = true;
    if (!cmd.position.empty() && !std::isfinite(cmd.position[i])) {
      c.problem = "position not finite";
      c.error = "target pose position of " + quoted(name) + " is not finite";
      return c;
    }
    if (!cmd.velocity.empty() && !std::isfinite(cmd.velocity[i])) {
      c.problem = "velocity not finite";
      c.error = "target pose velocity of " + quoted(name) + " is not finite";
      return c;
    }
    const AxisInfo& info = axes[a];
    if (!cmd.position.empty() && info.limited &&
        (cmd.position[i] < info.lower || cmd.position[i] > info.upper))
      c.clamped.push_back(name);
    c.axes.push_back(a);
  }
  c.ok = true;
  return c;
}

std::vector<std::pair<int, AxisTarget>> toAxisTargets(const TargetPoseCommand& cmd,
                                                      const TargetPoseCheck& check, double now) {
  std::vector<std::pair<int, AxisTarget>> out;
  for (size_t i = 0; i < check.axes.size(); ++i) {
    AxisTarget t;
    t.active = true;
    t.has_position = !cmd.position.empty();
    t.position = t.has_position ? cmd.position[i] : 0.0;
    t.velocity = cmd.velocity.empty() ? 0.0 : cmd.velocity[i];
    t.since = now;
    out.emplace_back(check.axes[i], t);
  }
  return out;
}

double targetPosition(const AxisTarget& t, const AxisInfo& axis, double now) {
  double p = t.position + t.velocity * std::max(0.0, now - t.since);
  if (axis.limited) p = std::clamp(p, axis.lower, axis.upper);
  return p;
}

JointMotor targetMotor(const AxisTarget& t, const AxisInfo& axis, const MotorGains& gains,
                       const JointMotor& passive, double now) {
  if (t.has_position) return holdMotor(targetPosition(t, axis, now), gains, passive);
  JointMotor m;
  m.enabled = true;
  m.hertz = 0.0;
  m.target_velocity = t.velocity;
  m.max_torque = gains.max_torque;
  m.damping = passive.damping;
  return m;
}

JointMotor holdMotor(double angle, const MotorGains& gains, const JointMotor& passive) {
  JointMotor m;
  m.enabled = true;
  m.target = angle;
  m.hertz = gains.hertz;
  m.damping_ratio = gains.damping_ratio;
  m.max_torque = gains.max_torque;
  m.damping = passive.damping;
  return m;
}

}  // namespace scene
}  // namespace ragdoll_sim
