// The island solve: solver bodies, the substep sequence of one island (IslandPass), and the
// islands spread over the threads. Data and the sequence in words: island_solve.hpp.
#include <algorithm>
#include <chrono>
#include <utility>

#include "parallel_for.hpp"
#include "thread_team.hpp"
#include "world_impl.hpp"

namespace ragdoll_sim {

// (island_solve.hpp)
void StealReserve::update(double seconds) {
  const int in_trial = step_ % kTrial;
  if (step_ < kTrial && in_trial >= kSettle) time_off_ += seconds;
  else if (step_ < 2 * kTrial && in_trial >= kSettle) time_on_ += seconds;
  if (++step_ == 2 * kTrial) {
    faster_on_ = time_on_ < time_off_;
    time_off_ = time_on_ = 0.0;
  } else if (step_ == kPeriod) {
    step_ = 0;
  }
}

// (island_solve.hpp)
bool extendsRange(IslandRange& c, const IslandRange& r, int k, int left, int fill) {
  const bool follows = k == c.island_end && r.body_begin == c.body_end &&
                       r.joint_begin == c.joint_end && r.contact_begin == c.contact_end &&
                       r.resting == c.resting;
  const int work = c.work() + r.work();
  if (!follows || work > kLaneRangeWork ||
      (work > fill && c.island_end - c.island_begin >= left))
    return false;
  c.body_end = r.body_end;
  c.joint_end = r.joint_end;
  c.contact_end = r.contact_end;
  c.island_end = k + 1;
  return true;
}

namespace {
using Clock = std::chrono::steady_clock;
double microseconds(Clock::duration d) {
  return std::chrono::duration<double, std::micro>(d).count();
}

// body(t) on each thread t of a parallel region of `threads`; returns the region's wall time in
// microseconds. With `wait` (while profiling), adds the region's time each thread spent outside
// body (the region reaching it, the others' end) to *wait.
template <class Body>
double teamRegion(int threads, double* wait, std::vector<SolveData::RegionSpan>& spans,
                  Body&& body) {
  const Clock::time_point start = Clock::now();
  if (wait) spans.resize(threads);
  int team = 1;
  teamRun(threads, [&](int t) {
    const Clock::time_point in = wait ? Clock::now() : Clock::time_point();
    if (t == 0) team = teamSlot().second;
    body(t);
    if (wait) spans[t].us = microseconds(Clock::now() - in);
  });
  const double region = microseconds(Clock::now() - start);
  if (wait)
    for (int t = 0; t < team; ++t) *wait += region - spans[t].us;
  return region;
}

// The batch just built in the lanes (the joints of p, none for nullptr, and the contacts
// [begin, end)) into this thread's LaneCount (World::islandCounters).
void countLanes(SolveData& s, const StepContext& c, const IslandRange* p, int begin, int end) {
  if (c.lanes == 1) return;
  const ContactBatch* b = s.contact_solver.batchOf(c, begin, end);
  const bool joints = p && p->joint_end > p->joint_begin;
  if (!b && !joints) return;
  SolveData::LaneCount& n = s.lane_counts[teamSlot().first];
  ++n.batches;
  if (joints) s.point_lanes.addLaneFill(*p, n.joint_rows, n.joint_lanes);
  if (b) {
    n.contact_rows += b->laneRows();
    n.contact_lanes += b->lanes();
  }
}
}  // namespace

StepContexts World::Impl::makeContexts(double dt) {
  const int substeps = std::max(1, def.solver.substeps);
  const auto makeContext = [&](int n, int relax) {
    StepContext c;
    c.dt = dt;
    c.h = dt / n;
    c.inv_h = 1.0 / c.h;
    c.substeps = n;
    c.relax = std::max(0, relax);
    c.track_impulses = track_contacts;
    c.lanes = lane_width;
    c.odd_step = steps % 2 == 1;
    c.settings = &def.solver;
    c.bodies = &solver;
    c.rotations = &rotations;
    c.motions = &motions;
    c.contact_softness = Softness::make(std::min(def.solver.contact_hertz, 0.25 * c.inv_h),
                                        def.solver.contact_damping_ratio, c.h);
    c.joint_softness = Softness::make(std::min(def.solver.joint_hertz, 0.25 * c.inv_h),
                                      def.solver.joint_damping_ratio, c.h);
    return c;
  };
  StepContexts s;
  s.full = makeContext(substeps, def.solver.contact_relax_iterations);
  s.rest_mode = def.sleep.restOn(substeps);
  s.rest = s.rest_mode
               ? makeContext(def.sleep.rest_substeps, def.sleep.rest_relax_iterations)
               : s.full;
  return s;
}

// After the schedule: with the width left to the solver, islands too few to fill the lanes
// together take the double rows (World::kLanesMinBodies). The count is the step's, not a
// thread's, so every thread count and width decides alike.
void World::Impl::chooseRows(StepContexts& ctx) const {
  if (!lanes_auto || int(island_bodies.size()) >= World::kLanesMinBodies) return;
  ctx.full.lanes = 1;
  ctx.rest.lanes = 1;
}

// The sleeping dynamic bodies' solver bodies here: the identity (no row reads them, a touching
// contact wakes the whole island; the contact reports read their dp, 0). An island's bodies,
// joints and contacts are prepared by the thread that solves it, right before it does, so they
// are in its core's cache. A static body's is the identity body it was made
// with (createBody): no row writes a body that is not movable() (solver_context.hpp).
void World::Impl::prepareOutsideBodies() {
  for (const int i : dynamic_bodies)
    if (island_of_body[i] < 0) prepareSolverBody(i);
}

void World::Impl::prepareIsland(const IslandRange& p, const StepContext& c) {
  prepareSolverBodies(p.body_begin, p.body_end, c);
  for (int k = p.joint_begin; k < p.joint_end; ++k) prepareJoint(*active_joints[k], c);
  if (c.lanes != 1) point_lanes.build(p, active_joints.data(), *c.bodies);
  for (int k = p.joint_begin; k < p.joint_end; ++k)
    scalar_sweeps[k] = !active_joints[k]->broken && !active_joints[k]->sweeps_in_lanes;
  if (def.solver.exact_joints)
    forIslands(p, [&](const IslandRange& q) { joint_tree.build(q, island_bodies, active_joints.data(), *c.bodies); });
  contact_solver.prepare(contacts, c, p.contact_begin, p.contact_end);
  countLanes(*this, c, &p, p.contact_begin, p.contact_end);
}

// The substep sequence of one island on this thread; touches only the island's bodies and
// constraints. A split island is solved by the team of the enclosing parallel region. Each
// sweep first solves the boundary contacts, its two groups at once (they share no body), then
// the threads take the halves (with one thread: the same work in the same order); the halves'
// joints thus follow the boundary's impulses in every sweep, as they follow the contacts in a
// sweep of a whole island. Work on the halves alone needs no barrier: they touch disjoint
// bodies. Thread k always takes half k and boundary group k, so their constraints stay in its
// core's cache.
class World::Impl::IslandPass {
 public:
  // shared: the boundary's context (on two threads a split island's halves are solved in solver
  // bodies of their threads' own, its boundary in split_bodies: solveSplitIsland).
  IslandPass(World::Impl& w, const IslandRange& r, const StepContext& ctx,
             const StepContext& shared)
      : w(w), r(r), ctx(ctx), shared(shared), halves{r.half(0), r.half(1)},
        js(w.active_joints.data()) {
    const std::pair<int, int> slot = teamSlot();  // read by a split island's sweeps only
    t = slot.first;
    nt = slot.second;
  }

