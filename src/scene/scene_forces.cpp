// Scene: timed forces. A force command that passes its checks becomes an ActiveForce of its
// ragdoll, re-applied every step until its duration is over. Two budgets keep one publisher from
// taking the forces of every other ragdoll: SceneDef::max_forces_per_ragdoll per ragdoll and
// SceneDef::max_active_forces over all of them. Each step the forces and torques on one link
// add up to at most CommandLimits::max_body_force / max_body_torque (the sum of magnitudes, so
// opposing forces cannot cancel their way past it): beyond, all of them are scaled down alike.
#include <algorithm>

#include "scene_impl.hpp"

namespace ragdoll_sim {

using scene::ActiveForce;
using scene::CommandCheck;
using scene::RagdollInstance;

size_t Scene::Impl::activeForceCount() const {
  size_t n = 0;
  for (const RagdollInstance& r : ragdolls) n += r.forces.size();
  return n;
}

bool Scene::Impl::applyForce(RagdollInstance& r, const ForceCommand& cmd,
                             const CommandCheck& link) {
  auto pose = [&](int link) { return world->bodyPose(r.ragdoll.bodies[static_cast<size_t>(link)]); };
  CommandCheck check = checkForce(cmd, link, def.limits, pose);
  if (!check.ok) {
    warn("force/" + check.problem, check.error + " (ragdoll '" + r.name + "'); command dropped");
    return false;
  }
  const std::string what = "force on '" + r.name + "/" + cmd.link + "' rejected: ";
  if (r.forces.size() >= static_cast<size_t>(def.max_forces_per_ragdoll)) {
    warn("force/too many on one ragdoll",
         what + "ragdoll '" + r.name + "' already has " + std::to_string(r.forces.size()) +
             " active forces (max_forces_per_ragdoll; call ~clear_forces)");
    return false;
  }
  const size_t active = activeForceCount();
  if (active >= static_cast<size_t>(def.max_active_forces)) {
    warn("force/too many", what + std::to_string(active) +
                               " forces are already active on all ragdolls (max_active_forces; "
                               "call ~clear_forces)");
    return false;
  }
  r.forces.push_back(toActiveForce(cmd, check, pose(check.link), dt));
  r.forces_capped_said = false;
  ++forces;
  const ActiveForce& f = r.forces.back();
  if (listener)
    listener->forceApplied(*world, r.ragdoll.bodies[static_cast<size_t>(f.link)],
                           pose(f.link).apply(f.local_point), f.force, simTime(),
                           f.steps_left < 0 ? -1.0 : static_cast<double>(f.steps_left) * dt);
  debug(scene::format("force on '%s/%s' for %lld steps from sim time %.6f s", r.name.c_str(),
                      cmd.link.c_str(), static_cast<long long>(f.steps_left), simTime()));
  return true;
}

void Scene::Impl::applyActiveForces(RagdollInstance& r) {
  if (r.forces.empty()) return;
  const CommandLimits& lim = def.limits;
  force_sum.assign(r.ragdoll.bodies.size(), 0.0);
  torque_sum.assign(r.ragdoll.bodies.size(), 0.0);
  for (const ActiveForce& f : r.forces) {
    force_sum[static_cast<size_t>(f.link)] += f.force.norm();
    torque_sum[static_cast<size_t>(f.link)] += f.torque.norm();
  }
  // Per link the factor that brings each sum down to its cap (1 when under it).
  bool capped = false;
  for (size_t l = 0; l < force_sum.size(); ++l) {
    const double fs = force_sum[l], ts = torque_sum[l];
    if (fs <= lim.max_body_force && ts <= lim.max_body_torque) {
      force_sum[l] = torque_sum[l] = 1.0;
      continue;
    }
    force_sum[l] = fs > lim.max_body_force ? lim.max_body_force / fs : 1.0;
    torque_sum[l] = ts > lim.max_body_torque ? lim.max_body_torque / ts : 1.0;
    capped = true;
    if (r.forces_capped_said) continue;  // said once per set of forces, not every step
    warn("force/body cap",
         scene::format("the active forces on '%s/%s' add up to %g N and %g N m (sums of "
                       "magnitudes), above max_body_force = %g N or max_body_torque = %g N m: "
                       "scaled down to the cap",
                       r.name.c_str(), r.def.links[l].name.c_str(), fs, ts, lim.max_body_force,
                       lim.max_body_torque));
  }
  r.forces_capped_said = capped;
  for (const ActiveForce& f : r.forces) {
    const size_t l = static_cast<size_t>(f.link);
    const BodyId body = r.ragdoll.bodies[l];
    world->applyForce(body, f.force * force_sum[l], world->bodyPose(body).apply(f.local_point));
    if (!f.torque.isZero(0.0)) world->applyTorque(body, f.torque * torque_sum[l]);
  }
}

void Scene::Impl::expireForces(RagdollInstance& r) {
  if (r.forces.empty()) return;
  for (ActiveForce& f : r.forces)
    if (f.steps_left > 0) --f.steps_left;
  const size_t before = r.forces.size();
  r.forces.erase(std::remove_if(r.forces.begin(), r.forces.end(),
                                [](const ActiveForce& f) { return f.steps_left == 0; }),
                 r.forces.end());
  if (r.forces.size() != before) r.forces_capped_said = false;
}

size_t Scene::activeForceCount() const { return impl_->activeForceCount(); }

size_t Scene::clearForces() {
  const size_t n = impl_->activeForceCount() + impl_->activeEffortCount();
  for (RagdollInstance& r : impl_->ragdolls) {
    r.forces.clear();
    r.efforts.clear();
  }
  return n;
}

}  // namespace ragdoll_sim
