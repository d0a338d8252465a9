#include "ragdoll_sim/balance.hpp"

#include <cmath>

namespace ragdoll_sim {

BalanceController::BalanceController(World& world, const Ragdoll& ragdoll, const RagdollDef& def,
                                     const BalanceDef& balance)
    : ragdoll_(ragdoll), def_(def), balance_(balance) {
  for (const LinkDef& l : def.links) masses_.push_back(l.mass);
  for (size_t k = 0; k < def.joints.size(); ++k) {
    const int axes = jointAxisCount(def.joints[k].kind);
    for (int a = 0; a < axes; ++a) world.setJointMotor(ragdoll.joints[k], a, balance.hold);
  }
  for (const std::string& name : balance.ankles) {
    int found = -1;
    for (size_t k = 0; k < def.joints.size(); ++k)
      if (def.joints[k].kind == RagdollJointKind::Hinge && def.joints[k].name == name) found = int(k);
    if (found < 0) missing_.push_back("ankle joint '" + name + "'");
    else ankles_.push_back(found);
  }
  for (const std::string& name : balance.feet) {
    const int l = def.findLink(name);
    if (l < 0) missing_.push_back("foot link '" + name + "'");
    else feet_.push_back(ragdoll.bodies[l]);
  }
  ankle_motors_.assign(ankles_.size(), balance.hold);
  if (!missing_.empty()) ankles_.clear();
}

bool BalanceController::setTarget(World& world, const std::string& urdf_joint, const JointMotor& motor) {
  for (size_t k = 0; k < def_.joints.size(); ++k) {
    const auto& names = def_.joints[k].source_joints;
    for (size_t a = 0; a < names.size(); ++a) {
      if (names[a] != urdf_joint) continue;
      for (size_t i = 0; i < ankles_.size(); ++i)
        if (ankles_[i] == int(k)) ankle_motors_[i] = motor;
      world.setJointMotor(ragdoll_.joints[k], int(a), motor);
      return true;
    }
  }
  return false;
}

void BalanceController::update(World& world) {
  if (ankles_.empty() || feet_.empty()) return;
  Vec3 c = Vec3::Zero(), v = Vec3::Zero(), s = Vec3::Zero();
  double total = 0.0;
  for (size_t i = 0; i < ragdoll_.bodies.size(); ++i) {
    c += masses_[i] * world.comPosition(ragdoll_.bodies[i]);
    v += masses_[i] * world.bodyState(ragdoll_.bodies[i]).linear_velocity;
    total += masses_[i];
  }
  c /= total;
  v /= total;
  for (BodyId f : feet_) s += world.comPosition(f);
  s /= double(feet_.size());
  for (size_t i = 0; i < ankles_.size(); ++i) {
    const RagdollJointDef& j = def_.joints[ankles_[i]];
    const Transform parent = world.bodyPose(ragdoll_.bodies[j.parent]);
    const Vec3 axis = parent.q * (j.frame_parent.q * j.axes[0]);
    Vec3 forward = axis.cross(Vec3::UnitZ());
    forward.z() = 0.0;
    if (forward.norm() < 1e-6) continue;
    forward.normalize();
    JointMotor m = ankle_motors_[i];
    m.target = ankle_motors_[i].target + balance_.kp * (c - s).dot(forward) + balance_.kd * v.dot(forward);
    if (!std::isfinite(m.target)) continue;  // gains so large that the law overflows: keep the last
    world.setJointMotor(ragdoll_.joints[ankles_[i]], 0, m);
  }
}

}  // namespace ragdoll_sim
