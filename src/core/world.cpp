// World: storage and the step pipeline.
//
// step(dt) (Box2D v3 soft step, in 3D):
//   1. collide: broadphase pairs -> narrowphase manifolds at the poses of the step start,
//      each pair in a frame at its dynamic body's centre (translation invariance, body.hpp)
//      (boxes, the sweep's pair loop with the pair filter, and the pairs in parallel;
//      separated pairs skipped by their cached axis, touching pairs that barely moved keep
//      their manifold, manifold_cache.hpp); impulses carried over by feature id (warm
//      starting; scaled by h / h_old where the substep changed, warmStartScale);
//   2. islands (island.hpp): awake bodies, joints and contacts grouped per island; substep
//      h = dt / substeps (rest_substeps, with rest_relax_iterations relax sweeps, for an island
//      whose bodies have all been slow for SleepDef::rest_time; a split island with the
//      islands attached to its halves, which share its substep loop);
//   3. per island (islands in parallel, WorldDef::threads, each thread a run of consecutive
//      islands, see partitionIslands, then what the other runs have left, run_queue.hpp,
//      which it prepares (solver bodies, joints, contacts, each into its own slot) and
//      solves; each island in a fixed order, so the result does not depend on the thread
//      count; an island of kSplitMin bodies or more that holds more than half the awake
//      work is split in two halves: each sweep solves its boundary contacts on one thread,
//      then both halves at once, see island_split.hpp), per substep: integrate velocities
//      (gravity, forces, damping), warm start, solve with bias (soft), integrate
//      positions, relax without bias (contacts several sweeps, the joints in the first
//      sweeps: Gauss-Seidel over a manifold's points and along a limb needs them to take back
//      the push-out velocity and to carry a landing's load up the chain, see
//      contact_solver.cpp); then
//      position_iterations sweeps of position projection (contacts, joint limits and angular
//      rows, joint anchors), which remove the error beyond the slops (linear_slop, angular_slop,
//      joint_slop) without touching velocities, and anchor_iterations sweeps over the joint
//      anchors alone. Static bodies are shared by all islands and are never written
//      (movable(), solver_context.hpp);
//   4. per island, on the thread that solved it: restitution, store impulses, write the
//      deltas back to the bodies, clear forces (a body left non-finite is reset after);
//   5. islands that stayed slow long enough go to sleep. Sleeping bodies are identity solver
//      bodies: not integrated, and pairs of them are not collided or solved; their shapes keep
//      their boxes. Once a full step has found no body awake, the next steps only advance the
//      time until something is built, woken, set or reset (World::Impl::settled).
// Fault guard (around the pipeline): before step 1 every body whose state, force or torque is
// not finite goes back to its last finite pose (kept per body, no allocation) with zero
// velocity, and every velocity is clamped to the caps (a huge impulse never reaches the
// solver); after step 4 a body the solver left non-finite is reset the same way, and the
// warm-start impulses of its joints and contacts are cleared. Each reset is a BodyFault.
// Semi-implicit Euler: v += h a first, then x += h v with the new v (and the same for the
// rotation, q += h/2 (0,w) q, renormalised, with the gyroscopic update in integratePositions).
#include "ragdoll_sim/world.hpp"

#include "ragdoll_sim/range_check.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#ifdef _OPENMP
#include <omp.h>
#endif

#include "body.hpp"
#include "broadphase.hpp"
#include "contact.hpp"
#include "contact_solver.hpp"
#include "gjk.hpp"
#include "group_by.hpp"
#include "island.hpp"
#include "island_split.hpp"
#include "joint.hpp"
#include "manifold_cache.hpp"
#include "run_queue.hpp"
#include "team_barrier.hpp"

namespace ragdoll_sim {

namespace {
// Below this many pairs / awake bodies a step is too short to gain from waking other threads
// (the fork-join costs microseconds, and much more when the cores are busy). Two ragdolls
// (30 bodies, ~130 us per step) are about where two threads start to pay: 4 ragdolls on 2
// threads ran 1.4x faster with 32 than with 128 here.
constexpr int kParallelMin = 32;
// An island with at least this many awake bodies, and more than half the awake work (bodies,
// joints, contacts), is split in two (island_split.hpp). Its ~22 boundary sweeps per step wait
// at two barriers each (TeamBarrier); timed inside scene c's 5,000 steps (the pile split from
// ~0.7 s), thread 0 waited 10 us per step and thread 1 14.5 us, 0.24 and 0.35 us per wait:
// mostly the halves' imbalance, not the barrier itself (its header). The substeps of 60 bodies
// take ~120 us on one thread. A smaller share needs no split: the runs of whole islands already
// balance the threads, and a split island takes every other island along in lockstep with its
// halves (attachToSplitHalves), sweep by sweep instead of one island at a time, so each sweep
// streams all of their constraints through the cache (64 ragdolls on the ground, one 60-body
// island among 48, 2 threads: 1.85 ms per step split, 1.52 ms not). The test depends only on
// the islands, not on the thread count, so the result stays the same for every count.
constexpr int kSplitMin = 60;

// This thread's number and the team's size in the enclosing parallel region ({0, 1} outside).
std::pair<int, int> teamSlot() {
#ifdef _OPENMP
  return {omp_get_thread_num(), omp_get_num_threads()};
#else
  return {0, 1};
#endif
}

// One test instead of one per component: NaN or inf anywhere makes the sum non-finite. Finite
// values whose sum overflows fall through to the exact check.
bool motionFinite(const BodyMotion& m) {
  if (std::isfinite(m.x.sum() + m.q.coeffs().sum() + m.v.sum() + m.w.sum())) return true;
  return m.x.allFinite() && m.q.coeffs().allFinite() && m.v.allFinite() && m.w.allFinite();
}

bool inputsFinite(const BodyMotion& m) {
  if (std::isfinite(m.force.sum() + m.torque.sum())) return motionFinite(m);
  return m.force.allFinite() && m.torque.allFinite() && motionFinite(m);
}

// Scales a finite v down to length `max` when longer (also when its norm overflows). The
// squared test first: it spares the square root for nearly every call (two per awake body and
// substep).
void clampNorm(Vec3& v, double max) {
  if (v.squaredNorm() <= max * max) return;
  double n = v.norm();
  if (n <= max) return;
  if (!std::isfinite(n)) n = v.stableNorm();
  v *= max / n;
}


}  // namespace

struct ShapeRef {
  int body;
  int index;  // in Body::shapes
};

struct World::Impl {
  WorldDef def;
  double time = 0.0;
  std::vector<Body> bodies;
  std::vector<BodyMotion> motions;
  std::vector<SolverBody> solver;
  // Per body: the rotation matrix of dq q, its world rotation at the current substep (set with
  // the solver body, advanced by integratePositions; only that reads it).
  std::vector<Mat3> rotations;
  std::vector<ShapeRef> shapes;
  std::vector<Joint> joints;
  Broadphase broadphase;
  std::vector<Contact> contacts, next_contacts;
  std::vector<uint64_t> contact_keys;  // contacts[k].key, sorted
  std::vector<uint64_t> carried_keys, merged_keys;
  std::vector<char> frozen;  // per shape: box or plane as in the last step (collide)
  std::vector<PlaneProxy> last_planes;
  // The broadphase filter changed (pairs enabled or disabled): the next collide finds every
  // pair again instead of carrying sleeping ones over.
  bool pairs_dirty = true;
  // Per contact (same index): its manifold in the shapes' frames (manifold_cache.hpp).
  std::vector<ManifoldCache> manifold_caches, next_manifold_caches;
  ContactSolver contact_solver;
  Islands islands;
  // scratch, reused every step
  std::vector<Aabb> aabbs;
  // Per shape: its box in aabbs is that of the current pose, kept while the body is static or
  // asleep (such a body has zero velocity and does not move, so the box is recomputed only
  // after the body woke, was set or was reset).
  std::vector<char> aabb_kept;
  // Per shape: its shapeFrame, formed in collide (a bounded shape's with its box, and kept with
  // it; a plane's every step) and read by each pair's narrowphase frame (shapePoseFrom), which
  // only adds the centre's offset from the pair's origin (scene c: composing the body and shape
  // transforms per pair was 5 % of a step).
  std::vector<Transform> shape_frames;
  // The last step found no body awake and ran the whole pipeline, and nothing has been built,
  // woken, set or reset since: the next step would give the same contacts and move nothing,
  // so it only advances the time (a world whose ragdolls all sleep costs almost nothing).
  bool settled = false;
  std::vector<char> unbounded;
  std::vector<PlaneProxy> planes;
  std::vector<std::pair<int, int>> pairs;
  std::vector<uint64_t> pair_keys;
  std::vector<double> island_slow;
  std::vector<Joint*> active_joints;  // grouped by island after partitionIslands()
  std::vector<JointId> broken_events;
  // This step's awake islands: ranges into island_bodies, active_joints and the contact
  // solver's constraints.
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
    bool resting = false;  // takes SleepDef::rest_substeps (World::step)
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
  IslandSplitter splitter;
  TeamBarrier team_barrier;  // the two threads of a split island
  // Whether each thread of a split island moved a body in a position sweep, by the sweep's
  // parity (solveIsland).
  char position_moved[2][2] = {};
  std::vector<IslandRange> island_ranges;
  std::vector<int> island_runs;  // thread t solves islands [island_runs[t], island_runs[t + 1])
  RunQueue run_queue;            // ... and then steals what is left of the others' runs
  std::vector<int> attached_islands;  // grouped by split island and half (IslandRange::attach)
  std::vector<std::pair<int, int>> attach_scratch;
  std::vector<long> island_load;
  long run_work = 0;  // work of the islands in runs (none when all go along with split ones)
  std::vector<int> island_split_of_slot;
  std::vector<int> island_bodies, island_of_body, group_offsets, group_cursor, body_scratch;
  std::vector<Joint*> joint_scratch;
  std::vector<int> contact_index_scratch;
  std::vector<int> old_contact;
  // Fault guard: per body its last finite pose (saved before and after each step; a reset
  // zeroes the velocity, so none is kept), faults not yet taken, bodies reset by this step's
  // solver.
  struct FinitePose {
    Vec3 x;
    Quat q;
  };
  std::vector<FinitePose> last_finite;
  std::vector<BodyFault> faults;
  int64_t fault_count = 0;
  std::vector<char> solver_reset;
  bool any_solver_reset = false;
  std::vector<char> solver_fault;  // finishBody left it non-finite: resetFaulted resets it

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
  void checkBody(BodyId id) const {
    if (id.index < 0 || id.index >= int(bodies.size()))
      throw std::out_of_range("ragdoll_sim: invalid body id");
  }
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
  bool isDynamic(int b) const { return bodies[b].def.type == BodyType::Dynamic; }
  void wake(int b) {
    settled = false;  // also for a static body: setBodyState moves it through here
    if (!isDynamic(b)) return;
    motions[b].awake = true;
    motions[b].sleep_time = 0.0;
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
  }

