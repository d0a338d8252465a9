// Scene: the queue of stamped commands. A command names its ragdoll and link, resolved once
// when it is submitted; it waits until its sim time and is then checked and applied, or
// rejected (a WARN throttled per problem kind names it), or dropped when the queue is full.
// The counters keep received = applied + rejected + dropped + queued.
#include "scene_impl.hpp"

namespace ragdoll_sim {

using scene::ActiveForce;
using scene::CommandCheck;
using scene::QueuedCommand;
using scene::RagdollInstance;

namespace {

// ragdoll name for messages: "'name'" or "the first ragdoll"
std::string which(const std::string& ragdoll) {
  return ragdoll.empty() ? std::string("the first ragdoll") : "ragdoll " + scene::quoted(ragdoll);
}

const char* what(const SceneCommandVariant& c) {
  if (std::holds_alternative<ImpulseCommand>(c)) return "impulse";
  if (std::holds_alternative<ForceCommand>(c)) return "force";
  if (std::holds_alternative<JointEffortCommand>(c)) return "joint effort";
  return "target pose";
}

}  // namespace

bool Scene::submit(const std::string& ragdoll, SceneCommandVariant command, int64_t due_ns) {
  Impl& s = *impl_;
  ++s.received;
  const std::string kind = what(command);
  const int k = s.find(ragdoll);
  if (k < 0) {
    ++s.rejected;
    s.warn(kind + "/unknown ragdoll",
           kind + " rejected: unknown ragdoll " + scene::quoted(ragdoll) +
               (s.ragdolls.empty() ? " (no ragdolls left)" : "") + "; command dropped");
    return false;
  }
  const RagdollInstance& r = s.ragdolls[static_cast<size_t>(k)];
  QueuedCommand q;
  q.ragdoll = ragdoll;
  q.ragdoll_id = r.id;
  if (const auto* c = std::get_if<ImpulseCommand>(&command))
    q.link = scene::resolveImpulseLink(*c, r.links);
  else if (const auto* f = std::get_if<ForceCommand>(&command))
    q.link = scene::resolveForceLink(*f, r.links);
  q.command = std::move(command);
  q.due_ns = due_ns;
  if (!s.queue.push(std::move(q))) {
    s.warn("queue full", kind + " for " + which(ragdoll) + " dropped: " +
                             std::to_string(s.queue.size()) +
                             " commands are already waiting (~max_queued_commands); " +
                             std::to_string(s.queue.dropped()) + " dropped so far");
    return false;
  }
  if (due_ns > s.sim_ns)
    s.debug(scene::format("%s queued for sim time %.6f s", kind.c_str(),
                          static_cast<double>(due_ns) * 1e-9));
  return true;
}

void Scene::reject(const std::string& kind, const std::string& text) {
  ++impl_->received;
  ++impl_->rejected;
  impl_->warn(kind, text);
}

void Scene::applyDueCommands() {
  if (impl_->queue.size() == 0) return;
  for (const QueuedCommand& q : impl_->queue.takeDue(impl_->sim_ns)) impl_->applyCommand(q);
}

void Scene::Impl::applyCommand(const QueuedCommand& q) {
  int k = -1;
  for (size_t i = 0; i < ragdolls.size(); ++i)
    if (ragdolls[i].id == q.ragdoll_id) k = static_cast<int>(i);
  bool ok = false;
  if (k < 0) {  // removed while the command waited
    warn("command/deleted ragdoll", "command for ragdoll '" + q.ragdoll +
                                        "' dropped: the ragdoll was deleted while it waited");
  } else {
    RagdollInstance& r = ragdolls[static_cast<size_t>(k)];
    if (const auto* c = std::get_if<ImpulseCommand>(&q.command))
      ok = applyImpulse(r, *c, q.link);
    else if (const auto* f = std::get_if<ForceCommand>(&q.command))
      ok = applyForce(r, *f, q.link);
    else if (const auto* t = std::get_if<TargetPoseCommand>(&q.command))
      ok = applyTargetPose(r, *t);
    else if (const auto* e = std::get_if<JointEffortCommand>(&q.command))
      ok = applyJointEffort(r, *e);
  }
  ++(ok ? applied : rejected);
}

bool Scene::Impl::applyImpulse(RagdollInstance& r, const ImpulseCommand& cmd,
                               const CommandCheck& link) {
  auto pose = [&](int link) { return world->bodyPose(r.ragdoll.bodies[static_cast<size_t>(link)]); };
  CommandCheck check = checkImpulse(cmd, link, def.limits, pose);
  if (!check.ok) {
    warn("impulse/" + check.problem, check.error + " (ragdoll '" + r.name + "'); command dropped");
    return false;
  }
  scene::WorldImpulse w = toWorldImpulse(cmd, check, pose(check.link));
  const BodyId body = r.ragdoll.bodies[static_cast<size_t>(w.link)];
  world->applyLinearImpulse(body, w.impulse, w.point);
  ++impulses;
  if (listener) listener->impulseApplied(*world, body, w.point, w.impulse, simTime());
  debug(scene::format("impulse (%g, %g, %g) N*s on '%s/%s' at (%g, %g, %g), sim time %.6f s",
                      w.impulse.x(), w.impulse.y(), w.impulse.z(), r.name.c_str(),
                      cmd.link.c_str(), w.point.x(), w.point.y(), w.point.z(), simTime()));
  return true;
}

SceneCounters Scene::counters() const {
  const Impl& s = *impl_;
  SceneCounters c;
  c.received = s.received;
  c.applied = s.applied;
  c.rejected = s.rejected;
  c.dropped = s.queue.dropped();
  c.body_faults = s.body_faults;
  c.impulses = s.impulses;
  c.forces = s.forces;
  c.active_forces = s.activeForceCount();
  c.queued = s.queue.size();
  c.max_queued = s.queue.maxSize();
  c.queue_capacity = s.queue.capacity();
  return c;
}

}  // namespace ragdoll_sim
