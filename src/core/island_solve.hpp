// The island solve's data (island_solve.cpp): per body its solver body, the contact constraints,
// and what the two threads of a split island share.
//
// Per island (islands in parallel, each on the thread that prepares it), per substep:
// integrate velocities (gravity, forces, damping), warm start, solve with bias (soft),
// integrate positions, relax without bias (contacts several sweeps, the joints in the first
// ones), mark the joints that break; then position sweeps (contacts, joint limits and angular
// rows, joint anchors) remove the error beyond the slops without touching velocities, and
// anchor sweeps go over the joint anchors alone. Then restitution, the impulses kept for the
// next warm start, and the bodies take the step. Static bodies are shared by all islands and
// are never written (movable(), solver_context.hpp).
// Semi-implicit Euler: v += h a first, then x += h v with the new v (and the same for the
// rotation, q += h/2 (0,w) q, renormalised, with the gyroscopic update in integratePositions).
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "body.hpp"
#include "contact_solver.hpp"
#include "island_schedule.hpp"
#include "joint_tree.hpp"
#include "point_lanes.hpp"
#include "solver_context.hpp"
#include "team_barrier.hpp"

namespace ragdoll_sim {

// With lanes, a thread solves consecutive whole islands of its run as one range (solveIslands):
// the most work (IslandRange::work) of such a range, enough for full lanes.
constexpr int kLaneRangeWork = 512;
// The work a range may take before it must leave islands to steal, while the threads keep a
// reserve (StealReserve): a lone ragdoll's joints fill about half the lanes of each
// colour's blocks, three fill them.
constexpr int kLaneRangeFill = 160;

// Appends island r (index k in island_ranges) to range c when it follows c directly in the body,
// joint and contact arrays, takes the same substeps, keeps c within kLaneRangeWork and either
// keeps it within fill or leaves at least as many islands untaken as c then holds (left: the
// islands of the run after r); false (c unchanged) otherwise. A thread takes a range's islands
// before it solves any of them, so the last rule shrinks the ranges towards the end of its run,
// down to fill, and leaves the other threads islands to steal.
bool extendsRange(IslandRange& c, const IslandRange& r, int k, int left, int fill);

// Whether the threads' ranges of islands keep a reserve to steal (kLaneRangeFill). The reserve
// costs the lanes' fill and pays where the threads end their runs apart; which weighs more
// depends on the machine (how fast its cores hand work over) and on the scene, so the rule
// times both: every kPeriod steps it runs kTrial steps without the reserve, then kTrial with it,
// sums the parallel region's time of each trial's steps after its first kSettle (the caches
// follow the new ranges), and keeps the faster until the period ends.
class StealReserve {
 public:
  bool on() const { return step_ < kTrial ? false : step_ < 2 * kTrial ? true : faster_on_; }
  // After a step's parallel region (on() before it decided its ranges): its wall time.
  void update(double seconds);

 private:
  static constexpr int kTrial = 32;
  static constexpr int kSettle = 8;
  static constexpr int kPeriod = 512;
  int step_ = 0;
  bool faster_on_ = false;
  double time_off_ = 0.0, time_on_ = 0.0;
};

// The step's two substep sequences: the full one, and the rest substeps of islands whose bodies
// have all been slow for SleepDef::rest_time (full again when rest_mode is off).
struct StepContexts {
  StepContext full, rest;
  bool rest_mode = false;
  const StepContext& of(bool resting) const { return resting ? rest : full; }
};

struct SolveData {
  std::vector<SolverBody> solver;
  // Per body: the rotation matrix of dq q, its world rotation at the current substep (set with
  // the solver body, advanced by integratePositions; only that reads it).
  std::vector<Mat3> rotations;
  ContactSolver contact_solver;
  // Impulse tracking (World::setContactImpulseTracking): on, the step files what it kept of
  // each contact it solved by contact index (the others' keys are 0); off, nothing is written.
  bool track_contacts = false;
  std::vector<ContactTrack> contact_tracks;
  // Per active joint (active_joints' order): 1 while it is unbroken and its sweeps are not all
  // in the lanes (Joint::sweeps_in_lanes), set when its island is prepared and cleared when it
  // breaks: the sweeps, the advance and the breaks of the substeps loop over these bytes instead
  // of reading each Joint (~1 KB apart) several times per substep.
  std::vector<char> scalar_sweeps;
  // A joint broke in this step's substeps (markBreaks): only then does breakJoints look at the
  // active joints, each on its own cache line, most written by another core.
  std::atomic<bool> joint_broke{false};
  JointTree joint_tree;  // exact anchors (SolverSettings::exact_joints)
  PointLanes point_lanes;  // the joint anchors in float lanes (SolverSettings::lanes != 1)
  TeamBarrier team_barrier;  // the two threads of a split island
  StealReserve steal_reserve;  // WorldTuning::range_reserve -1
  // While profiling, each thread's time in a parallel region of the solve, in microseconds
  // (a cache line each), for StepProfile::solve_wait.
  struct alignas(64) RegionSpan {
    double us = 0.0;
  };
  std::vector<RegionSpan> region_spans;
  // Per thread (a cache line each): the contact constraints solved, summed over the sweeps, in
  // which each is solved once (WorldInternals::contactSweeps, for tests).
  struct alignas(64) SweepCount {
    int64_t contacts = 0;
  };
  std::vector<SweepCount> contact_sweeps;
  // Per thread (a cache line each): the batches it built in the lanes and their rows and lanes
  // (World::islandCounters).
  struct alignas(64) LaneCount {
    int batches = 0, contact_rows = 0, contact_lanes = 0, joint_rows = 0, joint_lanes = 0;
  };
  std::vector<LaneCount> lane_counts;
  // Team thread t > 0 solves its whole islands, and the second half of a split island, in
  // solver bodies and rotations of its own (team_bodies[t - 1], by body index as solver; the
  // master uses solver and rotations), and copies dq and dp back to solver as its bodies finish
  // (finishIslandBodies), for the contact reports. In one array two runs' bodies share a
  // page, and the core of the run below, fetching ahead along its bodies, keeps taking the
  // lines of the run above away from the other core. A row reads only its island's bodies and
  // static ones, whose entries never change.
  struct TeamBodies {
    std::vector<SolverBody> solver;
    std::vector<Mat3> rotations;
  };
  std::vector<TeamBodies> team_bodies;
  // On two threads a split island's boundary is solved in split_bodies (by body index, only the
  // boundary's bodies are read): before each boundary phase each thread copies its half's
  // bodies that the boundary touches (split_shared[half]) there, and back after it. The
  // boundary's rows then never write a line of the other thread's array: each moves between
  // the cores in the copy's tight loop instead of in the middle of a sweep's dependent rows.
  // split_mark[half]: its thread's scratch, by body.
  std::vector<SolverBody> split_bodies;
  std::vector<int> split_shared[2];
  std::vector<char> split_mark[2];
  // Whether each thread of a split island moved a body in a position sweep, by the sweep's
  // parity (IslandPass::projectPositions).
  char position_moved[2][2] = {};
};

}  // namespace ragdoll_sim
