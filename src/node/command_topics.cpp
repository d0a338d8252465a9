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

void CommandTopics::onTargetPose(const sensor_msgs::JointState::ConstPtr& msg) {
  // Names are "<joint>" (the first ragdoll) or "<ragdoll>/<joint>", one ragdoll per message.
  const Scene& scene = *ctx_.scene;
  std::string first;
  TargetPoseCommand cmd;
  for (size_t i = 0; i < msg->name.size(); ++i) {
    std::string ragdoll, joint;
    scene::splitQualifiedName(msg->name[i],
                              [&](const std::string& n) { return scene.find(n) >= 0; }, &ragdoll,
                              &joint);
    if (i > 0 && ragdoll != first) {
      ctx_.scene->reject("target pose/two ragdolls",
                         "target pose rejected: it names joints of " + which(first) + " and of " +
                             which(ragdoll) + " (one ragdoll per message); target pose dropped");
      return;
    }
    first = ragdoll;
    cmd.names.push_back(joint);
  }
  cmd.position = msg->position;
  cmd.velocity = msg->velocity;
  submit(first, cmd, msg->header.stamp);
}

void CommandTopics::submit(const std::string& ragdoll, SceneCommandVariant command,
                           const ros::Time& stamp) {
  const int64_t due = scene::commandDueNs(static_cast<int64_t>(stamp.toNSec()),
                                          ctx_.clock.originNs(), ctx_.scene->timeNs());
  ctx_.scene->submit(ragdoll, std::move(command), due);
}

}  // namespace node
}  // namespace ragdoll_sim
