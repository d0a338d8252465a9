// World::Impl: the storage every phase reads (bodies, motions, shapes, joints) and, as its
// bases, the data each phase owns. Each phase's functions live in the phase's file:
//   collide.cpp          collide (broadphase, narrowphase, manifold cache, carried pairs)
//   island_schedule.cpp  buildIslands, partitionIslands, attachToSplitHalves
//   island_solve.cpp     the substep sequence, solveIslands
//   integrate.cpp        the solver bodies, the velocity and position steps (lanes: integrate_kernel.hpp)
//   fault_guard.cpp      guardInputs, finishBody, resetFaulted, clearWarmStart
//   sleep.cpp            markResting, updateSleep, World::setSleep
//   world_create.cpp     the create and destroy API, breakJoints
//   world_query.cpp      commands and queries
//   static_overlap.cpp   World::staticOverlap (spawn checks)
//   substep_samples.cpp  tracked bodies' velocities per substep (World::trackBody)
//   world.cpp            the constructor, World::step (the phase list) and the settings
//   world_tuning.hpp     the internal switches that check an optimisation (WorldInternals)
#pragma once

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "ragdoll_sim/world.hpp"

#include "body.hpp"
#include "collide.hpp"
#include "fault_guard.hpp"
#include "island_schedule.hpp"
#include "island_solve.hpp"
#include "joint.hpp"
#include "sleep.hpp"
#include "substep_samples.hpp"
#include "world_tuning.hpp"

