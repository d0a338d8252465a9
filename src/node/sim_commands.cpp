// SimNode: the command topics. A command applies at once, or, when its header stamp lies in
// the future, at the start of the first step that begins at that sim time (CommandQueue).
#include <algorithm>

#include "msg_convert.hpp"
#include "sim_node.hpp"

namespace ragdoll_sim {
namespace node {

namespace {

// ragdoll name for messages: "'name'" or "the first ragdoll"
std::string which(const std::string& ragdoll) {
  return ragdoll.empty() ? std::string("the first ragdoll") : "ragdoll '" + ragdoll + "'";
}

}  // namespace

void SimNode::onImpulse(const ragdoll_sim::ApplyImpulse::ConstPtr& msg) {
  QueuedCommand q;
  q.ragdoll = msg->ragdoll;
  ImpulseCommand cmd;
  cmd.link = msg->link;
  cmd.frame = msg->frame;
  cmd.point = toVec(msg->point);
  cmd.impulse = toVec(msg->impulse);
  q.command = cmd;
  submit(std::move(q), msg->header.stamp, "impulse");
}

void SimNode::onForce(const ragdoll_sim::ApplyForce::ConstPtr& msg) {
  QueuedCommand q;
  q.ragdoll = msg->ragdoll;
  ForceCommand cmd;
  cmd.link = msg->link;
  cmd.frame = msg->frame;
  cmd.point = toVec(msg->point);
  cmd.force = toVec(msg->force);
  cmd.torque = toVec(msg->torque);
  cmd.duration = msg->duration;
  q.command = cmd;
  submit(std::move(q), msg->header.stamp, "force");
}

void SimNode::onTargetPose(const sensor_msgs::JointState::ConstPtr& msg) {
  // Names are "<joint>" (the first ragdoll) or "<ragdoll>/<joint>", one ragdoll per message.
  QueuedCommand q;
  TargetPoseCommand cmd;
  for (size_t i = 0; i < msg->name.size(); ++i) {
    std::string ragdoll, joint;
    splitQualifiedName(msg->name[i], [this](const std::string& n) { return findRagdoll(n) >= 0; },
                       &ragdoll, &joint);
    if (i > 0 && ragdoll != q.ragdoll) {
      ROS_WARN_THROTTLE(1.0, "target pose rejected: it names joints of %s and of %s (one ragdoll "
                        "per message); target pose dropped",
                        which(q.ragdoll).c_str(), which(ragdoll).c_str());
      return;
    }
    q.ragdoll = ragdoll;
    cmd.names.push_back(joint);
  }
  cmd.position = msg->position;
  cmd.velocity = msg->velocity;
  q.command = cmd;
  submit(std::move(q), msg->header.stamp, "target pose");
}

void SimNode::submit(QueuedCommand q, const ros::Time& stamp, const char* what) {
  if (findRagdoll(q.ragdoll) < 0) {
    ROS_WARN_THROTTLE(1.0, "%s rejected: unknown ragdoll '%s'%s; command dropped", what,
                      q.ragdoll.c_str(), ragdolls_.empty() ? " (no ragdolls left)" : "");
    return;
  }
  q.due_ns = commandDueNs(static_cast<int64_t>(stamp.toNSec()),
                          static_cast<int64_t>(stamp_origin_.toNSec()), sim_ns_);
  if (q.due_ns <= sim_ns_) {
    applyCommand(q);
    return;
  }
  const std::string ragdoll = q.ragdoll;
  if (!queue_.push(std::move(q))) {
    ROS_WARN_THROTTLE(1.0, "%s for %s rejected: %zu stamped commands are already waiting; "
                      "command dropped", what, which(ragdoll).c_str(), queue_.size());
    return;
  }
  ROS_DEBUG("%s queued for sim time %.6f s", what, static_cast<double>(stamp.toNSec() -
                                                                       stamp_origin_.toNSec()) * 1e-9);
}

void SimNode::applyDueCommands() {
  if (queue_.size() == 0) return;
  for (const QueuedCommand& q : queue_.takeDue(sim_ns_)) applyCommand(q);
}

void SimNode::applyCommand(const QueuedCommand& q) {
  const int k = findRagdoll(q.ragdoll);
  if (k < 0) {  // deleted while the command waited
    ROS_WARN_THROTTLE(1.0, "command for unknown ragdoll '%s' dropped", q.ragdoll.c_str());
    return;
  }
  RagdollInstance& r = ragdolls_[static_cast<size_t>(k)];
  if (const auto* c = std::get_if<ImpulseCommand>(&q.command)) applyImpulse(r, *c);
  else if (const auto* f = std::get_if<ForceCommand>(&q.command)) applyForce(r, *f);
  else if (const auto* t = std::get_if<TargetPoseCommand>(&q.command)) applyTargetPose(r, *t);
}

bool SimNode::applyImpulse(RagdollInstance& r, const ImpulseCommand& cmd) {
  auto pose = [&](int link) { return world_->bodyPose(r.ragdoll.bodies[static_cast<size_t>(link)]); };
  CommandCheck check = checkImpulse(cmd, r.links, limits_, pose);
  if (!check.ok) {
    ROS_WARN_THROTTLE(1.0, "%s (ragdoll '%s'); command dropped", check.error.c_str(), r.name.c_str());
    return false;
  }
  WorldImpulse w = toWorldImpulse(cmd, check, pose(check.link));
  world_->applyLinearImpulse(r.ragdoll.bodies[static_cast<size_t>(w.link)], w.impulse, w.point);
  visualizer_->addImpulse(*world_, r.ragdoll.bodies[static_cast<size_t>(w.link)], w.point,
                          w.impulse, simTime());
  ROS_DEBUG("impulse (%g, %g, %g) N*s on '%s/%s' at (%g, %g, %g), sim time %.6f s",
            w.impulse.x(), w.impulse.y(), w.impulse.z(), r.name.c_str(), cmd.link.c_str(),
            w.point.x(), w.point.y(), w.point.z(), simTime());
  return true;
}

size_t SimNode::activeForceCount() const {
  size_t n = 0;
  for (const RagdollInstance& r : ragdolls_) n += r.forces.size();
  return n;
}

bool SimNode::applyForce(RagdollInstance& r, const ForceCommand& cmd) {
  auto pose = [&](int link) { return world_->bodyPose(r.ragdoll.bodies[static_cast<size_t>(link)]); };
  CommandCheck check = checkForce(cmd, r.links, limits_, pose);
  if (!check.ok) {
    ROS_WARN_THROTTLE(1.0, "%s (ragdoll '%s'); command dropped", check.error.c_str(), r.name.c_str());
    return false;
  }
  if (activeForceCount() >= kMaxActiveForces) {
    ROS_WARN_THROTTLE(1.0, "force on '%s/%s' rejected: %zu forces are already active (call "
                      "~clear_forces)", r.name.c_str(), cmd.link.c_str(), activeForceCount());
    return false;
  }
  r.forces.push_back(toActiveForce(cmd, check, pose(check.link), dt_));
  const ActiveForce& f = r.forces.back();
  visualizer_->addForce(*world_, r.ragdoll.bodies[static_cast<size_t>(f.link)],
                        pose(f.link).apply(f.local_point), f.force, simTime(),
                        f.steps_left < 0 ? -1.0 : static_cast<double>(f.steps_left) * dt_);
  ROS_DEBUG("force on '%s/%s' for %lld steps from sim time %.6f s", r.name.c_str(),
            cmd.link.c_str(), static_cast<long long>(r.forces.back().steps_left), simTime());
  return true;
}

bool SimNode::applyTargetPose(RagdollInstance& r, const TargetPoseCommand& cmd) {
  const TargetPoseCheck check = checkTargetPose(cmd, r.axes);
  if (!check.ok) {
    ROS_WARN_THROTTLE(1.0, "%s (ragdoll '%s'); target pose dropped", check.error.c_str(),
                      r.name.c_str());
    return false;
  }
  if (!check.clamped.empty()) {
    std::string names;
    for (const std::string& n : check.clamped) names += (names.empty() ? "'" : ", '") + n + "'";
    ROS_WARN_THROTTLE(1.0, "target pose of '%s': %s outside the joint limits, clamped to them",
                      r.name.c_str(), names.c_str());
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
  ROS_DEBUG("target pose for %zu joint(s) of '%s'", check.axes.size(), r.name.c_str());
  return true;
}

}  // namespace node
}  // namespace ragdoll_sim