  void collide(double dt);
  void partitionIslands();
  void attachToSplitHalves();
  // f(half k of split island r), then f(each island attached to that half).
  template <class F>
  void withAttached(const IslandRange& r, const IslandRange& half, int k, F&& f) {
    f(half);
    for (int a = r.attach[k]; a < r.attach[k + 1]; ++a) f(island_ranges[attached_islands[a]]);
  }
  void solveIsland(const IslandRange& r, const StepContext& ctx);
  // Every body of r has been slow for rest_time (SleepDef::rest_substeps).
  bool islandResting(const IslandRange& r) const {
    for (int k = r.body_begin; k < r.body_end; ++k)
      if (!(motions[island_bodies[k]].sleep_time >= def.sleep.rest_time)) return false;
    return true;
  }
  void integrateVelocities(double h, int begin, int end);
  void integratePositions(double h, int begin, int end);
  // The solver body of body i at the step start: an awake body's velocities, inverse mass
  // and world inverse inertia, an identity state for the others.
  void prepareSolverBody(int i) {
    const BodyMotion& m = motions[i];
    SolverBody& s = solver[i];
    if (!m.awake) {
      s = SolverBody();
      return;
    }
    const Mat3& R = rotations[i] = m.q.toRotationMatrix();
    s.dp.setZero();
    s.dq = Quat::Identity();
    s.moved_sweep = 0;
    s.v = m.v;
    s.w = m.w;
    s.inv_mass = m.inv_mass;
    s.inv_inertia = R * m.inv_inertia_local * R.transpose();
  }
  void finishBody(int i);
  void resetFaulted();
  void finishStep();
  void guardInputs();
  void resetBody(int b, BodyFaultCause cause);
  void clearWarmStart();
  void buildIslands();
  void breakJoints();
  void updateSleep(double dt);
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
    joints.push_back(Joint(def));
    return JointId{int32_t(joints.size() - 1)};
  }
};

