// Sleep: the rest substeps of slow islands, islands going to sleep, and World::setSleep.
// Data: sleep.hpp.
#include <algorithm>

#include "world_impl.hpp"

namespace ragdoll_sim {

// Every body of r has been slow for rest_time (SleepDef::rest_substeps), and none sped up on
// the rest substeps since it last slept: a pose that only the full substeps hold (a foot wedged
// between the ground and its own shin) would otherwise slip on the rest substeps, take the full
// ones until slow again, and so on, awake for ever.
bool World::Impl::islandResting(const IslandRange& r) const {
  for (int k = r.body_begin; k < r.body_end; ++k) {
    const BodyMotion& m = motions[island_bodies[k]];
    if (!(m.sleep_time >= def.sleep.rest_time) || m.rest_failed) return false;
  }
  return true;
}

// A split island's halves and the islands attached to them share one substep loop: they rest
// together or not at all, as the split island decides.
void World::Impl::markResting(bool rest_mode) {
  const int* const attached = attached_islands.data();
  for (IslandRange& r : island_ranges) {
    if (r.attached) continue;
    r.resting = rest_mode && islandResting(r);
    if (!r.split) continue;
    for (int a = r.attach[0]; a < r.attach[2]; ++a)
      r.resting = r.resting && islandResting(island_ranges[attached[a]]);
    for (int a = r.attach[0]; a < r.attach[2]; ++a) island_ranges[attached[a]].resting = r.resting;
  }
}

void World::Impl::updateSleep(double dt) {
  if (!def.sleep.enabled) return;
  // Per-body arrays are reset at the dynamic bodies only (island roots are dynamic bodies).
  const int n = int(bodies.size());
  // Per island root: twice its kinetic energy and its mass (the energy rule, SleepDef).
  const double island_speed = def.sleep.island_speed;
  if (island_speed > 0.0) {
    island_energy.resize(n);
    island_mass.resize(n);
    for (const int i : dynamic_bodies) island_energy[i] = island_mass[i] = 0.0;
    for (const int i : dynamic_bodies) {
      const BodyMotion& m = motions[i];
      if (!m.awake || !(m.inv_mass > 0.0)) continue;
      const int root = islands.find(i);
      const Vec3 wl = m.q.conjugate() * m.w;
      island_energy[root] += m.v.squaredNorm() / m.inv_mass + wl.dot(m.inertia_local * wl);
      island_mass[root] += 1.0 / m.inv_mass;
    }
  }
  // island root's sleep_time becomes the island minimum (roots have the smallest index)
  std::vector<double>& slow = island_slow;
  slow.resize(n);
  for (const int i : dynamic_bodies) slow[i] = 1e300;
  for (const int i : dynamic_bodies) {
    BodyMotion& m = motions[i];
    if (!m.awake) continue;
    const int root = islands.find(i);
    const double speed = std::max(m.v.norm(), m.extent * m.w.norm());  // as Box2D v3
    const bool island_calm =
        island_speed > 0.0 && island_energy[root] < island_mass[root] * island_speed * island_speed;
    const bool slow_now = speed < def.sleep.speed || island_calm;
    if (!slow_now && island_of_body[i] >= 0 && island_ranges[island_of_body[i]].resting)
      m.rest_failed = true;
    m.sleep_time = slow_now ? m.sleep_time + dt : 0.0;
    double& r = slow[root];
    r = std::min(r, m.sleep_time);
  }
  for (const int i : dynamic_bodies) {
    BodyMotion& m = motions[i];
    if (!m.awake || slow[islands.find(i)] < def.sleep.time) continue;
    m.awake = false;
    m.rest_failed = false;
    m.v.setZero();
    m.w.setZero();
    schedule_fresh = false;
  }
}

void World::setSleep(const SleepDef& sleep) {
  const std::string e = sleepDefError(sleep);
  if (!e.empty()) throw std::invalid_argument("ragdoll_sim: setSleep: " + e);
  Impl& w = *impl_;
  if (sleep.enabled != w.def.sleep.enabled) {
    // Slow times stood still while sleep was off (updateSleep); a body asleep when it is
    // turned off must move again.
    for (size_t i = 0; i < w.bodies.size(); ++i) {
      if (!w.bodies[i].alive) continue;
      if (!sleep.enabled && !w.motions[i].awake && w.isDynamic(int(i))) w.wake(int(i));
      w.motions[i].sleep_time = 0.0;
    }
  }
  w.def.sleep = sleep;
}

}  // namespace ragdoll_sim
