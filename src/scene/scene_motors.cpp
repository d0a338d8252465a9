// Scene: joint motors from targets (fixed and moving) and the balance controllers.
#include <algorithm>

#include "scene_impl.hpp"

namespace ragdoll_sim {

using scene::AxisInfo;
using scene::AxisTarget;
using scene::RagdollInstance;

void Scene::Impl::setBalance(RagdollInstance& r, bool on, bool log) {
  r.balance_on = on && !r.object;  // a crate has nothing to balance
  r.balance.reset();
  if (on) {
    BalanceDef bd = def.balance;
    bd.hold = scene::holdMotor(0.0, def.motor, JointMotor());
    r.balance = std::make_unique<BalanceController>(*world, r.ragdoll, r.def, bd);
    if (log)
      for (const std::string& m : r.balance->missing())
        warn("", scene::format("balance of '%s': %s not in the model; the joints hold their pose "
                               "but the balance law on the ankles is off (~balance/ankles, "
                               "~balance/feet)",
                               r.name.c_str(), m.c_str()));
  }
  // Per-joint gains, URDF damping and the targets on top of what the controller set.
  applyAllMotors(r);
}

void Scene::Impl::rebindControllers() {
  for (RagdollInstance& r : ragdolls)
    if (r.balance_on) setBalance(r, true, /*log=*/false);
}

void Scene::Impl::applyAllMotors(RagdollInstance& r) {
  for (int i = 0; i < r.axes.size(); ++i) applyAxisMotor(r, i);
}

void Scene::Impl::applyAxisMotor(RagdollInstance& r, int i) {
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
    if (r.balance && t.has_position) r.balance->setTarget(*world, a.name, m);
  } else if (r.balance) {
    m = scene::holdMotor(0.0, r.gains[static_cast<size_t>(i)], passive);
    r.balance->setTarget(*world, a.name, m);
  }
  world->setJointMotor(r.ragdoll.joints[static_cast<size_t>(a.joint)], a.axis, m);
}

bool Scene::Impl::applyTargetPose(RagdollInstance& r, const TargetPoseCommand& cmd) {
  const scene::TargetPoseCheck check = checkTargetPose(cmd, r.axes);
  if (!check.ok) {
    warn("target pose/" + check.problem,
         check.error + " (ragdoll '" + r.name + "'); target pose dropped");
    return false;
  }
  if (!check.clamped.empty()) {
    std::string names;
    for (const std::string& n : check.clamped) names += (names.empty() ? "'" : ", '") + n + "'";
    warn("target pose/clamped", "target pose of '" + r.name + "': " + names +
                                    " outside the joint limits, clamped to them");
  }
  for (const auto& [axis, target] : toAxisTargets(cmd, check, simTime())) {
    r.targets[static_cast<size_t>(axis)] = target;
    applyAxisMotor(r, axis);
  }
  r.moving_targets.clear();
  for (int i = 0; i < r.axes.size(); ++i) {
    const AxisTarget& t = r.targets[static_cast<size_t>(i)];
    if (t.active && t.has_position && t.velocity != 0.0) r.moving_targets.push_back(i);
  }
  debug(scene::format("target pose for %zu joint(s) of '%s'", check.axes.size(), r.name.c_str()));
  return true;
}

void Scene::clearTargets() {
  for (RagdollInstance& r : impl_->ragdolls) {
    r.targets.assign(r.targets.size(), AxisTarget());
    r.moving_targets.clear();
    impl_->applyAllMotors(r);
  }
}

void Scene::setBalance(bool on) {
  for (RagdollInstance& r : impl_->ragdolls) impl_->setBalance(r, on, /*log=*/true);
}

}  // namespace ragdoll_sim