void World::Impl::collide(double dt) {
  const int n = int(shapes.size());
  aabbs.resize(n);
  aabb_kept.resize(n, 0);
  shape_frames.resize(n);
  unbounded.resize(n);
  frozen.resize(n);
  const bool carry = def.carry_sleeping_pairs && !pairs_dirty;
  const double spec = def.speculative_distance;
  // Boxes in parallel (each shape its own slot), the few planes after.
#pragma omp parallel for schedule(static) num_threads(threadCount()) if (n >= kParallelMin)
  for (int s = 0; s < n; ++s) {
    const Geometry& g = shapeDef(s).geometry;
    const BodyMotion& m = motions[shapes[s].body];
    unbounded[s] = isUnbounded(g);
    frozen[s] = carry && !unbounded[s] && !m.awake && aabb_kept[s];
    if (unbounded[s] || (!m.awake && aabb_kept[s])) continue;
    aabb_kept[s] = !m.awake;
    const Transform& f = shape_frames[s] = shapeFrame(s);
    Aabb box = computeAabb(g, {m.x + f.p, f.q});
    const Vec3 grow = Vec3::Constant(spec) + (m.v * dt).cwiseAbs();
    box.lo -= grow;
    box.hi += grow;
    aabbs[s] = box;
  }
  planes.swap(last_planes);
  planes.clear();
  for (int s = 0; s < n; ++s) {
    if (!unbounded[s]) continue;
    const Transform& f = shape_frames[s] = shapeFrame(s);
    const Vec3 nw = f.q * shapeDef(s).geometry.normal;
    const Vec3 p = motions[shapes[s].body].x + f.p;  // world
    planes.push_back({s, nw, shapeDef(s).geometry.offset + nw.dot(p)});
    const size_t k = planes.size() - 1;  // frozen: the same plane as in the last step
    const PlaneProxy* last = k < last_planes.size() ? &last_planes[k] : nullptr;
    frozen[s] = carry && last && last->shape == s && last->normal == nw &&
                last->offset == planes.back().offset;
  }
  // Keep pairs between different bodies, at least one dynamic, not disabled (checked inside
  // the broadphase, on its threads); sort by key to merge with last step's contacts (also
  // sorted by key). The keys are sorted, not the contacts (a Contact is ~400 bytes).
  // A pair of two frozen shapes (boxes and planes as in the last step, which sleeping bodies
  // keep) overlaps now iff it did then, and the filter has not changed since (pairs_dirty):
  // such pairs are carried over from the last step's keys instead of found and filtered again.
  // (256 ragdolls of which one is awake: finding and filtering them was ~45 % of a step.)
  // With few frozen shapes (every ragdoll awake, static walls) the broadphase's frozen test
  // costs more than it saves (scene p: +0.6 % instructions): then nothing is carried.
  const bool carry_now = carry && 4 * std::count(frozen.begin(), frozen.end(), char(1)) >= n;
  if (carry && !carry_now) std::fill(frozen.begin(), frozen.end(), char(0));
  const auto accept = [this](int sa, int sb) {
    const int ba = shapes[sa].body, bb = shapes[sb].body;
    return ba != bb && (isDynamic(ba) || isDynamic(bb)) && !neverCollide(ba, bb);
  };
  broadphase.findPairs(aabbs, unbounded, planes, spec, pairs, accept, threadCount(),
                       carry_now ? &frozen : nullptr);
  pairs_dirty = false;
  pair_keys.clear();
  for (const auto& [sa, sb] : pairs) pair_keys.push_back(pairKey(sa, sb));
  sortPairKeys(pair_keys, n, merged_keys, group_offsets, group_cursor);  // scratch: merged_keys
  carried_keys.clear();
  if (carry_now)
    for (const uint64_t key : contact_keys)
      if (frozen[int(key >> 32)] && frozen[int(uint32_t(key))]) carried_keys.push_back(key);
  if (!carried_keys.empty()) {
    merged_keys.resize(pair_keys.size() + carried_keys.size());
    std::merge(pair_keys.begin(), pair_keys.end(), carried_keys.begin(), carried_keys.end(),
               merged_keys.begin());
    pair_keys.swap(merged_keys);
  }
  // Sized only: every contact is reset in the parallel loop below (a Contact is ~400 bytes, and
  // constructing them serially was ~15 us of a 32-ragdoll step).
  next_contacts.resize(pair_keys.size());
  next_manifold_caches.resize(pair_keys.size());

  // Merge with last step's contacts (both sorted by key), then run the narrowphase on each
  // pair independently (in parallel; each writes only its own contact).
  old_contact.assign(pair_keys.size(), -1);
  size_t old = 0;
  const size_t old_count = contact_keys.size();  // contacts[k].key: 8 bytes apart, not ~400
  for (size_t i = 0; i < pair_keys.size(); ++i) {
    while (old < old_count && contact_keys[old] < pair_keys[i]) ++old;
    if (old < old_count && contact_keys[old] == pair_keys[i]) old_contact[i] = int(old);
  }
  const int count = int(next_contacts.size());
  // Manifold cache (manifold_cache.hpp): a feature a kept manifold lacks is at least
  // (speculative - cache distance) away, so both bodies must move less than that in the step,
  // (|v| + extent |w|) dt, for it not to be reached unseen. (Separated pairs need no such
  // check: the collision at the step start decides the step's contacts.)
  const double cache_distance = def.manifold_cache_distance;
  const bool cache_on = cache_distance > 0.0 && cache_distance < spec;
  const double cache_speed = (spec - cache_distance) / dt;
  const auto slow = [&](int b) {
    const BodyMotion& m = motions[b];
    return m.v.norm() + m.extent * m.w.norm() <= cache_speed;
  };
#pragma omp parallel for schedule(static) num_threads(threadCount()) if (count >= kParallelMin)
  for (int i = 0; i < count; ++i) {
    Contact& c = next_contacts[i];
    ManifoldCache& cache = next_manifold_caches[i];
    const int o = old_contact[i];
    const int sa = int(pair_keys[i] >> 32), sb = int(uint32_t(pair_keys[i]));
    const int ba = shapes[sa].body, bb = shapes[sb].body;
    const bool asleep = !motions[ba].awake && !motions[bb].awake;
    if (o >= 0 && asleep) {  // the manifold and impulses stay as they were
      c = contacts[o];
      cache = manifold_caches[o];
      continue;
    }
    // The pair is collided in a frame at the centre of its (first) dynamic body: the
    // manifold's points are relative to it (Contact::origin).
    const Vec3 origin = motions[isDynamic(ba) ? ba : bb].x;
    const Transform xa = shapePoseFrom(sa, origin), xb = shapePoseFrom(sb, origin);
    // Kept (manifold_cache.hpp): a separated pair still beyond the band, or a touching pair
    // whose manifold moves along with the shapes (ids and impulses stay).
    if (o >= 0 && manifold_caches[o].valid &&
        (manifold_caches[o].separated() || (slow(ba) && slow(bb))) &&
        manifold_caches[o].holds(xa, xb, cache_distance)) {
      c = contacts[o];
      cache = manifold_caches[o];
      if (!cache.separated()) {
        c.origin = origin;
        cache.apply(shapeDef(sa).geometry, xa, shapeDef(sb).geometry, xb, c.manifold);
        c.sep_axis = c.manifold.normal;
      }
      continue;
    }
    c = Contact();
    c.key = pair_keys[i];
    c.shape_a = sa;
    c.shape_b = sb;
    c.body_a = ba;
    c.body_b = bb;
    c.origin = origin;
    cache.valid = false;
    if (asleep) continue;
    const ShapeDef &da = shapeDef(sa), &db = shapeDef(sb);
    if (o >= 0 && contacts[o].sep_valid) {
      const np::ConvexCore ca{&da.geometry, xa}, cb{&db.geometry, xb};
      const Vec3& n = contacts[o].sep_axis;
      const double gap = n.dot(cb.support(-n)) - cb.radius() - n.dot(ca.support(n)) - ca.radius();
      if (gap > spec) {
        c.sep_axis = n;
        c.sep_valid = true;
        c.manifold.count = 0;
        continue;
      }
    }
    // Last step's normal of the pair (kept as sep_axis) starts GJK near its answer.
    const Vec3* guess = o >= 0 ? &contacts[o].sep_axis : nullptr;
    ragdoll_sim::collide(da.geometry, xa, db.geometry, xb, spec, c.manifold, guess);
    cache.store(c.manifold, da.geometry, xa, db.geometry, xb, spec, cache_on);
    // Cache the normal of a separated pair as its axis (not for planes: they are cheap).
    c.sep_valid = c.manifold.count == 0 && !unbounded[sa] && !unbounded[sb];
    c.sep_axis = c.manifold.normal;
    const Material pair = def.materials.resolve(da.material, db.material);
    c.static_friction = pair.static_friction;
    c.kinetic_friction = pair.kinetic_friction;
    c.restitution = pair.restitution;
    c.rolling = pair.rolling_resistance > 0.0
                    ? pair.rolling_resistance * std::max(rollingRadius(da.geometry), rollingRadius(db.geometry))
                    : 0.0;
    matchImpulses(o >= 0 ? contacts[o] : Contact(), c);
  }
  manifold_caches.swap(next_manifold_caches);
  contacts.swap(next_contacts);
  contact_keys.swap(pair_keys);
}