  // Velocities take gravity, forces and damping; joints and contacts apply last step's impulses.
  // moved: the deltas changed since the separations were last computed.
  void integrateAndWarmStart(int sub, bool moved) {
    parts([&](const IslandRange& p) {
      w.integrateVelocities(ctx, p.body_begin, p.body_end);
      if (wide && w.tuning.lane_exact_angles) w.point_lanes.exactAngles(p, solver, ctx, sub == 0);
      else if (sub == 0 && w.tuning.lane_exact_angles)
        firstSubstepAngles(js + p.joint_begin, p.joint_end - p.joint_begin, ctx);
      joints(p, [&](Joint& j) { warmStartJoint(j, ctx, sub == 0); });
      if (wide)
        w.point_lanes.load(p, solver, ctx, sub == 0, sub == 0 || !w.tuning.lane_angles_kept);
      w.contact_solver.warmStart(ctx, p.contact_begin, p.contact_end, moved);
    });
    boundary([&](int b, int e) {
      w.contact_solver.warmStart(shared, b, e, moved);
      solveContacts(shared, true, b, e, false);
    });
  }

  // The soft solve with bias (the boundary's was solved with its warm start), then the
  // positions advance.
  void solveBiasedAndIntegrate() {
    parts([&](const IslandRange& p) {
      solveJoints(p, true, last_joint_sweep < 0);
      solveContacts(ctx, true, p.contact_begin, p.contact_end, false);
      w.integratePositions(ctx, p.body_begin, p.body_end);
      poses_shared = false;
      // a joint whose sweeps are all in the lanes advances there (anchors, axis, angles)
      scalarJoints(p, [&](Joint& j) { advanceJoint(j, ctx); });
      if (wide) w.point_lanes.refreshAnchors(p, solver, ctx);
    });
  }

