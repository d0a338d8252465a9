// Island scheduling: the awake islands (union-find over joints and touching contacts), grouped
// into ranges, the biggest one split, the islands attached to its halves, and the thread runs.
// Data: island_schedule.hpp.
#include <algorithm>

#include "constants.hpp"
#include "group_by.hpp"
#include "world_impl.hpp"

namespace ragdoll_sim {

// The islands' schedule is a function of the joints (and which are broken), the awake dynamic
// bodies, the contacts (their order: the constraints are their indices) and which of them touch,
// and the thread count; whatever changes one of those clears schedule_fresh (a wake of a sleeping
// body, sleep, a body, joint or contact made or removed, a joint broken, a body reset, collide
// finding other pairs or a pair starting or ending touching). Otherwise last step's is this one's:
// built again it would come out the same, bit for bit.
void World::Impl::scheduleIslands() {
  if (tuning.keep_schedule && schedule_fresh && schedule_threads == threadCount()) return;
  buildIslands();
  collectActiveJoints();
  partitionIslands();
  schedule_fresh = true;  // the wakes of buildIslands are in it
  schedule_threads = threadCount();
  ++schedule_builds;
}

void World::Impl::buildIslands() {
  islands.reset(int(bodies.size()), dynamic_bodies);  // static bodies are never united
  for (const Joint& j : joints)
    if (!j.broken && isDynamic(j.a) && isDynamic(j.b)) islands.unite(j.a, j.b);
  for (const Contact& c : contacts)
    if (c.manifold.count > 0 && isDynamic(c.body_a) && isDynamic(c.body_b))
      islands.unite(c.body_a, c.body_b);
  // An island with one awake body is awake as a whole (only dynamic bodies are ever awake).
  for (const int i : dynamic_bodies)
    if (motions[i].awake) motions[islands.find(i)].awake = true;
  for (const int i : dynamic_bodies)
    if (!motions[i].awake && motions[islands.find(i)].awake) wake(i);
}

// The joints solved this step: not broken, one body awake.
void World::Impl::collectActiveJoints() {
  active_joints.clear();
  for (Joint& j : joints)
    if (!j.broken && (motions[j.a].awake || motions[j.b].awake)) active_joints.push_back(&j);
}

// Numbers the awake islands by their first body and groups bodies, joints and contact
// constraints by island, so each island is a contiguous range of each.
void World::Impl::partitionIslands() {
  // Entries of static bodies stay -1: only the dynamic ones are set and reset.
  const int n = int(bodies.size());
  island_of_body.resize(n, -1);
  island_slot.resize(n, -1);
  for (const int i : dynamic_bodies) island_of_body[i] = -1;
  int count = 0;
  island_bodies.clear();
  for (const int i : dynamic_bodies) {
    if (!motions[i].awake) continue;
    int& k = island_slot[islands.find(i)];
    if (k < 0) k = count++;
    island_of_body[i] = k;
    island_bodies.push_back(i);
  }
  for (const int i : island_bodies) island_slot[islands.find(i)] = -1;
  island_ranges.assign(count, IslandRange());
  const auto bodyIsland = [&](int b) { return island_of_body[b]; };
  groupBy(island_bodies, count, bodyIsland, body_scratch, group_offsets, group_cursor);
  for (int k = 0; k < count; ++k) {
    island_ranges[k].body_begin = group_offsets[k];
    island_ranges[k].body_end = group_offsets[k + 1];
  }
  const auto pairIsland = [&](int a, int b) {
    return island_of_body[a] >= 0 ? island_of_body[a] : island_of_body[b];
  };
  groupBy(active_joints, count, [&](const Joint* j) { return pairIsland(j->a, j->b); },
          joint_scratch, group_offsets, group_cursor);
  for (int k = 0; k < count; ++k) {
    island_ranges[k].joint_begin = group_offsets[k];
    island_ranges[k].joint_end = group_offsets[k + 1];
  }
  // The contacts are grouped as indices before they are prepared: a constraint is ~840 bytes.
  std::vector<int>& active_contacts = contact_solver.selectActive(contacts, motions);
  groupBy(active_contacts, count,
          [&](int ci) { return pairIsland(contacts[ci].body_a, contacts[ci].body_b); },
          contact_index_scratch, group_offsets, group_cursor);
  for (int k = 0; k < count; ++k) {
    island_ranges[k].contact_begin = group_offsets[k];
    island_ranges[k].contact_end = group_offsets[k + 1];
  }
  long awake_work = 0;
  for (const IslandRange& r : island_ranges) awake_work += r.work();
  for (IslandRange& r : island_ranges) {
    if (r.body_end - r.body_begin < kSplitMin || 2L * r.work() <= awake_work) continue;
    IslandHalves h;
    r.split = splitter.split(island_bodies.data() + r.body_begin, r.body_end - r.body_begin,
                             active_joints.data() + r.joint_begin, r.joint_end - r.joint_begin,
                             active_contacts.data() + r.contact_begin,
                             r.contact_end - r.contact_begin, contacts, n, h);
    if (!r.split) continue;
    r.body_mid = r.body_begin + h.body_mid;
    r.joint_mid = r.joint_begin + h.joint_mid;
    r.contact_mid = r.contact_begin + h.contact_mid;
    r.boundary_begin = r.contact_begin + h.boundary_begin;
    r.boundary_mid = r.contact_begin + h.boundary_mid;
  }
  attachToSplitHalves();
  assignThreadRuns();
}

// Each thread takes a run of consecutive islands (in body order) of about equal work, the same run
// step after step while the islands last: its bodies and constraints stay in that core's cache
// (handing out islands dynamically would move them between the cores). A thread done with its run
// takes what is left of the others' from their back (run_queue.hpp).
void World::Impl::assignThreadRuns() {
  const int count = int(island_ranges.size());
  const int threads = threadCount();
  long total = 0;
  const auto work = [&](int k) {
    const IslandRange& r = island_ranges[k];
    return r.split || r.attached ? 0L : long(r.work());
  };
  for (int k = 0; k < count; ++k) total += work(k);
  run_work = total;
  island_runs.assign(threads + 1, count);
  island_runs[0] = 0;
  long prefix = 0;  // work of islands [0, k)
  int k = 0;
  for (int t = 1; t < threads; ++t) {
    // the cut nearest to this run's share of the work
    const long share = total * t / threads;
    while (k < count && prefix + work(k) <= share) prefix += work(k++);
    if (k < count && prefix + work(k) - share < share - prefix) prefix += work(k++);
    island_runs[t] = k;
  }
}

// With a split island, the whole islands go along with its halves instead of into runs: each, in
// order, to the half with the least work so far (its bodies, joints and contacts plus its boundary
// group's). The threads wait for each other at every boundary sweep, so the thread of the lighter
// half solves, e.g., a ragdoll that lies apart in that time instead of after the split island while
// the other thread idles. An attached island goes through the same substep sequence as alone, in
// lockstep with the half, so the result does not change. With more than two threads (a split island
// takes two) an island only fills a lighter half up to the other's work: the runs spread the rest
// over all threads.
void World::Impl::attachToSplitHalves() {
  attached_islands.clear();
  attach_scratch.clear();  // (slot, island); slot = 2 x (split island's rank) + half
  std::vector<long>& load = island_load;
  load.clear();
  std::vector<int>& split_of_slot = island_split_of_slot;
  split_of_slot.clear();
  for (int s = 0; s < int(island_ranges.size()); ++s) {
    const IslandRange& r = island_ranges[s];
    if (!r.split) continue;
    for (int k = 0; k < 2; ++k) {
      load.push_back(r.half(k).work() + (r.boundaryEnd(k) - r.boundaryBegin(k)));
      split_of_slot.push_back(s);
    }
  }
  if (load.empty()) return;
  const bool fill_only = threadCount() > 2;
  for (int i = 0; i < int(island_ranges.size()); ++i) {
    IslandRange& r = island_ranges[i];
    if (r.split) continue;
    const int slot = int(std::min_element(load.begin(), load.end()) - load.begin());
    if (fill_only && load[slot] + r.work() > load[slot ^ 1]) continue;
    load[slot] += r.work();
    r.attached = true;
    attach_scratch.push_back({slot, i});
  }
  // Grouped by slot, in island order (a pass per slot: there are two per split island, and
  // std::stable_sort would take a buffer from the heap every step).
  for (int slot = 0; slot < int(load.size()); ++slot) {
    IslandRange& r = island_ranges[split_of_slot[slot]];
    const int k = slot % 2;
    r.attach[k] = int(attached_islands.size());
    for (const auto& [s, island] : attach_scratch)
      if (s == slot) attached_islands.push_back(island);
    r.attach[k + 1] = int(attached_islands.size());
  }
}

}  // namespace ragdoll_sim