void World::Impl::integrateVelocities(double h, int begin, int end) {
  for (int k = begin; k < end; ++k) {
    const int i = island_bodies[k];
    const BodyMotion& m = motions[i];
    SolverBody& s = solver[i];
    const Vec3 a = m.gravity_scale * def.gravity + m.inv_mass * m.force;
    s.v = (s.v + h * a) / (1.0 + h * m.linear_damping);
    s.w = (s.w + h * (s.inv_inertia * m.torque)) / (1.0 + h * m.angular_damping);
    // Clamped per substep as well as at the step end (as Box2D v3 does): a torque at the
    // command cap on a light link (1e5 N m on a foot: 2.5e4 rad/s per substep) otherwise spins
    // it so fast within one step that the joints fling their neighbours to 1e7 m, then NaN.
    clampNorm(s.v, def.max_linear_speed);
    clampNorm(s.w, def.max_angular_speed);
  }
}

// The rotation advances with w; then w is recomputed from the world angular momentum
// L = R I R^T w, which free rotation conserves: w' = R' I^-1 R'^T L. This is the gyroscopic
// term (precession, the middle-axis flip) and keeps L exact in free flight. Two loops: the
// first parks L in w, the second turns it back; each body's chain (a square root and a division
// in the middle) is then short enough for the core to overlap bodies (scene b on one thread:
// 7.4 -> 5.9 % of perf's samples, bit-identical).
void World::Impl::integratePositions(double h, int begin, int end) {
  for (int k = begin; k < end; ++k) {
    const int i = island_bodies[k];
    const BodyMotion& m = motions[i];
    SolverBody& s = solver[i];
    Mat3& R = rotations[i];
    s.dp += h * s.v;
    const Vec3 L = R * (m.inertia_local * (R.transpose() * s.w));
    const Vec3 hw = 0.5 * h * s.w;
    Quat dq = s.dq;
    dq.coeffs() += (Quat(0, hw.x(), hw.y(), hw.z()) * s.dq).coeffs();
    s.dq = dq.normalized();
    R = (s.dq * m.q).toRotationMatrix();
    s.w = L;  // parked
  }
  for (int k = begin; k < end; ++k) {
    const int i = island_bodies[k];
    SolverBody& s = solver[i];
    const Mat3& R = rotations[i];
    s.w = R * (motions[i].inv_inertia_local * (R.transpose() * s.w));
  }
}

// An awake body takes the step's deltas and velocities; forces are cleared. A body the
// solver left non-finite is only marked here (islands finish on their own threads):
// resetFaulted resets the marked ones, in body order.
void World::Impl::finishBody(int i) {
  BodyMotion& m = motions[i];
  const SolverBody& s = solver[i];
  if (m.awake) {
    const Vec3 d = s.dp + m.x_carry;
    const Vec3 on_grid = snapPosition(d);
    m.x_carry = d - on_grid;  // exact
    m.x += on_grid;           // exact: both on the grid
    m.q = (s.dq * m.q).normalized();
    m.v = s.v;
    m.w = s.w;
    if (motionFinite(m)) {
      clampNorm(m.v, def.max_linear_speed);
      clampNorm(m.w, def.max_angular_speed);
      last_finite[i] = {m.x, m.q};
    } else {
      solver_fault[i] = 1;
    }
  }
  m.force.setZero();
  m.torque.setZero();
}

void World::Impl::resetFaulted() {
  for (size_t i = 0; i < bodies.size(); ++i)
    if (solver_fault[i]) {
      solver_fault[i] = 0;
      resetBody(int(i), BodyFaultCause::Solver);
    }
}

void World::Impl::finishStep() {
  for (size_t i = 0; i < bodies.size(); ++i) finishBody(int(i));
  resetFaulted();
}

// Before the step: what was set since the last one (impulses, forces, setBodyState) must be
// finite, and velocities are clamped. A finite pose is the body's last finite one (it may come
// from setBodyState); a body with a bad velocity, force or torque keeps it.
void World::Impl::guardInputs() {
  for (size_t i = 0; i < bodies.size(); ++i) {
    BodyMotion& m = motions[i];
    if (inputsFinite(m)) {
      clampNorm(m.v, def.max_linear_speed);
      clampNorm(m.w, def.max_angular_speed);
      last_finite[i] = {m.x, m.q};
      continue;
    }
    if (m.x.allFinite() && m.q.coeffs().allFinite()) last_finite[i] = {m.x, m.q};
    resetBody(int(i), BodyFaultCause::Input);
  }
}

void World::Impl::resetBody(int b, BodyFaultCause cause) {
  settled = false;
  forgetBoxes(b);
  BodyMotion& m = motions[b];
  m.x = last_finite[b].x;
  m.x_carry.setZero();
  m.q = last_finite[b].q;
  m.v.setZero();
  m.w.setZero();
  m.force.setZero();
  m.torque.setZero();
  ++fault_count;
  if (faults.size() < World::kMaxPendingFaults) faults.push_back({BodyId{b}, cause, time});
  if (cause == BodyFaultCause::Solver) {
    solver_reset[b] = 1;
    any_solver_reset = true;
  }
}

// After a solver fault the impulses accumulated by the reset bodies' joints and contacts are
// garbage (NaN) and would poison the next warm start. prepareJoint rebuilds everything else in
// the parts each step, so fresh parts lose only the impulses.
void World::Impl::clearWarmStart() {
  for (Joint& j : joints)
    if (solver_reset[j.a] || solver_reset[j.b]) j.clearWarmStart();
  for (Contact& c : contacts) {
    if (!solver_reset[c.body_a] && !solver_reset[c.body_b]) continue;
    for (int i = 0; i < Manifold::kMaxPoints; ++i) {
      c.normal_impulse[i] = 0.0;
      c.friction_impulse[i].setZero();
    }
    c.rolling_impulse.setZero();
    c.sep_valid = false;
  }
  std::fill(solver_reset.begin(), solver_reset.end(), 0);
  any_solver_reset = false;
}

// A joint whose anchor force reached its limit breaks (a rigid anchor never transmits more
// than break_force: its impulse is capped at break_force h). solveIsland marks it broken at
// the end of the substep, which drops it from the solver; here, after the islands, the pair
// collides again and the event is recorded. The bodies keep their momentum.
void World::Impl::breakJoints() {
  bool any = false;
  for (Joint* j : active_joints) {
    if (!j->broken) continue;
    any = true;
    setCollides(j->a, j->b, true);
    broken_events.push_back(JointId{int32_t(j - joints.data())});
  }
  if (any)
    active_joints.erase(std::remove_if(active_joints.begin(), active_joints.end(),
                                       [](const Joint* j) { return j->broken; }),
                        active_joints.end());
}