  // Relax sweep `it` without bias: contacts every sweep, joints in the first
  // joint_relax_iterations (Gauss-Seidel over a manifold's points and along a limb needs them
  // to take back the push-out velocity and to carry a landing's load up the chain). After the
  // last joint sweep the joint trees' anchors are made exact (joint_tree.hpp); the contact
  // sweeps that follow see them, so the contacts end consistent (no push into the ground).
  void relax(int it) {
    // an anchor velocity error that moves it less than a tenth of the slop per step is left
    const double tolerance = 0.1 * w.def.solver.joint_slop / ctx.dt;
    const int last_tree_sweep = w.def.solver.exact_joints ? last_joint_sweep : -1;
    boundary([&](int b, int e) { solveContacts(shared, false, b, e, it == 0); });
    parts([&](const IslandRange& p) {
      if (it < w.def.solver.joint_relax_iterations) solveJoints(p, false, it == last_joint_sweep);
      if (it == last_tree_sweep)
        w.forIslands(p, [&](const IslandRange& q) {
          w.joint_tree.projectVelocities(q, solver, w.island_bodies, ctx.h, tolerance);
        });
      solveContacts(ctx, false, p.contact_begin, p.contact_end, it == 0);
    });
  }

  // Joints whose anchor reached its break force are marked (breakJoints acts after the solve).
  // A joint whose sweeps are all in the lanes cannot break (wideAnchor, point_lanes.cpp): only
  // its force after the last substep is read.
  void markBreaks(bool last_substep) {
    parts([&](const IslandRange& p) {  // touches only the part's joints and their flags
      for (int k = p.joint_begin; k < p.joint_end; ++k)
        if ((last_substep || scalar[k]) && breaksAfterSubstep(*js[k], ctx)) {
          js[k]->broken = true;
          scalar[k] = 0;
          w.joint_broke.store(true, std::memory_order_relaxed);
        }
    });
  }

  // Impulse tracking after a substep: each thread reads the contacts it solved last (its
  // halves and its boundary group), so no barrier is needed.
  void trackImpulses(bool first) {
    parts([&](const IslandRange& p) {
      w.contact_solver.trackSubstep(p.contact_begin, p.contact_end, first);
    });
    if (!r.split) return;
    for (int k = t; k < 2; k += nt)
      w.contact_solver.trackSubstep(r.boundaryBegin(k), r.boundaryEnd(k), first);
  }

  void projectPositions();

  // This pass's contact sweeps into its thread's count (World::Impl::contact_sweeps).
  void countSweeps() { w.contact_sweeps[t].contacts += swept; }

  // The tracked bodies' velocities at the end of substep `sub` (substep_samples.hpp).
  void sample(int sub) {
    parts([&](const IslandRange& p) { w.sampleSubstep(p, sub, solver); });
  }

