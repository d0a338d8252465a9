#include "command_topics.hpp"

#include "command_queue.hpp"
#include "commands.hpp"
#include "msg_convert.hpp"
#include "node_context.hpp"

namespace ragdoll_sim {
namespace node {

namespace {

// ragdoll name for messages: "'name'" or "the first ragdoll"
std::string which(const std::string& ragdoll) {
  return ragdoll.empty() ? std::string("the first ragdoll") : "ragdoll " + scene::quoted(ragdoll);
}

}  // namespace

CommandTopics::CommandTopics(NodeContext& ctx) : ctx_(ctx) {
  const ros::TransportHints no_delay = ros::TransportHints().tcpNoDelay();
  target_sub_ = ctx_.pnh.subscribe("target_pose", kQueue, &CommandTopics::onTargetPose, this,
                                   no_delay);
  impulse_sub_ = ctx_.pnh.subscribe("apply_impulse", kQueue, &CommandTopics::onImpulse, this,
                                    no_delay);
  force_sub_ = ctx_.pnh.subscribe("apply_force", kQueue, &CommandTopics::onForce, this, no_delay);
  effort_sub_ = ctx_.pnh.subscribe("joint_effort", kQueue, &CommandTopics::onJointEffort, this,
                                   no_delay);
}

void CommandTopics::onImpulse(const ragdoll_sim::ApplyImpulse::ConstPtr& msg) {
  ImpulseCommand cmd;
  cmd.link = msg->link;
  cmd.frame = msg->frame;
  cmd.point = toVec(msg->point);
  cmd.impulse = toVec(msg->impulse);
  submit(msg->ragdoll, cmd, msg->header.stamp);
}

void CommandTopics::onForce(const ragdoll_sim::ApplyForce::ConstPtr& msg) {
  ForceCommand cmd;
  cmd.link = msg->link;
  cmd.frame = msg->frame;
  cmd.point = toVec(msg->point);
  cmd.force = toVec(msg->force);
  cmd.torque = toVec(msg->torque);
  cmd.duration = msg->duration;
  submit(msg->ragdoll, cmd, msg->header.stamp);
}

bool CommandTopics::splitNames(const sensor_msgs::JointState& msg, const std::string& kind,
                               std::string* ragdoll, std::vector<std::string>* joints) {
  const Scene& scene = *ctx_.scene;
  ragdoll->clear();
  for (size_t i = 0; i < msg.name.size(); ++i) {
    std::string r, joint;
    scene::splitQualifiedName(msg.name[i], [&](const std::string& n) { return scene.find(n) >= 0; },
                              &r, &joint);
    if (i > 0 && r != *ragdoll) {
      ctx_.scene->reject(kind + "/two ragdolls",
                         kind + " rejected: it names joints of " + which(*ragdoll) + " and of " +
                             which(r) + " (one ragdoll per message); " + kind + " dropped");
      return false;
    }
    *ragdoll = r;
    joints->push_back(joint);
  }
  return true;
}

void CommandTopics::onTargetPose(const sensor_msgs::JointState::ConstPtr& msg) {
  std::string ragdoll;
  TargetPoseCommand cmd;
  if (!splitNames(*msg, "target pose", &ragdoll, &cmd.names)) return;
  cmd.position = msg->position;
  cmd.velocity = msg->velocity;
  submit(ragdoll, cmd, msg->header.stamp);
}

void CommandTopics::onJointEffort(const sensor_msgs::JointState::ConstPtr& msg) {
  // `effort` only; the Scene checks names, lengths, NaN and the caps when it applies it.
  std::string ragdoll;
  JointEffortCommand cmd;
  if (!splitNames(*msg, "joint effort", &ragdoll, &cmd.names)) return;
  cmd.efforts = msg->effort;
  cmd.duration = ctx_.config.joint_effort_duration;
  submit(ragdoll, cmd, msg->header.stamp);
}

void CommandTopics::submit(const std::string& ragdoll, SceneCommandVariant command,
                           const ros::Time& stamp) {
  const int64_t due = scene::commandDueNs(static_cast<int64_t>(stamp.toNSec()),
                                          ctx_.clock.originNs(), ctx_.scene->timeNs());
  ctx_.scene->submit(ragdoll, std::move(command), due);
}

}  // namespace node
}  // namespace ragdoll_sim