// Numbers the awake islands by their first body and groups bodies, joints and contact
// constraints by island, so each island is a contiguous range of each.
void World::Impl::partitionIslands() {
  const int n = int(bodies.size());
  island_of_body.assign(n, -1);
  std::vector<int>& slot = group_offsets;  // island root -> island index (reused below)
  slot.assign(n, -1);
  int count = 0;
  island_bodies.clear();
  for (int i = 0; i < n; ++i) {
    if (!isDynamic(i) || !motions[i].awake) continue;
    int& k = slot[islands.find(i)];
    if (k < 0) k = count++;
    island_of_body[i] = k;
    island_bodies.push_back(i);
  }
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
  // The contacts are grouped as indices before they are prepared: a constraint is ~1.9 kB.
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
  // Each thread takes a run of consecutive islands (in body order) of about equal work, the
  // same run step after step while the islands last: its bodies and constraints stay in that
  // core's cache. (Handing out islands dynamically, biggest first, moved them between the
  // cores: scene b ran 12 % slower on 2 threads.) A thread done with its run takes what is
  // left of the others' from their back (run_queue.hpp).
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

// With a split island, the whole islands go along with its halves instead of into runs: each,
// in order, to the half with the least work so far (its bodies, joints and contacts plus its
// boundary group's). The threads wait for each other at every boundary sweep, and the thread
// of the lighter half (scene c: the upper ragdolls of the pile, 95 against 129 us per step)
// now solves, e.g., a ragdoll that lies apart in that time, instead of after the split island
// while the other thread idles. An attached island goes through the same substep sequence as
// alone, in lockstep with the half, so the result does not change. With more than two threads
// (a split island takes two) an island only fills a lighter half up to the other's work: the
// runs spread the rest over all threads.
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

// The substep loop for one island; touches only the island's bodies and constraints. A split
// island is solved by the team of the enclosing parallel region. Each sweep first solves the
// boundary contacts, its two groups at once (they share no body), then the threads take the
// halves (with one thread: the same work in the same order); the halves' joints thus follow
// the boundary's impulses in every sweep, as they follow the contacts in a sweep of a whole
// island. Work on the halves alone needs no barrier: they touch disjoint bodies. Thread k
// always takes half k and boundary group k, so their constraints stay in its core's cache.
void World::Impl::solveIsland(const IslandRange& r, const StepContext& ctx) {
  Joint* const* js = active_joints.data();
  const IslandRange halves[2] = {r.half(0), r.half(1)};
  const std::pair<int, int> slot = teamSlot();  // read by a split island's sweeps only
  const int t = slot.first, nt = slot.second;
  const auto parts = [&](auto&& part) {
    if (!r.split) return part(r);
    for (int k = t; k < 2; k += nt) withAttached(r, halves[k], k, part);
  };
  const auto boundary = [&](auto&& contacts) {
    if (!r.split) return;
    team_barrier.wait(t, nt);
    for (int k = t; k < 2; k += nt) contacts(r.boundaryBegin(k), r.boundaryEnd(k));
    team_barrier.wait(t, nt);
  };
  const auto joints = [&](const IslandRange& p, auto&& f) {
    for (int k = p.joint_begin; k < p.joint_end; ++k)
      if (!js[k]->broken) f(*js[k]);
  };
  const int relax = ctx.relax;
  for (int sub = 0; sub < ctx.substeps; ++sub) {
    // From the second substep on, the first relax sweep of the last one (if any) already set
    // the separations at the current deltas.
    const bool moved = sub == 0 || relax < 1;
    parts([&](const IslandRange& p) {
      integrateVelocities(ctx.h, p.body_begin, p.body_end);
      joints(p, [&](Joint& j) { warmStartJoint(j, ctx, sub == 0); });
      contact_solver.warmStart(ctx, p.contact_begin, p.contact_end, moved);
    });
    boundary([&](int b, int e) {
      contact_solver.warmStart(ctx, b, e, moved);
      contact_solver.solve(ctx, true, b, e, false);
    });
    parts([&](const IslandRange& p) {
      joints(p, [&](Joint& j) { solveJoint(j, ctx, true); });
      contact_solver.solve(ctx, true, p.contact_begin, p.contact_end, false);
      integratePositions(ctx.h, p.body_begin, p.body_end);
      joints(p, [&](Joint& j) { advanceJoint(j, ctx); });
    });
    for (int it = 0; it < relax; ++it) {
      boundary([&](int b, int e) { contact_solver.solve(ctx, false, b, e, it == 0); });
      parts([&](const IslandRange& p) {
        if (it < def.joint_relax_iterations)
          joints(p, [&](Joint& j) { solveJoint(j, ctx, false); });
        contact_solver.solve(ctx, false, p.contact_begin, p.contact_end, it == 0);
      });
    }
    parts([&](const IslandRange& p) {  // reads only the joint
      for (int k = p.joint_begin; k < p.joint_end; ++k)
        if (breaksAfterSubstep(*js[k], ctx)) js[k]->broken = true;
    });
  }
  // Position sweeps. A sweep that moved no body leaves the next ones nothing to do: they see
  // the same poses and recompute the same angles, so the projection stops there, the anchor
  // sweeps too (the result is the same bit for bit). Most sweeps are such (scene b: 65 % of
  // them, c: 60 %; b -2.75 % instructions, c -0.36 %). A split island's threads decide
  // together: each notes whether it moved anything (by the sweep's parity, so that the next
  // sweep's note does not overwrite one still being read) and reads both notes after the
  // barrier that starts the next sweep's boundary.
  // Within a sweep, a projection whose bodies have not moved since its last look, when it
  // moved nothing, is skipped too (unchangedSince, solver_context.hpp; b -1.03 % and c -1.85 %
  // instructions, the same result). Those marks alone would skip every projection after an
  // idle sweep; the stop also saves the pass over the constraints and, on a split island, the
  // sweep's two barriers.
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
    const char* note = position_moved[sweep & 1];
    return std::any_of(note, note + nt, [](char c) { return c != 0; });
  };
  bool moved = true;  // by the last sweep, on any thread
  for (int it = 0; it < def.position_iterations && moved; ++it) {
    mine = false;
    sweep = it + 1;
    if (r.split) {
      team_barrier.wait(t, nt);
      if (it > 0 && !teamMoved(it - 1)) {
        moved = false;
        break;
      }
      for (int k = t; k < 2; k += nt)
        mine |= contact_solver.project(ctx, r.boundaryBegin(k), r.boundaryEnd(k), sweep);
      team_barrier.wait(t, nt);
    }
    parts([&](const IslandRange& p) {
      mine |= contact_solver.project(ctx, p.contact_begin, p.contact_end, sweep);
      for (int k = p.joint_begin; k < p.joint_end; ++k) project(*js[k], sweep, limitsOf);
      anchors(p);
    });
    if (r.split) position_moved[it & 1][t] = mine;
    else moved = mine;
  }
  if (r.split && moved && def.position_iterations > 0 && def.anchor_iterations > 0) {
    team_barrier.wait(t, nt);
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
}

void World::Impl::buildIslands() {
  islands.reset(int(bodies.size()));
  for (const Joint& j : joints)
    if (!j.broken && isDynamic(j.a) && isDynamic(j.b)) islands.unite(j.a, j.b);
  for (const Contact& c : contacts)
    if (c.manifold.count > 0 && isDynamic(c.body_a) && isDynamic(c.body_b))
      islands.unite(c.body_a, c.body_b);
  // An island with one awake body is awake as a whole.
  for (size_t i = 0; i < bodies.size(); ++i)
    if (motions[i].awake) motions[islands.find(int(i))].awake = true;
  for (size_t i = 0; i < bodies.size(); ++i)
    if (isDynamic(int(i)) && !motions[i].awake && motions[islands.find(int(i))].awake) wake(int(i));
}

void World::Impl::updateSleep(double dt) {
  if (!def.sleep.enabled) return;
  const int n = int(bodies.size());
  // island root's sleep_time becomes the island minimum (roots have the smallest index)
  std::vector<double>& slow = island_slow;
  slow.assign(n, 1e300);
  for (int i = 0; i < n; ++i) {
    BodyMotion& m = motions[i];
    if (!m.awake) continue;
    const double speed = std::max(m.v.norm(), m.extent * m.w.norm());  // as Box2D v3
    m.sleep_time = speed < def.sleep.speed ? m.sleep_time + dt : 0.0;
    double& r = slow[islands.find(i)];
    r = std::min(r, m.sleep_time);
  }
  for (int i = 0; i < n; ++i) {
    BodyMotion& m = motions[i];
    if (!m.awake || slow[islands.find(i)] < def.sleep.time) continue;
    m.awake = false;
    m.v.setZero();
    m.w.setZero();
  }
}

World::World(const WorldDef& def) : impl_(new Impl) {
  const std::string e = worldDefError(def);
  if (!e.empty()) throw std::invalid_argument("ragdoll_sim: WorldDef: " + e);
  impl_->def = def;
}
World::~World() = default;

BodyId World::createBody(const BodyDef& def) {
  Impl& w = *impl_;
  Body body;
  body.def = def;
  if (!def.pose.p.allFinite() || !def.pose.q.coeffs().allFinite() ||
      !def.linear_velocity.allFinite() || !def.angular_velocity.allFinite())
    throw std::invalid_argument("ragdoll_sim: body '" + def.name +
                                "' needs a finite pose and velocity");
  BodyMotion m;
  m.local_com = def.com;
  m.q = def.pose.q.normalized();
  m.x = snapPosition(def.pose.p + m.q * def.com);
  if (!m.x.allFinite() || !def.com.allFinite())
    throw std::invalid_argument("ragdoll_sim: body '" + def.name +
                                "' has a non-finite centre of mass position");
  const std::string e = firstError({nonNegativeError("linear_damping", def.linear_damping),
                                    nonNegativeError("angular_damping", def.angular_damping),
                                    finiteError("gravity_scale", def.gravity_scale)});
  if (!e.empty()) throw std::invalid_argument("ragdoll_sim: body '" + def.name + "': " + e);
  m.inertia_local = def.inertia;
  m.linear_damping = def.linear_damping;
  m.angular_damping = def.angular_damping;
  m.gravity_scale = def.gravity_scale;
  if (def.type == BodyType::Dynamic) {
    if (!(def.mass > 0.0) || !def.inertia.allFinite() || def.inertia.determinant() <= 0.0)
      throw std::invalid_argument("ragdoll_sim: body '" + def.name +
                                  "' needs a positive mass and a positive definite inertia");
    m.inv_mass = 1.0 / def.mass;
    m.inv_inertia_local = def.inertia.inverse();
    m.v = def.linear_velocity;
    m.w = def.angular_velocity;
    m.awake = true;
  }
  w.bodies.push_back(std::move(body));
  w.motions.push_back(m);
  w.solver.emplace_back();
  w.rotations.emplace_back(Mat3::Identity());
  w.last_finite.push_back({m.x, m.q});
  w.solver_reset.push_back(0);
  w.solver_fault.push_back(0);
  return BodyId{int32_t(w.bodies.size() - 1)};
}

void World::addShape(BodyId id, const ShapeDef& def) {
  impl_->checkBody(id);
  std::string e = firstError({geometryError(def.geometry), poseError("local", def.local)});
  if (e.empty() && !(e = materialError(def.material)).empty()) e = "material " + e;
  if (!e.empty())
    throw std::invalid_argument("ragdoll_sim: a shape of body '" +
                                impl_->bodies[id.index].def.name + "': " + e);
  Body& b = impl_->bodies[id.index];
  b.shapes.push_back(def);
  b.shape_ids.push_back(int(impl_->shapes.size()));
  impl_->shapes.push_back({id.index, int(b.shapes.size() - 1)});
  impl_->settled = false;
  // farthest shape point from the COM, for the sleep speed
  BodyMotion& m = impl_->motions[id.index];
  m.extent = std::max(m.extent, maxExtent(def.geometry, def.local, m.local_com));
}

JointId World::createBallJoint(const BallJointDef& def) { return impl_->addJoint("ball", def); }

JointId World::createHingeJoint(const HingeJointDef& def) {
  return impl_->addJoint("hinge", def);
}

JointId World::createFixedJoint(const FixedJointDef& def) {
  return impl_->addJoint("fixed", def);
}

JointId World::createPrismaticJoint(const PrismaticJointDef& def) {
  return impl_->addJoint("prismatic", def);
}

void World::disableCollision(BodyId a, BodyId b) {
  impl_->checkBody(a);
  impl_->checkBody(b);
  impl_->setCollides(a.index, b.index, false);
  impl_->settled = false;
}

void World::step(double dt) {
  Impl& w = *impl_;
  if (!(dt > 0.0)) return;
  const int substeps = std::max(1, w.def.substeps);
  const auto makeContext = [&](int n, int relax) {
    StepContext c;
    c.dt = dt;
    c.h = dt / n;
    c.inv_h = 1.0 / c.h;
    c.substeps = n;
    c.relax = std::max(0, relax);
    c.def = &w.def;
    c.bodies = &w.solver;
    c.motions = &w.motions;
    c.contact_softness = Softness::make(std::min(w.def.contact_hertz, 0.25 * c.inv_h),
                                        w.def.contact_damping_ratio, c.h);
    c.joint_softness = Softness::make(std::min(w.def.joint_hertz, 0.25 * c.inv_h),
                                      w.def.joint_damping_ratio, c.h);
    return c;
  };
  const StepContext ctx = makeContext(substeps, w.def.contact_relax_iterations);
  const bool rest_mode = w.def.sleep.restOn(substeps);
  const StepContext rest_ctx =
      rest_mode ? makeContext(w.def.sleep.rest_substeps, w.def.sleep.rest_relax_iterations) : ctx;

  w.guardInputs();
  const bool any_awake =
      std::any_of(w.motions.begin(), w.motions.end(), [](const BodyMotion& m) { return m.awake; });
  if (w.settled && !any_awake) {
    w.finishStep();  // clears the forces, as a full step does
    w.time += dt;
    return;
  }
  w.collide(dt);
  w.buildIslands();

  w.active_joints.clear();
  for (Joint& j : w.joints)
    if (!j.broken && (w.motions[j.a].awake || w.motions[j.b].awake)) w.active_joints.push_back(&j);
  w.partitionIslands();
  // A split island's halves and the islands attached to them share one substep loop: they rest
  // together or not at all, as the split island decides.
  const int* const attached = w.attached_islands.data();
  for (World::Impl::IslandRange& r : w.island_ranges) {
    if (r.attached) continue;
    r.resting = rest_mode && w.islandResting(r);
    if (!r.split) continue;
    for (int a = r.attach[0]; a < r.attach[2]; ++a)
      r.resting = r.resting && w.islandResting(w.island_ranges[attached[a]]);
    for (int a = r.attach[0]; a < r.attach[2]; ++a) w.island_ranges[attached[a]].resting = r.resting;
  }
  // Solver bodies outside the islands (static, asleep) here; an island's bodies, joints and
  // contacts are prepared by the thread that solves it, right before it does, so they are in
  // its core's cache, without three parallel loops of their own (256 ragdolls on 2 threads:
  // 0.95 -> 0.90 us/body-step; scenes b and c within the run-to-run noise).
  const int body_count = int(w.bodies.size());
  for (int i = 0; i < body_count; ++i)
    if (w.island_of_body[i] < 0) w.prepareSolverBody(i);
  w.contact_solver.resize();
  const auto contextOf = [&](const World::Impl::IslandRange& r) -> const StepContext& {
    return r.resting ? rest_ctx : ctx;
  };
  const auto prepare = [&](const World::Impl::IslandRange& p, const StepContext& c) {
    for (int k = p.body_begin; k < p.body_end; ++k) w.prepareSolverBody(w.island_bodies[k]);
    for (int k = p.joint_begin; k < p.joint_end; ++k) prepareJoint(*w.active_joints[k], c);
    w.contact_solver.prepare(w.contacts, c, p.contact_begin, p.contact_end);
  };
  // After an island's substeps, on the same thread: restitution and the impulses stored for
  // the next warm start, then its bodies take the step (joint breaks only mark the joints).
  const auto restitute = [&](int begin, int end, const StepContext& c) {
    w.contact_solver.applyRestitution(c, begin, end);
    w.contact_solver.storeImpulses(w.contacts, c.h, begin, end);
  };
  const auto finishBodies = [&](const World::Impl::IslandRange& p) {
    for (int k = p.body_begin; k < p.body_end; ++k) w.finishBody(w.island_bodies[k]);
  };

  // Split islands one after another, each by the whole team (two threads at most: it has two
  // halves): each thread prepares a half, then a group of the boundary contacts (their bodies
  // are in both halves). Then the others, each thread its run of islands.
  const int islands = int(w.island_ranges.size());
  for (const World::Impl::IslandRange& r : w.island_ranges) {
    if (!r.split) continue;
#pragma omp parallel num_threads(std::min(2, w.threadCount()))
    {
      const auto [t, nt] = teamSlot();
      const StepContext& c = contextOf(r);  // for the halves and the attached islands too
      // half k and the islands attached to it (attachToSplitHalves)
      const auto withAttached = [&](int k, auto&& f) { w.withAttached(r, r.half(k), k, f); };
      for (int k = t; k < 2; k += nt)
        withAttached(k, [&](const World::Impl::IslandRange& p) { prepare(p, c); });
      w.team_barrier.wait(t, nt);
      for (int k = t; k < 2; k += nt)
        w.contact_solver.prepare(w.contacts, c, r.boundaryBegin(k), r.boundaryEnd(k));
      w.team_barrier.wait(t, nt);
      w.solveIsland(r, c);
      // Restitution reads the halves' bodies as the boundary's does: halves first, then the
      // boundary, then the bodies take their velocities.
      for (int k = t; k < 2; k += nt)
        withAttached(k, [&](const World::Impl::IslandRange& p) {
          restitute(p.contact_begin, p.contact_end, c);
        });
      w.team_barrier.wait(t, nt);
      for (int k = t; k < 2; k += nt) restitute(r.boundaryBegin(k), r.boundaryEnd(k), c);
      w.team_barrier.wait(t, nt);
      for (int k = t; k < 2; k += nt) withAttached(k, finishBodies);
    }
  }
  const auto solveOne = [&](int k) {
    const World::Impl::IslandRange& r = w.island_ranges[k];
    if (r.split || r.attached) return;
    const StepContext& c = contextOf(r);
    prepare(r, c);
    w.solveIsland(r, c);
    restitute(r.contact_begin, r.contact_end, c);
    finishBodies(r);
  };
  // Its own run first, then what is left of the others' (run_queue.hpp).
  w.run_queue.reset(w.island_runs);
  const auto solveRun = [&](int t) {
    for (int k; (k = w.run_queue.take(t)) >= 0;) solveOne(k);
    for (int k; (k = w.run_queue.steal(t)) >= 0;) solveOne(k);
  };
  // (no runs when every island is split or goes along with a split one's half)
  if (w.run_work > 0 && islands > 1 && int(w.island_bodies.size()) >= kParallelMin) {
#ifdef _OPENMP
#pragma omp parallel num_threads(w.threadCount())
    solveRun(omp_get_thread_num());
#else
    solveRun(0);  // threadCount() is 1
#endif
  } else if (w.run_work > 0) {
    solveRun(0);  // its own run, then the others' (stolen from the back)
  }
  w.breakJoints();
  for (int i = 0; i < body_count; ++i)
    if (w.island_of_body[i] < 0) w.finishBody(i);
  w.resetFaulted();
  if (w.any_solver_reset) w.clearWarmStart();
  w.updateSleep(dt);
  w.settled = !any_awake;
  w.time += dt;
}

double World::time() const { return impl_->time; }
const WorldDef& World::def() const { return impl_->def; }
void World::setGravity(const Vec3& g) { impl_->def.gravity = g; }

void World::setSleep(const SleepDef& sleep) {
  const std::string e = sleepDefError(sleep);
  if (!e.empty()) throw std::invalid_argument("ragdoll_sim: setSleep: " + e);
  Impl& w = *impl_;
  if (sleep.enabled != w.def.sleep.enabled) {
    // Slow times stood still while sleep was off (updateSleep); a body asleep when it is
    // turned off must move again.
    for (size_t i = 0; i < w.bodies.size(); ++i) {
      if (!sleep.enabled && !w.motions[i].awake && w.isDynamic(int(i))) w.wake(int(i));
      w.motions[i].sleep_time = 0.0;
    }
  }
  w.def.sleep = sleep;
}

std::vector<BodyFault> World::takeBodyFaults() {
  std::vector<BodyFault> out;
  out.swap(impl_->faults);
  return out;
}

int64_t World::bodyFaultCount() const { return impl_->fault_count; }

void World::applyLinearImpulse(BodyId id, const Vec3& impulse, const Vec3& world_point) {
  impl_->checkBody(id);
  impl_->wake(id.index);
  BodyMotion& m = impl_->motions[id.index];
  if (m.inv_mass == 0.0) return;
  const Mat3 R = m.q.toRotationMatrix();
  m.v += m.inv_mass * impulse;
  m.w += R * m.inv_inertia_local * R.transpose() * (world_point - m.x).cross(impulse);
}

void World::applyLinearImpulseToCenter(BodyId id, const Vec3& impulse) {
  impl_->checkBody(id);
  impl_->wake(id.index);
  BodyMotion& m = impl_->motions[id.index];
  m.v += m.inv_mass * impulse;
}

void World::applyAngularImpulse(BodyId id, const Vec3& impulse) {
  impl_->checkBody(id);
  impl_->wake(id.index);
  BodyMotion& m = impl_->motions[id.index];
  if (m.inv_mass == 0.0) return;
  const Mat3 R = m.q.toRotationMatrix();
  m.w += R * m.inv_inertia_local * R.transpose() * impulse;
}

void World::applyForce(BodyId id, const Vec3& force, const Vec3& world_point) {
  impl_->checkBody(id);
  impl_->wake(id.index);
  BodyMotion& m = impl_->motions[id.index];
  m.force += force;
  m.torque += (world_point - m.x).cross(force);
}

void World::applyTorque(BodyId id, const Vec3& torque) {
  impl_->checkBody(id);
  impl_->wake(id.index);
  impl_->motions[id.index].torque += torque;
}

void World::setBodyState(BodyId id, const Transform& pose, const Vec3& v, const Vec3& w) {
  impl_->checkBody(id);
  impl_->wake(id.index);
  impl_->forgetBoxes(id.index);
  BodyMotion& m = impl_->motions[id.index];
  m.q = pose.q.normalized();
  m.x = snapPosition(pose.p + m.q * m.local_com);
  m.x_carry.setZero();
  const bool dyn = impl_->isDynamic(id.index);
  m.v = dyn ? v : Vec3::Zero();
  m.w = dyn ? w : Vec3::Zero();
  m.force.setZero();
  m.torque.setZero();
}

int World::bodyCount() const { return int(impl_->bodies.size()); }
int World::jointCount() const { return int(impl_->joints.size()); }
bool World::isAwake(BodyId id) const {
  impl_->checkBody(id);
  return impl_->motions[id.index].awake;
}

void World::wake(BodyId id) {
  impl_->checkBody(id);
  impl_->wake(id.index);
}

int World::awakeBodyCount() const {
  int n = 0;
  for (const BodyMotion& m : impl_->motions) n += m.awake ? 1 : 0;
  return n;
}

IslandCounters World::islandCounters() const {
  IslandCounters c;
  for (const Impl::IslandRange& r : impl_->island_ranges) {
    ++c.islands;
    c.split_islands += r.split ? 1 : 0;
    c.largest_island = std::max(c.largest_island, r.body_end - r.body_begin);
    c.bodies += r.body_end - r.body_begin;
    c.joints += r.joint_end - r.joint_begin;
    c.contacts += r.contact_end - r.contact_begin;
    c.resting_islands += r.resting ? 1 : 0;
    c.resting_bodies += r.resting ? r.body_end - r.body_begin : 0;
  }
  return c;
}

bool World::isValid(BodyId id) const { return id.index >= 0 && id.index < bodyCount(); }

BodyState World::bodyState(BodyId id) const {
  impl_->checkBody(id);
  const BodyMotion& m = impl_->motions[id.index];
  return {m.linkPose(), m.x, m.v, m.w};
}

Transform World::bodyPose(BodyId id) const {
  impl_->checkBody(id);
  return impl_->motions[id.index].linkPose();
}

const BodyDef& World::bodyDef(BodyId id) const {
  impl_->checkBody(id);
  return impl_->bodies[id.index].def;
}

const std::vector<ShapeDef>& World::bodyShapes(BodyId id) const {
  impl_->checkBody(id);
  return impl_->bodies[id.index].shapes;
}

Vec3 World::comPosition(BodyId id) const {
  impl_->checkBody(id);
  return impl_->motions[id.index].x;
}

Vec3 World::pointVelocity(BodyId id, const Vec3& p) const {
  impl_->checkBody(id);
  const BodyMotion& m = impl_->motions[id.index];
  return m.v + m.w.cross(p - m.x);
}

JointType World::jointType(JointId id) const { return impl_->joints.at(id.index).type(); }

double World::hingeAngle(JointId id) const {
  const Joint& j = impl_->joints.at(id.index);
  const HingeJoint* h = j.as<HingeJoint>();
  return h ? h->angle(j, impl_->motions) : 0.0;
}

std::array<double, 3> World::ballAngles(JointId id) const {
  const Joint& j = impl_->joints.at(id.index);
  const BallJoint* b = j.as<BallJoint>();
  return b ? b->eulerAngles(j, impl_->motions) : std::array<double, 3>{0, 0, 0};
}

std::array<double, 2> World::ballSwingTwist(JointId id) const {
  const Joint& j = impl_->joints.at(id.index);
  const BallJoint* b = j.as<BallJoint>();
  return b ? b->swingTwistAngles(j, impl_->motions) : std::array<double, 2>{0, 0};
}

double World::prismaticPosition(JointId id) const {
  const Joint& j = impl_->joints.at(id.index);
  const PrismaticJoint* p = j.as<PrismaticJoint>();
  return p ? p->position(j, impl_->motions) : 0.0;
}

Vec3 World::jointAnchorError(JointId id) const {
  const Joint& j = impl_->joints.at(id.index);
  const auto& m = impl_->motions;
  const Vec3 e = m[j.b].linkPose().apply(j.frame_b.p) - m[j.a].linkPose().apply(j.frame_a.p);
  const PrismaticJoint* p = j.as<PrismaticJoint>();
  return p ? p->offAxis(j, m, e) : e;
}

double World::jointForce(JointId id) const { return impl_->joints.at(id.index).force; }
double World::jointTorque(JointId id) const { return impl_->joints.at(id.index).torque; }
bool World::isJointBroken(JointId id) const { return impl_->joints.at(id.index).broken; }

std::vector<JointId> World::takeBrokenJoints() {
  std::vector<JointId> out;
  out.swap(impl_->broken_events);
  return out;
}

void World::breakJoint(JointId id) {
  Joint& j = impl_->joints.at(id.index);
  if (j.broken) return;
  j.broken = true;
  impl_->setCollides(j.a, j.b, true);
  impl_->wake(j.a);
  impl_->wake(j.b);
}

void World::setJointMotor(JointId id, int axis, const JointMotor& motor) {
  Joint& j = impl_->joints.at(id.index);
  const std::string e = jointMotorError(motor);
  if (!e.empty())
    throw std::invalid_argument("ragdoll_sim: setJointMotor, axis " + std::to_string(axis) +
                                " of the joint between '" + impl_->bodies[j.a].def.name +
                                "' and '" + impl_->bodies[j.b].def.name + "': motor." + e);
  j.motorAt(axis) = motor;
  impl_->wake(j.a);
  impl_->wake(j.b);
}

Vec3 World::linearMomentum() const {
  Vec3 p = Vec3::Zero();
  for (size_t i = 0; i < impl_->bodies.size(); ++i)
    if (impl_->isDynamic(int(i))) p += impl_->motions[i].v / impl_->motions[i].inv_mass;
  return p;
}

Vec3 World::angularMomentum(const Vec3& about) const {
  Vec3 L = Vec3::Zero();
  for (size_t i = 0; i < impl_->bodies.size(); ++i) {
    if (!impl_->isDynamic(int(i))) continue;
    const BodyMotion& m = impl_->motions[i];
    const Mat3 R = m.q.toRotationMatrix();
    L += (m.x - about).cross(m.v / m.inv_mass) + R * m.inertia_local * R.transpose() * m.w;
  }
  return L;
}

double World::kineticEnergy() const {
  double e = 0.0;
  for (size_t i = 0; i < impl_->bodies.size(); ++i) {
    if (!impl_->isDynamic(int(i))) continue;
    const BodyMotion& m = impl_->motions[i];
    const Vec3 wb = m.q.conjugate() * m.w;
    e += 0.5 * m.v.squaredNorm() / m.inv_mass + 0.5 * wb.dot(m.inertia_local * wb);
  }
  return e;
}

std::vector<ContactInfo> World::contacts() const {
  std::vector<ContactInfo> out;
  for (const Contact& c : impl_->contacts)
    for (int i = 0; i < c.manifold.count; ++i)
      out.push_back({BodyId{c.body_a}, BodyId{c.body_b}, c.origin + c.manifold.points[i].point,
                     c.manifold.normal, c.manifold.points[i].separation, c.normal_impulse[i]});
  return out;
}

}  // namespace ragdoll_sim