 private:
  // f(the island), or for a split island f(each of this thread's halves and the islands
  // attached to it).
  template <class F>
  void parts(F&& part) {
    if (!r.split) return part(r);
    for (int k = t; k < 2; k += nt) w.withAttached(r, halves[k], k, part);
  }
  // A split island's boundary contacts, this thread's group, between two barriers.
  template <class F>
  void boundary(F&& contacts) {
    if (!r.split) return;
    share(ctx, shared, !poses_shared);
    poses_shared = true;
    w.team_barrier.wait(t, nt);
    for (int k = t; k < 2; k += nt) contacts(r.boundaryBegin(k), r.boundaryEnd(k));
    w.team_barrier.wait(t, nt);
    share(shared, ctx, false);  // the boundary's rows change velocities only
  }
  // A joint sweep: with lanes, every joint's other parts, then the rigid anchors' wide pass
  // (last: the substep's last joint sweep, after which the impulses are read).
  void solveJoints(const IslandRange& p, bool use_bias, bool last) {
    scalarJoints(p, [&](Joint& j) { solveJoint(j, ctx, use_bias); });
    if (wide) w.point_lanes.solve(p, solver, ctx, use_bias, last);
  }
  void solveContacts(const StepContext& c, bool use_bias, int begin, int end,
                     bool positions_moved) {
    w.contact_solver.solve(c, use_bias, begin, end, positions_moved);
    swept += end - begin;
  }
  void share(const StepContext& from, const StepContext& to, bool whole) {
    w.shareSplitBodies(from, to, t, nt, whole);
  }
  template <class F>
  void joints(const IslandRange& p, F&& f) {
    for (int k = p.joint_begin; k < p.joint_end; ++k)
      if (!js[k]->broken) f(*js[k]);
  }
  // f(each unbroken joint whose sweeps are not all in the lanes).
  template <class F>
  void scalarJoints(const IslandRange& p, F&& f) {
    for (int k = p.joint_begin; k < p.joint_end; ++k)
      if (scalar[k]) f(*js[k]);
  }

