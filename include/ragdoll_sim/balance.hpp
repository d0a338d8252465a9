// Active ragdoll: joint motors hold a pose (the rest pose unless targets are set) and a balance law
// on the ankles keeps the body over its feet: the body is an inverted pendulum standing on the
// ankles, so each ankle's target angle leans it back towards the support with a PD law on the
// centre of mass,
//   target = kp (c - s) . f + kd v_c . f,
// c, v_c: centre of mass and its velocity, s: centre of the feet, f: the ankle's forward
// direction (its hinge axis x up; the sign follows the URDF axis).
#pragma once

#include <string>
#include <vector>

#include "ragdoll_sim/ragdoll.hpp"

namespace ragdoll_sim {

struct BalanceDef {
  JointMotor hold = {true, 0.0, 0.0, 120.0, 1.0, 5000.0, 0.0};  // motor on every joint angle
  double kp = 2.0;    // rad per m of centre-of-mass offset
  double kd = 0.5;    // rad per m/s of centre-of-mass velocity
  std::vector<std::string> ankles = {"ankle_l", "ankle_r"};  // hinge joints, by name
  std::vector<std::string> feet = {"foot_l", "foot_r"};       // support links
};

class BalanceController {
 public:
  // Enables the hold motors on every joint of the ragdoll. Unknown ankle / foot names are
  // listed in missing() and leave the balance law off.
  BalanceController(World& world, const Ragdoll& ragdoll, const RagdollDef& def,
                    const BalanceDef& balance = BalanceDef());
  // Call before each World::step.
  void update(World& world);
  // Sets the motor (gains, and target = the held angle) of one URDF revolute joint (a hinge,
  // or one axis of a ball chain); an ankle keeps these gains under the balance law.
  bool setTarget(World& world, const std::string& urdf_joint, const JointMotor& motor);
  // The motor the balance law drives an ankle with (its gains; the target is the law's).
  const JointMotor& ankleMotor(size_t i) const { return ankle_motors_.at(i); }
  const std::vector<std::string>& missing() const { return missing_; }

 private:
  const Ragdoll& ragdoll_;
  const RagdollDef& def_;
  BalanceDef balance_;
  std::vector<double> masses_;
  std::vector<int> ankles_;   // RagdollDef joint indices
  std::vector<BodyId> feet_;
  std::vector<JointMotor> ankle_motors_;  // gains and base target of each ankle
  std::vector<std::string> missing_;
};

}  // namespace ragdoll_sim
