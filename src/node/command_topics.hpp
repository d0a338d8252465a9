// The command topics ~apply_impulse, ~apply_force, ~target_pose and ~joint_effort: each
// message becomes one
// Scene command, due at the sim time of its stamp (a zero or past stamp: at the next loop
// iteration, also while paused). The Scene resolves its ragdoll on receipt, queues it
// (bounded), applies or rejects it when due and counts it (~stats).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <sensor_msgs/JointState.h>

#include "ragdoll_sim/ApplyForce.h"
#include "ragdoll_sim/ApplyImpulse.h"
#include "ragdoll_sim/scene.hpp"

namespace ragdoll_sim {
namespace node {

struct NodeContext;

class CommandTopics {
 public:
  explicit CommandTopics(NodeContext& ctx);

 private:
  void onImpulse(const ragdoll_sim::ApplyImpulse::ConstPtr& msg);
  void onForce(const ragdoll_sim::ApplyForce::ConstPtr& msg);
  void onTargetPose(const sensor_msgs::JointState::ConstPtr& msg);
  void onJointEffort(const sensor_msgs::JointState::ConstPtr& msg);
  // Names "<joint>" (the first ragdoll) or "<ragdoll>/<joint>", one ragdoll per message: false
  // (rejected with a WARN of kind "<kind>/two ragdolls") when it names two.
  bool splitNames(const sensor_msgs::JointState& msg, const std::string& kind,
                  std::string* ragdoll, std::vector<std::string>* joints);
  void submit(const std::string& ragdoll, SceneCommandVariant command, const ros::Time& stamp);

  // roscpp's queue per command topic: the callbacks only queue, so it holds what arrives
  // during one loop iteration or one long service call (0.1 s at 10 kHz).
  static constexpr uint32_t kQueue = 1000;
  NodeContext& ctx_;
  ros::Subscriber target_sub_, impulse_sub_, force_sub_, effort_sub_;
};

}  // namespace node
}  // namespace ragdoll_sim
