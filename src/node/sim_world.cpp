// SimNode: ragdoll instances, building and rebuilding the World, joint motors.
#include <algorithm>
#include <cmath>

#include "sim_node.hpp"

namespace ragdoll_sim {
namespace node {

bool SimNode::makeInstance(RagdollDef def, const std::string& name, const std::string& tf_prefix,
                           const Transform& spawn, bool warn_unknown_joints, RagdollInstance* out,
                           std::string* error) {
  if (def.links.empty()) {
    *error = "the model has no links";
    return false;
  }
  RagdollInstance& r = *out;
  r.name = name;
  r.tf_prefix = tf_prefix;
  r.spawn_pose = spawn;
  // Joint springs, break forces and motor gains (~joint_defaults, ~joints) by joint name.
  r.axes = AxisTable(def);
  JointSettingsResult settings =
      applyJointSettings(&def, r.axes, config_.joint_defaults, config_.joints, config_.motor);
  if (warn_unknown_joints)
    for (const std::string& w : settings.warnings) ROS_WARN("%s", w.c_str());
  if (!settings.error.empty()) {
    *error = settings.error;
    return false;
  }
  r.def = std::move(def);
  r.gains = std::move(settings.gains);
  r.targets.assign(static_cast<size_t>(r.axes.size()), AxisTarget());
  r.moving_targets.clear();
  r.links = LinkTable(r.def);
  r.color_index = next_color_++;
  for (const RagdollJointDef& j : r.def.joints) {
    if (j.spring.stiffness > 0.0 || std::isfinite(j.spring.break_force) ||
        std::isfinite(j.spring.break_torque))
      ROS_INFO("%s: joint '%s': anchor stiffness %g N/m, damping %g N*s/m, break_force %g N, "
               "break_torque %g N*m",
               r.name.c_str(), j.name.c_str(), j.spring.stiffness, j.spring.damping,
               j.spring.break_force, j.spring.break_torque);
  }
  return true;
}

bool SimNode::spawnInWorld(RagdollInstance& r, std::string* error) {
  try {  // the World refuses what it cannot simulate (e.g. a non-finite pose) by throwing
    r.ragdoll = spawnRagdoll(*world_, r.def, r.spawn_pose, &config_.ragdoll_surface);
  } catch (const std::exception& e) {
    *error = e.what();
    return false;
  }
  if (r.ragdoll.bodies.size() != r.def.links.size() ||
      r.ragdoll.joints.size() != r.def.joints.size()) {
    *error = "spawnRagdoll returned " + std::to_string(r.ragdoll.bodies.size()) + " bodies / " +
             std::to_string(r.ragdoll.joints.size()) + " joints for a model with " +
             std::to_string(r.def.links.size()) + " links / " +
             std::to_string(r.def.joints.size()) + " joints";
    return false;
  }
  return true;
}

bool SimNode::buildWorld(bool carry_state, std::string* error) {
  // The state to carry over, per ragdoll: body states and broken joints.
  std::vector<std::vector<BodyState>> bodies(ragdolls_.size());
  std::vector<std::vector<char>> broken(ragdolls_.size());
  if (carry_state && world_) {
    for (size_t k = 0; k < ragdolls_.size(); ++k) {
      for (BodyId b : ragdolls_[k].ragdoll.bodies) bodies[k].push_back(world_->bodyState(b));
      for (JointId j : ragdolls_[k].ragdoll.joints)
        broken[k].push_back(world_->isJointBroken(j) ? 1 : 0);
    }
  }
  for (RagdollInstance& r : ragdolls_) r.balance.reset();  // they drive the old world's joints

  try {  // validated at start-up, and the .cfg ranges hold at run time: this is a guard
    world_ = std::make_unique<World>(worldDefOf(config_));
  } catch (const std::invalid_argument& e) {
    *error = e.what();
    return false;
  }
  ground_ = BodyId();
  if (config_.ground) {
    BodyDef gd;
    gd.type = BodyType::Static;
    gd.name = "ground";
    ground_ = world_->createBody(gd);
    ShapeDef sd;
    sd.geometry = Geometry::plane(Vec3::UnitZ(), 0.0);
    sd.material = config_.ground_surface;
    world_->addShape(ground_, sd);
  }
  for (size_t k = 0; k < ragdolls_.size(); ++k) {
    RagdollInstance& r = ragdolls_[k];
    if (!spawnInWorld(r, error)) return false;
    if (carry_state && bodies[k].size() == r.ragdoll.bodies.size()) {
      for (size_t i = 0; i < bodies[k].size(); ++i) {
        const BodyState& s = bodies[k][i];
        world_->setBodyState(r.ragdoll.bodies[i], s.pose, s.linear_velocity, s.angular_velocity);
      }
      for (size_t j = 0; j < broken[k].size(); ++j)
        if (broken[k][j]) world_->breakJoint(r.ragdoll.joints[j]);
    }
    setBalance(r, r.balance_on, /*log=*/false);
  }
  return true;
}

void SimNode::setBalance(RagdollInstance& r, bool on, bool log) {
  r.balance_on = on;
  r.balance.reset();
  if (on) {
    BalanceDef bd;
    bd.hold = holdMotor(0.0, config_.motor, JointMotor());
    bd.kp = config_.balance.kp;
    bd.kd = config_.balance.kd;
    bd.ankles = config_.balance.ankles;
    bd.feet = config_.balance.feet;
    r.balance = std::make_unique<BalanceController>(*world_, r.ragdoll, r.def, bd);
    if (log)
      for (const std::string& m : r.balance->missing())
        ROS_WARN("balance of '%s': %s not in the model; the joints hold their pose but the "
                 "balance law on the ankles is off (~balance/ankles, ~balance/feet)",
                 r.name.c_str(), m.c_str());
  }
  // Per-joint gains, URDF damping and the targets on top of what the controller set.
  applyAllMotors(r);
}

void SimNode::rebindControllers() {
  for (RagdollInstance& r : ragdolls_)
    if (r.balance_on) setBalance(r, true, /*log=*/false);
}

void SimNode::applyAllMotors(RagdollInstance& r) {
  for (int i = 0; i < r.axes.size(); ++i) applyAxisMotor(r, i);
}

void SimNode::applyAxisMotor(RagdollInstance& r, int i) {
  const AxisInfo& a = r.axes[i];
  const JointMotor passive = passiveMotor(r.def.joints[static_cast<size_t>(a.joint)], a.axis);
  const AxisTarget& t = r.targets[static_cast<size_t>(i)];
  JointMotor m = passive;
  if (t.active) {
    m = targetMotor(t, a, r.gains[static_cast<size_t>(i)], passive, simTime());
    const std::string bad = jointMotorError(m);
    if (!bad.empty()) {
      // Finite inputs that overflow on the way (1e308 rad moving at 1e308 rad/s on an
      // unlimited axis): the World would refuse the motor, so the target is dropped.
      warn("target/overflow", "ragdoll '" + r.name + "', joint '" + a.name + "': motor " + bad +
                                  "; the target is dropped");
      r.targets[static_cast<size_t>(i)].active = false;
      applyAxisMotor(r, i);
      return;
    }
    // The controller keeps its own ankle targets (its balance law adds to them).
    if (r.balance && t.has_position) r.balance->setTarget(*world_, a.name, m);
  } else if (r.balance) {
    m = holdMotor(0.0, r.gains[static_cast<size_t>(i)], passive);
    r.balance->setTarget(*world_, a.name, m);
  }
  world_->setJointMotor(r.ragdoll.joints[static_cast<size_t>(a.joint)], a.axis, m);
}

void SimNode::resetAll() {
  // A fresh world with every ragdoll at its spawn pose rejoins broken joints.
  for (RagdollInstance& r : ragdolls_) {
    r.forces.clear();
    r.prev_joint_ns = -1;
  }
  std::string error;
  if (!buildWorld(/*carry_state=*/false, &error)) ROS_ERROR("reset: %s", error.c_str());
  structureChanged();
}

int SimNode::findRagdoll(const std::string& name) const {
  if (name.empty()) return ragdolls_.empty() ? -1 : 0;
  for (size_t k = 0; k < ragdolls_.size(); ++k)
    if (ragdolls_[k].name == name) return static_cast<int>(k);
  return -1;
}

std::vector<RagdollView> SimNode::ragdollViews() const {
  std::vector<RagdollView> views;
  for (const RagdollInstance& r : ragdolls_) views.push_back({r.name, r.tf_prefix, &r.def, &r.ragdoll});
  return views;
}

void SimNode::structureChanged() {
  for (RagdollInstance& r : ragdolls_) {
    buildTf(r);
    buildJointState(r);
  }
  const std::vector<RagdollView> views = ragdollViews();
  if (visualizer_) visualizer_->setScene(*world_, views, ground_);
  if (interaction_) interaction_->setScene(world_.get(), views);
  buildLinkStates();
  last_publish_step_ = -1;  // publish the new set at once
}

}  // namespace node
}  // namespace ragdoll_sim
