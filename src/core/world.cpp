// World: the step as a list of named phases (Box2D v3's b2World_Step, in 3D). Each phase lives
// in its own file with the data it owns (world_impl.hpp lists them).
#include "ragdoll_sim/world.hpp"

#include <algorithm>

#include "lane_width.hpp"
#include "phase_clock.hpp"
#include "world_impl.hpp"

namespace ragdoll_sim {

namespace {
int laneWidthOf(int lanes) { return lanes == 1 ? 1 : chooseLaneWidth(lanes); }
}  // namespace

void World::Impl::resolveLanes(int lanes) {
  lane_width = laneWidthOf(lanes);
  lanes_auto = laneWidthAutomatic(lanes);
}

World::World(const WorldDef& def) : impl_(new Impl) {
  const std::string e = worldDefError(def);
  if (!e.empty()) throw std::invalid_argument("ragdoll_sim: WorldDef: " + e);
  impl_->resolveLanes(def.solver.lanes);
  impl_->def = def;
}
World::~World() = default;

void World::step(double dt) {
  Impl& w = *impl_;
  if (!(dt > 0.0)) return;
  StepProfile& profile = w.profile;
  if (w.profiling) profile = StepProfile();
  PhaseClock clock(w.profiling);
  StepContexts ctx = w.makeContexts(dt);  // the full and the rest substeps
  ++w.steps;  // the contexts took the parity of the steps before this one

  // Fault guard: non-finite bodies go back to their last finite pose, speeds are clamped.
  w.guardInputs();
  clock.lap(profile.guard);
  const bool any_awake = w.anyAwake();
  if (w.settled && !any_awake) {
    // Nothing built, woken, set or reset since a step found no body awake: only the time moves.
    if (!w.tracks.empty()) w.beginSamples(ctx, /*solved=*/false);
    w.finishStep();  // clears the forces, as a full step does
    w.time += dt;
    clock.lap(profile.finish);
    profile.step = profile.guard + profile.finish;
    return;
  }

  // Collide: boxes, broadphase pairs (sleeping ones carried), narrowphase or manifold cache.
  w.collide(dt);
  clock.lap(profile.collide);

  // Island scheduling: union-find (wakes whole islands), ranges, split, attach, thread runs;
  // last step's while nothing it is built from changed.
  w.scheduleIslands();
  w.chooseRows(ctx);  // double rows where the islands are too few to fill the lanes
  w.markResting(ctx.rest_mode);  // sleep: islands that take the rest substeps
  if (!w.tracks.empty()) w.beginSamples(ctx, /*solved=*/true);  // World::trackBody
  clock.lap(profile.islands);

  // Island solve: substeps, position sweeps, restitution, bodies take the step.
  w.prepareOutsideBodies();
  w.solveIslands(ctx);
  clock.lap(profile.solve);

  // After the islands: broken joints let their pair collide, bodies outside the islands clear
  // their forces, the fault guard resets what the solver left non-finite.
  w.breakJoints();
  w.finishOutsideBodies();
  w.resetFaulted();
  w.clearTouched();
  if (w.any_solver_reset) w.clearWarmStart();

  // Sleep: islands slow for long enough go to sleep (most on their threads, sleepIslands).
  w.updateSleep(dt);
  w.settled = !any_awake;
  w.time += dt;
  clock.lap(profile.finish);
  profile.step = profile.guard + profile.collide + profile.islands + profile.solve + profile.finish;
}

double World::time() const { return impl_->time; }
const WorldDef& World::def() const { return impl_->def; }
int World::laneWidth() const { return impl_->lane_width; }
bool World::lanesAutomatic() const { return impl_->lanes_auto; }
void World::setGravity(const Vec3& g) { impl_->def.gravity = g; }

void World::setProfiling(bool on) {
  impl_->profiling = on;
  impl_->profile = StepProfile();
}
const StepProfile& World::stepProfile() const { return impl_->profile; }

void World::setSolverSettings(const SolverSettings& solver) {
  const std::string e = solverSettingsError(solver);
  if (!e.empty()) throw std::invalid_argument("ragdoll_sim: setSolverSettings: " + e);
  Impl& w = *impl_;
  w.resolveLanes(solver.lanes);
  if (solver.speculative_distance != w.def.solver.speculative_distance) {
    // Kept boxes are grown by the old distance and cached manifolds were made within it.
    std::fill(w.aabb_kept.begin(), w.aabb_kept.end(), char(0));
    w.static_dirty = true;
    for (ManifoldCache& c : w.manifold_caches) c.valid = false;
    w.pairs_dirty = true;
    w.settled = false;
  }
  // the caps may have changed: the next guard clamps every body again
  std::fill(w.guard_clean.begin(), w.guard_clean.end(), char(0));
  w.def.solver = solver;
}

void World::setMaterials(const MaterialTable& materials) {
  const std::string e = materials.error();
  if (!e.empty()) throw std::invalid_argument("ragdoll_sim: setMaterials: " + e);
  Impl& w = *impl_;
  w.def.materials = materials;
  for (Contact& c : w.contacts) w.applyPairMaterial(c, w.shapeDef(c.shape_a), w.shapeDef(c.shape_b));
}

const WorldTuning& WorldInternals::tuning(const World& world) { return world.impl_->tuning; }

void WorldInternals::setTuning(World& world, const WorldTuning& tuning) {
  const std::string e = worldTuningError(tuning);
  if (!e.empty()) throw std::invalid_argument("ragdoll_sim: setTuning: " + e);
  World::Impl& w = *world.impl_;
  w.tuning = tuning;
  for (ManifoldCache& c : w.manifold_caches) c.valid = false;
  w.pairs_dirty = true;
  w.shape_lists_dirty = true;
  w.static_dirty = true;
  w.settled = false;
  w.schedule_fresh = false;
}

int64_t WorldInternals::scheduleBuilds(const World& world) {
  return world.impl_->schedule_builds;
}

int64_t WorldInternals::contactSweeps(const World& world) {
  int64_t n = 0;
  for (const auto& c : world.impl_->contact_sweeps) n += c.contacts;
  return n;
}

int64_t WorldInternals::staticTreeBuilds(const World& world) {
  return world.impl_->static_tree.builds();
}

int64_t WorldInternals::staticBoxesComputed(const World& world) {
  return world.impl_->static_boxes_computed;
}

std::vector<std::pair<int, int>> WorldInternals::pairs(const World& world) {
  std::vector<std::pair<int, int>> out;
  for (const uint64_t key : world.impl_->contact_keys)
    out.emplace_back(int(key >> 32), int(uint32_t(key)));
  return out;
}

const std::vector<Aabb>& WorldInternals::shapeBoxes(const World& world) { return world.impl_->aabbs; }

std::vector<double> WorldInternals::solverAngles(const World& world, JointId joint) {
  const Joint& j = world.impl_->joint(joint);
  std::vector<double> out;
  const auto take = [&](const auto& ax) {
    out.assign(ax.angles.begin(), ax.angles.begin() + ax.count);
  };
  if (const BallJoint* b = j.as<BallJoint>()) take(b->axes);
  if (const HingeJoint* h = j.as<HingeJoint>()) take(h->axes);
  return out;
}

std::vector<char> WorldInternals::boundedShapes(const World& world) {
  const World::Impl& w = *world.impl_;
  std::vector<char> out(w.shapes.size(), 0);
  for (size_t s = 0; s < w.shapes.size(); ++s)
    out[s] = w.shapes[s].alive && !isUnbounded(w.shapeDef(int(s)).geometry);
  return out;
}

}  // namespace ragdoll_sim
