// SimNode: the command topics. The callbacks only count and queue (CommandQueue, bounded); a
// command with a zero or past stamp is applied at the next loop iteration (also while paused),
// one stamped in the future at the start of the first step that begins at that sim time.
// Every received command ends up applied, rejected (a WARN throttled per problem kind names
// it) or dropped (the queue was full); ~stats publishes the counts.
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
  ++received_;
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
  ++received_;
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
  ++received_;
  QueuedCommand q;
  TargetPoseCommand cmd;
  for (size_t i = 0; i < msg->name.size(); ++i) {
    std::string ragdoll, joint;
    splitQualifiedName(msg->name[i], [this](const std::string& n) { return findRagdoll(n) >= 0; },
                       &ragdoll, &joint);
    if (i > 0 && ragdoll != q.ragdoll) {
      ++rejected_;
      warn("target pose/two ragdolls", "target pose rejected: it names joints of " +
                                           which(q.ragdoll) + " and of " + which(ragdoll) +
                                           " (one ragdoll per message); target pose dropped");
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
    ++rejected_;
    warn(std::string(what) + "/unknown ragdoll",
         std::string(what) + " rejected: unknown ragdoll '" + q.ragdoll + "'" +
             (ragdolls_.empty() ? " (no ragdolls left)" : "") + "; command dropped");
    return;
  }
  q.due_ns = commandDueNs(static_cast<int64_t>(stamp.toNSec()),
                          static_cast<int64_t>(stamp_origin_.toNSec()), sim_ns_);
  const int64_t due_ns = q.due_ns;
  const std::string ragdoll = q.ragdoll;
  if (!queue_.push(std::move(q))) {
    warn("queue full", std::string(what) + " for " + which(ragdoll) + " dropped: " +
                           std::to_string(queue_.size()) +
                           " commands are already waiting (~max_queued_commands); " +
                           std::to_string(queue_.dropped()) + " dropped so far");
    return;
  }
  if (due_ns > sim_ns_)
    ROS_DEBUG("%s queued for sim time %.6f s", what, static_cast<double>(due_ns) * 1e-9);
}

void SimNode::applyDueCommands() {
  if (queue_.size() == 0) return;
  for (const QueuedCommand& q : queue_.takeDue(sim_ns_)) applyCommand(q);
}

void SimNode::applyCommand(const QueuedCommand& q) {
  const int k = findRagdoll(q.ragdoll);
  bool applied = false;
  if (k < 0) {  // deleted while the command waited
    warn("command/deleted ragdoll", "command for ragdoll '" + q.ragdoll +
                                        "' dropped: the ragdoll was deleted while it waited");
  } else {
    RagdollInstance& r = ragdolls_[static_cast<size_t>(k)];
    if (const auto* c = std::get_if<ImpulseCommand>(&q.command))
      applied = applyImpulse(r, *c);
    else if (const auto* f = std::get_if<ForceCommand>(&q.command))
      applied = applyForce(r, *f);
    else if (const auto* t = std::get_if<TargetPoseCommand>(&q.command))
      applied = applyTargetPose(r, *t);
  }
  ++(applied ? applied_ : rejected_);
}

bool SimNode::applyImpulse(RagdollInstance& r, const ImpulseCommand& cmd) {
  auto pose = [&](int link) { return world_->bodyPose(r.ragdoll.bodies[static_cast<size_t>(link)]); };
  CommandCheck check = checkImpulse(cmd, r.links, limits_, pose);
  if (!check.ok) {
    warn("impulse/" + check.problem, check.error + " (ragdoll '" + r.name + "'); command dropped");
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
    warn("force/" + check.problem, check.error + " (ragdoll '" + r.name + "'); command dropped");
    return false;
  }
  if (activeForceCount() >= kMaxActiveForces) {
    warn("force/too many", "force on '" + r.name + "/" + cmd.link + "' rejected: " +
                               std::to_string(activeForceCount()) +
                               " forces are already active (call ~clear_forces)");
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
  ROS_DEBUG("target pose for %zu joint(s) of '%s'", check.axes.size(), r.name.c_str());
  return true;
}

}  // namespace node
}  // namespace ragdoll_sim
