// Island scheduling's data (island_schedule.cpp): this step's awake islands as ranges of bodies,
// joints and contact constraints, the split of the biggest one, the islands that go along with
// its halves, and the thread runs.
//
// Islands (island.hpp) are numbered by their first body; each is a contiguous range of each
// kind. An island of kSplitMin bodies or more that holds more than half the awake work is split
// in two halves (island_split.hpp). Each thread takes a run of consecutive islands of about equal
// work, then what is left of the other runs (run_queue.hpp). Every island is solved in the same
// order whatever the thread count, so the result does not depend on it.
#pragma once

#include <utility>
#include <vector>

#include "island.hpp"
#include "island_split.hpp"
#include "joint.hpp"
#include "run_queue.hpp"

namespace ragdoll_sim {

struct IslandRange {
  int body_begin = 0, body_end = 0, joint_begin = 0, joint_end = 0;
  int contact_begin = 0, contact_end = 0;
  // A split island (island_split.hpp): halves [begin, mid) and [mid, end) of bodies and
  // joints, contacts [contact_begin, contact_mid) and [contact_mid, boundary_begin), then the
  // boundary contacts up to contact_end, in two groups that share no body (boundary(k)).
  bool split = false;
  int body_mid = 0, joint_mid = 0, contact_mid = 0, boundary_begin = 0, boundary_mid = 0;
  int boundaryBegin(int k) const { return k == 0 ? boundary_begin : boundary_mid; }
  int boundaryEnd(int k) const { return k == 0 ? boundary_mid : contact_end; }
  // Split: the whole islands solved along with half k, attached_islands[attach[k],
  // attach[k + 1]). Whole: attached to a split island's half (not in a run).
  int attach[3] = {0, 0, 0};
  bool attached = false;
  bool resting = false;  // takes SleepDef::rest_substeps (markResting)
  // Consecutive whole islands solved as one range (with lanes, island_solve.cpp): islands
  // [island_begin, island_end) of island_ranges; empty for one island or a half.
  int island_begin = 0, island_end = 0;
  int work() const {
    return (body_end - body_begin) + (joint_end - joint_begin) + (contact_end - contact_begin);
  }
  IslandRange half(int k) const {
    IslandRange r = *this;
    r.split = false;
    if (k == 0) {
      r.body_end = body_mid, r.joint_end = joint_mid, r.contact_end = contact_mid;
    } else {
      r.body_begin = body_mid, r.joint_begin = joint_mid;
      r.contact_begin = contact_mid, r.contact_end = boundary_begin;
    }
    return r;
  }
};

struct IslandSchedule {
  Islands islands;
  std::vector<Joint*> active_joints;  // grouped by island after partitionIslands()
  std::vector<IslandRange> island_ranges;
  std::vector<int> island_runs;  // thread t solves islands [island_runs[t], island_runs[t + 1])
  RunQueue run_queue;            // ... and then steals what is left of the others' runs
  std::vector<int> attached_islands;  // grouped by split island and half (IslandRange::attach)
  long run_work = 0;  // work of the islands in runs (none when all go along with split ones)
  std::vector<int> island_bodies;   // awake bodies, grouped by island
  std::vector<int> island_of_body;  // per body: its island, -1 when not awake or not dynamic
  std::vector<int> island_slot;     // per island root: its island while numbering, else -1
  IslandSplitter splitter;
  // Whether the schedule above still fits what it was built from (scheduleIslands): cleared
  // where an awake flag, a joint, the contacts or which of them touch change.
  bool schedule_fresh = false;
  int schedule_threads = 0;  // threadCount() when it was built
  int64_t schedule_builds = 0;
  // scratch, reused every step
  std::vector<std::pair<int, int>> attach_scratch;
  std::vector<long> island_load;
  std::vector<int> island_split_of_slot;
  std::vector<int> group_offsets, group_cursor, body_scratch;
  std::vector<Joint*> joint_scratch;
  std::vector<int> contact_index_scratch;
};

}  // namespace ragdoll_sim
