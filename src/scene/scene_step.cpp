// Scene: the fixed step, the settings that change between steps, and the reports of a step
// (bodies the World reset, joints that broke).
#include <algorithm>
#include <sstream>

#include "scene_impl.hpp"

namespace ragdoll_sim {

using scene::RagdollInstance;

void Scene::setBeforeForces(std::function<void(World&, double)> fn) {
  impl_->before_forces = std::move(fn);
}

void Scene::step() {
  Impl& s = *impl_;
  World& world = *s.world;
  applyDueCommands();
  if (s.before_forces) s.before_forces(world, s.simTime());
  for (RagdollInstance& r : s.ragdolls) {
    s.applyActiveForces(r);
    s.applyActiveEfforts(r);
    for (int i : r.moving_targets) s.applyAxisMotor(r, i);  // targets that move with their velocity
    // applyAxisMotor drops a target that overflowed: it moves no more.
    r.moving_targets.erase(std::remove_if(r.moving_targets.begin(), r.moving_targets.end(),
                                          [&](int i) { return !r.targets[size_t(i)].active; }),
                           r.moving_targets.end());
    if (r.balance) r.balance->update(world);
  }
  world.step(s.dt);
  s.sim_ns += s.def.dt_ns;
  ++s.steps;
  s.reportBodyFaults();
  for (RagdollInstance& r : s.ragdolls) s.expireForces(r);
  s.collectBrokenJoints();
  s.findImpacts();
  s.updateInjury();
}

void Scene::Impl::reportBodyFaults() {
  const std::vector<BodyFault> faults = world->takeBodyFaults();
  if (faults.empty()) return;
  body_faults += faults.size();
  std::string input, solver, range;
  for (const BodyFault& f : faults) {
    std::string where = "body " + std::to_string(f.body.index);
    for (const RagdollInstance& r : ragdolls)
      for (size_t l = 0; l < r.ragdoll.bodies.size(); ++l)
        if (r.ragdoll.bodies[l] == f.body) where = "'" + r.name + "/" + r.def.links[l].name + "'";
    std::string& list = f.cause == BodyFaultCause::Input    ? input
                        : f.cause == BodyFaultCause::Solver ? solver
                                                            : range;
    list += (list.empty() ? "" : ", ") + where;
  }
  std::ostringstream at;
  at << "solver fault at sim time " << simTime() << " s: ";
  if (!input.empty())
    warn("body fault/input", at.str() + "link(s) " + input + " had a non-finite state, force or "
         "torque before the step; reset to the last finite pose with zero velocity");
  if (!solver.empty())
    warn("body fault/solver", at.str() + "link(s) " + solver + " went non-finite in the step; "
         "reset to the last finite pose with zero velocity");
  if (!range.empty())
    warn("body fault/range", at.str() + "link(s) " + range + " left the world range (a "
         "coordinate beyond kWorldRange = 1048576 m); reset to the last pose in range with zero "
         "velocity");
}

void Scene::Impl::collectBrokenJoints() {
  broken.clear();
  for (JointId id : world->takeBrokenJoints()) {
    for (const RagdollInstance& r : ragdolls) {
      const auto it = std::find(r.ragdoll.joints.begin(), r.ragdoll.joints.end(), id);
      if (it == r.ragdoll.joints.end()) continue;
      const RagdollJointDef& j = r.def.joints[static_cast<size_t>(it - r.ragdoll.joints.begin())];
      BrokenJointReport b;
      b.ragdoll = r.name;
      b.joint = j.name;
      b.parent_link = r.def.links[static_cast<size_t>(j.parent)].name;
      b.child_link = r.def.links[static_cast<size_t>(j.child)].name;
      b.force = world->jointForce(id);
      b.torque = world->jointTorque(id);
      b.break_force = j.spring.break_force;
      b.break_torque = j.spring.break_torque;
      broken.push_back(std::move(b));
      break;
    }
  }
}

const std::vector<BrokenJointReport>& Scene::brokenJoints() const { return impl_->broken; }

// ------------------------------------------------------------------------------------------
// Settings between steps

void Scene::setGravity(const Vec3& g) {
  impl_->def.world.gravity = g;
  if (impl_->world) impl_->world->setGravity(g);
}

void Scene::setTimeStep(int64_t dt_ns) {
  impl_->def.dt_ns = std::max<int64_t>(1, dt_ns);
  impl_->dt = static_cast<double>(impl_->def.dt_ns) * 1e-9;
}

void Scene::setSleep(const SleepDef& sleep) {
  impl_->def.world.sleep = sleep;
  if (impl_->world) impl_->world->setSleep(sleep);
}

// Changed in place: nothing wakes and warm starts are rescaled to a new substep.
bool Scene::setSolverSettings(const SolverSettings& solver, std::string* error) {
  try {
    if (impl_->world) impl_->world->setSolverSettings(solver);
  } catch (const std::invalid_argument& e) {
    *error = e.what();
    return false;
  }
  impl_->def.world.solver = solver;
  return true;
}

// Every ragdoll shape and the ground get `surface` in place; touching pairs take the new
// coefficients at once and nothing wakes.
void Scene::setMaterials(const Material& surface, const MaterialTable& table) {
  Impl& s = *impl_;
  try {  // the node checks the ranges first: a guard
    const std::string bad = materialError(surface);
    if (!bad.empty()) throw std::invalid_argument("surface: " + bad);
    if (s.world) s.world->setMaterials(table);
  } catch (const std::invalid_argument& e) {
    s.say(SceneMessage::Level::Error, "", std::string("reconfigure: ") + e.what());
    return;
  }
  s.def.material = surface;
  s.def.ragdoll_surface = surface;
  s.def.ground_surface = surface;
  s.def.world.materials = table;
  // Shapes that name a material take the new table's entry, the rest the new surface (objects
  // keep object_surface); every one is valid now, so nothing below throws.
  World* world = s.world.get();
  auto apply = [world](const std::vector<BodyId>& bodies, const RagdollDef& d) {
    for (size_t l = 0; world && l < bodies.size() && l < d.links.size(); ++l)
      for (size_t k = 0; k < d.links[l].shapes.size(); ++k)
        world->setShapeMaterial(bodies[l], static_cast<int>(k), d.links[l].shapes[k].material);
  };
  for (RagdollInstance& r : s.ragdolls) {
    s.resolveSurfaces(r, /*say_unknown=*/false);
    apply(r.ragdoll.bodies, r.def);
  }
  for (scene::StaticObject& o : s.statics) {
    scene::resolveSurfaces(&o.def, s.surfaceRules(true), o.written);
    apply(o.bodies, o.def);
  }
  if (world && s.ground.valid() && s.ground_object.empty())
    for (int i = 0; i < static_cast<int>(world->bodyShapes(s.ground).size()); ++i)
      world->setShapeMaterial(s.ground, i, surface);
}

int64_t Scene::timeNs() const { return impl_->sim_ns; }
double Scene::time() const { return impl_->simTime(); }
int64_t Scene::steps() const { return impl_->steps; }
int64_t Scene::dtNs() const { return impl_->def.dt_ns; }
double Scene::dt() const { return impl_->dt; }

}  // namespace ragdoll_sim