namespace ragdoll_sim {

struct ShapeRef {
  int body;
  int index;  // in Body::shapes
  bool alive = true;  // false once removed: collide puts it in no pair
};

struct World::Impl : CollideData, IslandSchedule, SolveData, FaultGuardData, SleepData,
                     SubstepSampleData {
  WorldDef def;
  // def.solver.lanes resolved once when set (1, 4 or 8; lane_width.hpp reads the CPU and the
  // environment), not per step; lanes_auto: no width was forced (laneWidthAutomatic).
  int lane_width = 1;
  bool lanes_auto = false;
  void resolveLanes(int lanes);  // both from SolverSettings::lanes (world.cpp)
  WorldTuning tuning;  // world_tuning.hpp
  double time = 0.0;
  uint64_t steps = 0;  // World::step calls with dt > 0
  std::vector<Body> bodies;
  std::vector<BodyMotion> motions;
  std::vector<ShapeRef> shapes;
  std::vector<Joint> joints;
  std::vector<char> joint_alive;  // per joint: not destroyed
  std::vector<JointId> broken_events;
  // The last step found no body awake and ran the whole pipeline, and nothing has been built,
  // woken, set or reset since: the next step would give the same contacts and move nothing,
  // so it only advances the time (a world whose ragdolls all sleep costs almost nothing).
  bool settled = false;
  bool profiling = false;  // World::setProfiling
  StepProfile profile;     // of the last step, while profiling
  // The per-step body loops walk these instead of every body, so that static bodies cost
  // nothing per step: the alive dynamic bodies (ascending), and the static bodies created or
  // commanded (state, force, impulse) since the last step, which the fault guard checks and
  // whose forces are cleared (static_touched: per body, whether it is listed).
  std::vector<int> dynamic_bodies;
  std::vector<int> touched_static;
  std::vector<char> static_touched;

  int threadCount() const {
#ifdef _OPENMP
    return def.threads > 0 ? def.threads : omp_get_max_threads();
#else
    return 1;
#endif
  }
  const ShapeDef& shapeDef(int s) const { return bodies[shapes[s].body].shapes[shapes[s].index]; }
  // The shape's pose relative to its body's centre of mass, in world axes: x + f.p, f.q is
  // its world pose.
  Transform shapeFrame(int s) const {
    const BodyMotion& m = motions[shapes[s].body];
    const Transform& local = shapeDef(s).local;
    return {m.q * (local.p - m.local_com), m.q * local.q};
  }
  // The shape's pose in a frame at world point o (a centre of mass, on the grid): from the
  // exact difference x - o, so it does not depend on where the pair is (body.hpp). A plane is
  // kept at its distance along the normal from o: moving it within itself changes nothing, and
  // its x and y would carry o's magnitude into the manifold cache's points. (The cache thus
  // sees a shape sliding on a plane as not moving, and keeps its manifold: right for a plane,
  // whose features are the same everywhere; tilting or lifting it still counts.)
  Transform shapePoseFrom(int s, const Vec3& o) const {
    const Transform& f = shape_frames[s];
    const Vec3 p = (motions[shapes[s].body].x - o) + f.p;
    const Geometry& g = shapeDef(s).geometry;
    if (isUnbounded(g)) {
      const Vec3 n = f.q * g.normal;
      return {n * n.dot(p), f.q};
    }
    return {p, f.q};
  }
  bool validBody(BodyId id) const {
    return id.index >= 0 && id.index < int(bodies.size()) && bodies[id.index].alive;
  }
  bool validJoint(JointId id) const {
    return id.index >= 0 && id.index < int(joints.size()) && joint_alive[id.index];
  }
  void checkBody(BodyId id) const {
    if (!validBody(id)) throw std::out_of_range("ragdoll_sim: invalid body id");
  }
  Joint& joint(JointId id) {
    if (!validJoint(id)) throw std::out_of_range("ragdoll_sim: invalid joint id");
    return joints[id.index];
  }
  const Joint& joint(JointId id) const { return const_cast<Impl*>(this)->joint(id); }
  // Throws std::invalid_argument with jointDefError's message e (if any), naming the bodies.
  template <class Def>
  void checkJointDef(const char* type, const Def& def) const {
    checkBody(def.body_a);
    checkBody(def.body_b);
    const std::string e = jointDefError(def);
    if (!e.empty())
      throw std::invalid_argument(std::string("ragdoll_sim: ") + type + " joint between '" +
                                  bodies[def.body_a.index].def.name + "' and '" +
                                  bodies[def.body_b.index].def.name + "': " + e);
  }
  // False for a destroyed body too: nothing wakes, moves or collides it.
  bool isDynamic(int b) const {
    return bodies[b].def.type == BodyType::Dynamic && bodies[b].alive;
  }
  // The body whose centre a pair of bodies a, b is collided at (Contact::origin): the first
  // dynamic one.
  int pairOrigin(int a, int b) const { return isDynamic(a) ? a : b; }
  void wake(int b) {
    settled = false;  // also for a static body: setBodyState moves it through here
    guard_clean[b] = 0;  // a command changes it through here
    if (!isDynamic(b)) return touchStatic(b);
    if (!motions[b].awake) schedule_fresh = false;
    motions[b].awake = true;
    motions[b].sleep_time = 0.0;
  }
  bool anyAwake() const {
    return std::any_of(dynamic_bodies.begin(), dynamic_bodies.end(),
                       [this](int i) { return motions[i].awake; });
  }
  void touchStatic(int b) {
    if (static_touched[b]) return;
    static_touched[b] = 1;
    touched_static.push_back(b);
  }
  // f(i) for the dynamic and the touched static bodies, alive, in ascending order, but those
  // skip(i) leaves out (asked first: a Body is far larger than its flags).
  template <class F, class S>
  void forEachGuarded(F&& f, S&& skip) {
    std::sort(touched_static.begin(), touched_static.end());
    size_t a = 0, b = 0;
    while (a < dynamic_bodies.size() || b < touched_static.size()) {
      const bool dyn = b == touched_static.size() ||
                       (a < dynamic_bodies.size() && dynamic_bodies[a] < touched_static[b]);
      const int i = dyn ? dynamic_bodies[a++] : touched_static[b++];
      if (!skip(i) && bodies[i].alive) f(i);
    }
  }
  template <class F>
  void forEachGuarded(F&& f) {
    forEachGuarded(f, [](int) { return false; });
  }
  void clearTouched() {
    for (int b : touched_static) static_touched[b] = 0;
    touched_static.clear();
  }

  // The one way to change Body::no_collide: the broadphase filter changes with it, so the next
  // collide finds every pair again instead of carrying sleeping ones over (pairs_dirty).
  void setCollides(int a, int b, bool collides) {
    const int hi = std::max(a, b);
    std::vector<int>& v = bodies[std::min(a, b)].no_collide;
    const auto it = std::lower_bound(v.begin(), v.end(), hi);
    const bool listed = it != v.end() && *it == hi;
    if (collides && listed) v.erase(it);
    else if (!collides && !listed) v.insert(it, hi);
    pairs_dirty = true;
  }
  bool neverCollide(int a, int b) const {
    const std::vector<int>& v = bodies[std::min(a, b)].no_collide;
    return std::find(v.begin(), v.end(), std::max(a, b)) != v.end();
  }
  void forgetBoxes(int b) {
    for (int s : bodies[b].shape_ids)
      if (s < int(aabb_kept.size())) aabb_kept[s] = 0;
    if (bodies[b].def.type == BodyType::Static && !bodies[b].shape_ids.empty())
      static_dirty = true;
  }
  // A shape of body b was added or removed (collide.hpp's lists; the static tree for a static b).
  void shapesChanged(int b) {
    shape_lists_dirty = true;
    if (bodies[b].def.type == BodyType::Static) static_dirty = true;
  }

  // collide.cpp
  void rebuildShapeLists();
  void collide(double dt);
  void orderPairs(int count);
  // shape_boxes.cpp: shape s's frame and box, grown by the speculative distance and its body's
  // step; the moving shapes' (each kept while its body sleeps; carry: sleeping ones frozen).
  void computeBox(int s, double dt);
  void movingBoxes(double dt, bool carry);
  void applyPairMaterial(Contact& c, const ShapeDef& da, const ShapeDef& db) const;

  // island_schedule.cpp
  void scheduleIslands();
  void buildIslands();
  void collectActiveJoints();
  void partitionIslands();
  void attachToSplitHalves();
  void assignThreadRuns();
  // f(half k of split island r), then f(each island attached to that half).
  template <class F>
  void withAttached(const IslandRange& r, const IslandRange& half, int k, F&& f) {
    f(half);
    for (int a = r.attach[k]; a < r.attach[k + 1]; ++a) f(island_ranges[attached_islands[a]]);
  }

  // island_solve.cpp
  StepContexts makeContexts(double dt);
  void chooseRows(StepContexts& ctx) const;
  class IslandPass;  // one island's substep sequence on this thread (island_solve.cpp)
  void prepareSolverBody(int i);  // integrate.cpp
  // island_bodies[begin, end) in c's solver bodies, integrate.cpp
  void prepareSolverBodies(int begin, int end, const StepContext& c);
  void finishPoses(int begin, int end, const StepContext& c);
  void prepareOutsideBodies();
  void prepareIsland(const IslandRange& p, const StepContext& c);
  // f(each island of p) when p is several whole islands solved as one range, else f(p): the
  // joint trees are built and solved island by island.
  template <class F>
  void forIslands(const IslandRange& p, F&& f) const {
    if (p.island_end - p.island_begin < 2) return f(p);
    for (int k = p.island_begin; k < p.island_end; ++k) f(island_ranges[k]);
  }
  void integrateVelocities(const StepContext& c, int begin, int end);  // integrate.cpp
  void integratePositions(const StepContext& c, int begin, int end);   // integrate.cpp
  void solveIsland(const IslandRange& r, const StepContext& ctx) { solveIsland(r, ctx, ctx); }
  void solveIsland(const IslandRange& r, const StepContext& ctx, const StepContext& shared);
  StepContext onTeamBodies(StepContext c, int t);
  void findSplitShared(const IslandRange& r, int k);
  void shareSplitBodies(const StepContext& from, const StepContext& to, int t, int nt,
                        bool whole);
  void restitute(int begin, int end, const StepContext& c);
  void finishIslandBodies(const IslandRange& p, const StepContext& c);
  void solveSplitIsland(const IslandRange& r, const StepContexts& ctx);
  void solveIslands(const StepContexts& ctx);

  // fault_guard.cpp
  void guardInputs();
  void finishBody(int i);
  void finishMotion(int i, const SolverBody& s);  // finishBody after the pose
  void finishOutsideBodies();
  void resetFaulted();
  void finishStep();
  void resetBody(int b, BodyFaultCause cause);
  void clearWarmStart();

  // sleep.cpp
  bool islandResting(const IslandRange& r) const;
  void markResting(bool rest_mode);
  bool sleepIsland(const int* ids, int n, bool resting, double dt);
  void sleepIslands(const IslandRange& p, double dt);
  void updateSleep(double dt);

  // substep_samples.cpp (each only while something is tracked)
  void beginSamples(const StepContexts& ctx, bool solved);
  void sampleSubstep(const IslandRange& p, int sub, const std::vector<SolverBody>& solver);
  void sampleFinish(const IslandRange& p);
  void untrack(int body);

  // world_create.cpp
  void breakJoints();
  void removeJoint(int k);
  // Erases the contacts for which drop(c) holds, waking the bodies of the touching ones.
  template <class Pred>
  void removeContacts(Pred&& drop);
  // The joint's type struct takes its own fields from the def (joint_<type>.cpp).
  template <class Def>
  JointId addJoint(const char* type, const Def& def) {
    checkJointDef(type, def);
    checkBody(def.body_a);
    checkBody(def.body_b);
    if (def.body_a == def.body_b)
      throw std::invalid_argument("ragdoll_sim: a joint needs two different bodies");
    wake(def.body_a.index);
    wake(def.body_b.index);
    if (!def.collide_connected) setCollides(def.body_a.index, def.body_b.index, false);
    joints.push_back(Joint(def));  // may move every joint: active_joints points into them
    joint_alive.push_back(1);
    schedule_fresh = false;
    return JointId{int32_t(joints.size() - 1)};
  }
};

}  // namespace ragdoll_sim
