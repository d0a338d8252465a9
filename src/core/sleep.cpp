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

// The sleep rule for one island, its awake bodies ids[0, n) in ascending order (the order the
// energy is summed in). A body the solver left faulted is at rest, as resetFaulted leaves it
// after this (its state may be non-finite, so it is not read). True when the island went to
// sleep.
bool World::Impl::sleepIsland(const int* ids, int n, bool resting, double dt) {
  const double island_speed = def.sleep.island_speed;
  // Twice the kinetic energy (m |v|^2 + w.I.w) and the mass (the energy rule, SleepDef).
  double energy = 0.0, mass = 0.0;
  if (island_speed > 0.0)
    for (int k = 0; k < n; ++k) {
      const BodyMotion& m = motions[ids[k]];
      if (!(m.inv_mass > 0.0)) continue;
      mass += 1.0 / m.inv_mass;
      if (solver_fault[ids[k]]) continue;
      const Vec3 wl = m.q.conjugate() * m.w;
      energy += m.v.squaredNorm() / m.inv_mass + wl.dot(m.inertia_local * wl);
    }
  const bool calm = island_speed > 0.0 && energy < mass * island_speed * island_speed;
  double slow = 1e300;  // the island's shortest slow time
  for (int k = 0; k < n; ++k) {
    BodyMotion& m = motions[ids[k]];
    const double speed =  // as Box2D v3
        solver_fault[ids[k]] ? 0.0 : std::max(m.v.norm(), m.extent * m.w.norm());
    const bool slow_now = speed < def.sleep.speed || calm;
    if (!slow_now && resting) m.rest_failed = true;
    m.sleep_time = slow_now ? m.sleep_time + dt : 0.0;
    slow = std::min(slow, m.sleep_time);
  }
  if (slow < def.sleep.time) return false;
  for (int k = 0; k < n; ++k) {
    BodyMotion& m = motions[ids[k]];
    m.awake = false;
    m.rest_failed = false;
    m.v.setZero();
    m.w.setZero();
  }
  return true;
}

// On the thread that finished them: the whole islands of range p (not a split island's half).
void World::Impl::sleepIslands(const IslandRange& p, double dt) {
  if (!def.sleep.enabled) return;
  forIslands(p, [&](const IslandRange& q) {
    if (sleepIsland(island_bodies.data() + q.body_begin, q.body_end - q.body_begin, q.resting, dt))
      islands_slept.store(true, std::memory_order_relaxed);
  });
}

// After the solve: the split islands (their bodies sorted back into ascending order) and the
// islands attached to their halves; the other islands went to sleep or not on their threads.
void World::Impl::updateSleep(double dt) {
  if (!def.sleep.enabled) return;
  bool slept = islands_slept.exchange(false, std::memory_order_relaxed);
  for (const IslandRange& r : island_ranges) {
    if (!r.split && !r.attached) continue;
    const int n = r.body_end - r.body_begin;
    const int* ids = island_bodies.data() + r.body_begin;
    if (r.split) {
      sleep_order.assign(ids, ids + n);
      std::sort(sleep_order.begin(), sleep_order.end());
      ids = sleep_order.data();
    }
    slept |= sleepIsland(ids, n, r.resting, dt);
  }
  if (slept) schedule_fresh = false;
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