  World::Impl& w;
  const IslandRange& r;
  const StepContext& ctx;
  const StepContext& shared;
  std::vector<SolverBody>& solver = *ctx.bodies;
  const IslandRange halves[2];
  Joint* const* js;
  char* const scalar = w.scalar_sweeps.data();
  const bool wide = ctx.lanes != 1;
  // the substep's last sweep that solves the joints (-1: the biased one)
  const int last_joint_sweep = std::min(ctx.relax, w.def.solver.joint_relax_iterations) - 1;
  int t = 0, nt = 1;
  bool poses_shared = true;  // the boundary's copies hold this thread's dq and dp (share)
  int64_t swept = 0;  // contact constraints solved, summed over the sweeps
};

// Position sweeps. A sweep that moved no body leaves the next ones nothing to do: they see
// the same poses and recompute the same angles, so the projection stops there, the anchor
// sweeps too (the result is the same bit for bit). A split island's threads decide together:
// each notes whether it moved anything (by the sweep's parity, so that the next sweep's note
// does not overwrite one still being read) and reads both notes after the barrier that starts
// the next sweep's boundary.
// Within a sweep, a projection whose bodies have not moved since its last look, when it
// moved nothing, is skipped too (unchangedSince, solver_context.hpp). Those marks alone would
// skip every projection after an idle sweep; the stop also saves the pass over the constraints
// and, on a split island, the sweep's two barriers.
void World::Impl::IslandPass::projectPositions() {
  const SolverSettings& def = w.def.solver;
  bool mine = false;  // this thread moved a body in the current sweep
  // f(j): projectJointLimits or projectJointAnchor, as a lambda so that each is called directly
  const auto project = [&](Joint& j, int sweep, auto&& f) {
    SolverBody &A = solver[j.a], &B = solver[j.b];
    if (unchangedSince(sweep, j.moved_sweep, A, B) || !f(j)) return;
    markMoved(sweep, j.moved_sweep, A, B);
    mine = true;
  };
  const auto limitsOf = [&](Joint& j) { return projectJointLimits(j, ctx); };
  const auto anchorOf = [&](Joint& j) { return projectJointAnchor(j, ctx); };
  int sweep = 0;  // numbered from 1 in the step
  const auto anchors = [&](const IslandRange& p) {
    for (int k = p.joint_begin; k < p.joint_end; ++k) project(*js[k], sweep, anchorOf);
  };
  const auto teamMoved = [&](int sweep) {
    const char* note = w.position_moved[sweep & 1];
    return std::any_of(note, note + nt, [](char c) { return c != 0; });
  };
  bool moved = true;  // by the last sweep, on any thread
  for (int it = 0; it < def.position_iterations && moved; ++it) {
    mine = false;
    sweep = it + 1;
    if (r.split) {
      share(ctx, shared, true);
      w.team_barrier.wait(t, nt);
      if (it > 0 && !teamMoved(it - 1)) {
        moved = false;
        break;
      }
      for (int k = t; k < 2; k += nt)
        mine |= w.contact_solver.project(shared, r.boundaryBegin(k), r.boundaryEnd(k), sweep);
      w.team_barrier.wait(t, nt);
      share(shared, ctx, true);
    }
    parts([&](const IslandRange& p) {
      mine |= w.contact_solver.project(ctx, p.contact_begin, p.contact_end, sweep);
      for (int k = p.joint_begin; k < p.joint_end; ++k) project(*js[k], sweep, limitsOf);
      anchors(p);
    });
    if (r.split) w.position_moved[it & 1][t] = mine;
    else moved = mine;
  }
  if (r.split && moved && def.position_iterations > 0 && def.anchor_iterations > 0) {
    w.team_barrier.wait(t, nt);
    moved = teamMoved(def.position_iterations - 1);
  }
  // The joints of a half touch only its bodies (halves are whole limbs): no boundary, and
  // each thread stops when its own halves' anchors did not move.
  for (int it = 0; it < def.anchor_iterations && moved; ++it) {
    mine = false;
    sweep = def.position_iterations + it + 1;
    parts(anchors);
    moved = mine;
  }
  // The joint trees' anchors exact (joint_tree.hpp); each half's trees are its own.
  if (def.exact_joints)
    parts([&](const IslandRange& p) {
      w.forIslands(p, [&](const IslandRange& q) {
        w.joint_tree.projectPositions(q, solver, w.island_bodies, def.joint_slop,
                                      def.max_position_correction);
      });
    });
}

// One island's substeps, then its position and anchor sweeps.
void World::Impl::solveIsland(const IslandRange& r, const StepContext& ctx,
                              const StepContext& shared) {
  IslandPass pass(*this, r, ctx, shared);
  for (int sub = 0; sub < ctx.substeps; ++sub) {
    // From the second substep on, the first relax sweep of the last one (if any) already set
    // the separations at the current deltas.
    const bool moved = sub == 0 || ctx.relax < 1;
    pass.integrateAndWarmStart(sub, moved);
    pass.solveBiasedAndIntegrate();
    for (int it = 0; it < ctx.relax; ++it) pass.relax(it);
    pass.markBreaks(sub == ctx.substeps - 1);
    if (ctx.track_impulses) pass.trackImpulses(sub == 0);
    if (!tracks.empty()) pass.sample(sub);
  }
  pass.projectPositions();
  pass.countSweeps();
}

// After an island's substeps, on the same thread: restitution and the impulses stored for the
// next warm start.
void World::Impl::restitute(int begin, int end, const StepContext& c) {
  contact_solver.applyRestitution(c, begin, end);
  contact_solver.storeImpulses(contacts, c.h, begin, end);
  if (c.track_impulses) contact_solver.storeTracks(contact_tracks, contacts, c.h, begin, end);
}

// The island's bodies take the step (joint breaks only mark the joints).
// finishBody of each (all awake), the poses in lanes (finishPoses, integrate.cpp). Solved in a
// team thread's own solver bodies, their step's motion (dq, dp) goes to solver too, where the
// contact reports read it after the step.
void World::Impl::finishIslandBodies(const IslandRange& p, const StepContext& c) {
  finishPoses(p.body_begin, p.body_end, c);
  const bool own = c.bodies != &solver;
  for (int k = p.body_begin; k < p.body_end; ++k) {
    const int i = island_bodies[k];
    const SolverBody& s = (*c.bodies)[size_t(i)];
    finishMotion(i, s);
    motions[i].force.setZero();
    motions[i].torque.setZero();
    if (own) {
      solver[size_t(i)].dq = s.dq;
      solver[size_t(i)].dp = s.dp;
    }
  }
  if (!tracks.empty()) sampleFinish(p);
}

// c on team thread t: from the second thread on, in that thread's solver bodies and rotations.
StepContext World::Impl::onTeamBodies(StepContext c, int t) {
  if (t > 0) {
    c.bodies = &team_bodies[size_t(t - 1)].solver;
    c.rotations = &team_bodies[size_t(t - 1)].rotations;
  }
  return c;
}

// Half k's bodies that a boundary contact touches, into split_shared[k].
void World::Impl::findSplitShared(const IslandRange& r, int k) {
  const IslandRange h = r.half(k);
  std::vector<char>& mark = split_mark[k];
  mark.resize(bodies.size(), 0);
  for (int i = h.body_begin; i < h.body_end; ++i) mark[size_t(island_bodies[i])] = 1;
  std::vector<int>& shared = split_shared[k];
  shared.clear();
  for (int i = r.boundary_begin; i < r.contact_end; ++i) {
    const Contact& c = contacts[size_t(contact_solver.active()[size_t(i)])];
    for (const int b : {c.body_a, c.body_b})
      if (mark[size_t(b)] == 1) {
        mark[size_t(b)] = 2;
        shared.push_back(b);
      }
  }
  for (int i = h.body_begin; i < h.body_end; ++i) mark[size_t(island_bodies[i])] = 0;
}

// The boundary bodies of thread t's halves (split_shared) from `from`'s solver bodies to
// `to`'s, whole or v and w (nothing on one thread, where the boundary is solved in the halves'
// array).
void World::Impl::shareSplitBodies(const StepContext& from, const StepContext& to, int t, int nt,
                                   bool whole) {
  if (from.bodies == to.bodies) return;
  for (int k = t; k < 2; k += nt)
    for (const int b : split_shared[k]) {
      const SolverBody& f = (*from.bodies)[size_t(b)];
      SolverBody& s = (*to.bodies)[size_t(b)];
      if (whole) {
        s = f;
      } else {
        s.v = f.v;
        s.w = f.w;
      }
    }
}

// A split island by the whole team (two threads at most: it has two halves): each thread
// prepares a half, then a group of the boundary contacts (their bodies are in both halves).
void World::Impl::solveSplitIsland(const IslandRange& r, const StepContexts& ctx) {
  const auto team = [&] {
    const std::pair<int, int> slot = teamSlot();
    const int t = slot.first, nt = slot.second;
    // On two threads each half (and the islands attached to it) in solver bodies of its
    // thread's own, the boundary in split_bodies (SolveData::split_shared).
    const StepContext c = onTeamBodies(ctx.of(r.resting), t);
    StepContext shared = ctx.of(r.resting);
    if (nt > 1) {
      shared.bodies = &split_bodies;
      findSplitShared(r, t);
    }
    // half k and the islands attached to it (attachToSplitHalves)
    const auto withHalf = [&](int k, auto&& f) { withAttached(r, r.half(k), k, f); };
    for (int k = t; k < 2; k += nt) withHalf(k, [&](const IslandRange& p) { prepareIsland(p, c); });
    shareSplitBodies(c, shared, t, nt, true);
    team_barrier.wait(t, nt);
    for (int k = t; k < 2; k += nt) {
      contact_solver.prepare(contacts, shared, r.boundaryBegin(k), r.boundaryEnd(k));
      countLanes(*this, shared, nullptr, r.boundaryBegin(k), r.boundaryEnd(k));
    }
    team_barrier.wait(t, nt);
    solveIsland(r, c, shared);
    // Restitution reads the halves' bodies as the boundary's does: halves first, then the
    // boundary, then the bodies take their velocities.
    for (int k = t; k < 2; k += nt)
      withHalf(k, [&](const IslandRange& p) { restitute(p.contact_begin, p.contact_end, c); });
    shareSplitBodies(c, shared, t, nt, true);
    team_barrier.wait(t, nt);
    for (int k = t; k < 2; k += nt) restitute(r.boundaryBegin(k), r.boundaryEnd(k), shared);
    team_barrier.wait(t, nt);
    shareSplitBodies(shared, c, t, nt, false);
    for (int k = t; k < 2; k += nt)
      withHalf(k, [&](const IslandRange& p) { finishIslandBodies(p, c); });
  };
  // One thread takes both halves in turn, outside a region (parallel_for.hpp says why).
  if (threadCount() > 1) {
    split_bodies.resize(solver.size());
    double* wait = profiling ? &profile.solve_wait : nullptr;
    teamRegion(2, wait, region_spans, [&](int) { team(); });
    if (wait) *wait += team_barrier.takeWaited();
  } else {
    team();
  }
}

// Split islands one after another, each by the whole team; then the others, each thread its
// run of islands first, then what is left of the others' (run_queue.hpp).
void World::Impl::solveIslands(const StepContexts& ctx) {
  contact_solver.resize(threadCount());
  contact_sweeps.resize(std::max(threadCount(), TeamBarrier::kMaxTeam));
  lane_counts.assign(contact_sweeps.size(), LaneCount());
  joint_tree.reserve(int(bodies.size()), int(island_bodies.size()), int(active_joints.size()));
  point_lanes.reserve(int(active_joints.size()));
  scalar_sweeps.resize(active_joints.size());
  // A new body's entries are the identity a static body keeps (createBody); an island's are
  // prepared by the thread that solves it.
  team_bodies.resize(size_t(threadCount() - 1));
  for (TeamBodies& t : team_bodies) {
    t.solver.resize(solver.size());
    t.rotations.resize(rotations.size(), Mat3::Identity());
  }
  if (track_contacts) contact_tracks.assign(contacts.size(), ContactTrack());
  team_barrier.setTimed(profiling);
  const int count = int(island_ranges.size());
  for (const IslandRange& r : island_ranges)
    if (r.split) solveSplitIsland(r, ctx);
  const auto solveRange = [&](const IslandRange& r) {
    const StepContext c = onTeamBodies(ctx.of(r.resting), teamSlot().first);
    prepareIsland(r, c);
    solveIsland(r, c);
    restitute(r.contact_begin, r.contact_end, c);
    finishIslandBodies(r, c);
    sleepIslands(r, c.dt);
  };
  const auto solveOne = [&](int k) {
    const IslandRange& r = island_ranges[k];
    if (!r.split && !r.attached) solveRange(r);
  };
  // With lanes, a thread solves consecutive whole islands of its run as one range, so that their
  // rows fill the lanes together; an island's arithmetic does not depend on the islands that
  // share its range (docs/physics.md, the wide solver), only the lanes' fill does.
  const bool chunks = ctx.full.lanes != 1;
  const int reserve_mode = tuning.range_reserve;
  const bool reserve = reserve_mode > 0 || (reserve_mode < 0 && steal_reserve.on());
  const int fill = reserve ? kLaneRangeFill : kLaneRangeWork;
  run_queue.reset(island_runs);
  const auto solveRun = [&](int t) {
    // Alone (no team, or a team of one) nobody steals: the ranges need not shrink.
    const bool shared = teamSlot().second > 1;
    const auto left = [&](int k) { return shared ? island_runs[t + 1] - k - 1 : count; };
    IslandRange chunk;
    bool open = false;
    const auto flush = [&] {
      if (open) solveRange(chunk);
      open = false;
    };
    for (int k; (k = run_queue.take(t)) >= 0;) {
      const IslandRange& r = island_ranges[k];
      if (r.split || r.attached) continue;
      if (chunks && open && extendsRange(chunk, r, k, left(k), fill)) continue;
      flush();
      chunk = r;
      chunk.island_begin = k;
      chunk.island_end = k + 1;
      open = true;
    }
    flush();
    for (int k; (k = run_queue.steal(t)) >= 0;) solveOne(k);
  };
  // (no runs when every island is split or goes along with a split one's half)
  const bool team = splitOverThreads(int(island_bodies.size()), threadCount());
  if (run_work > 0 && count > 1 && team) {
    double* wait = profiling ? &profile.solve_wait : nullptr;
    const double region = teamRegion(threadCount(), wait, region_spans, solveRun);
    if (reserve_mode < 0 && chunks) steal_reserve.update(1e-6 * region);
  } else if (run_work > 0) {
    solveRun(0);  // its own run, then the others' (stolen from the back)
  }
}

}  // namespace ragdoll_sim
