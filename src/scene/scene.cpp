// Scene: ragdolls by name and the World they live in (building, spawning, removal, reset).
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <stdexcept>

#include "link_damping.hpp"
#include "scene_impl.hpp"
#include "static_overlap.hpp"

namespace ragdoll_sim {

namespace scene {

std::string format(const char* fmt, ...) {
  va_list args;
  va_start(args, fmt);
  va_list copy;
  va_copy(copy, args);
  const int n = std::vsnprintf(nullptr, 0, fmt, copy);
  va_end(copy);
  std::string out(n > 0 ? static_cast<size_t>(n) : 0, '\0');
  if (n > 0) std::vsnprintf(&out[0], out.size() + 1, fmt, args);
  va_end(args);
  return out;
}

}  // namespace scene

using scene::RagdollInstance;

void Scene::Impl::say(SceneMessage::Level level, const std::string& kind,
                      const std::string& text) const {
  if (listener) listener->message(SceneMessage{level, kind, text});
}

Scene::Scene(SceneDef def, SceneListener* listener) : impl_(std::make_unique<Impl>()) {
  impl_->def = std::move(def);
  impl_->listener = listener;
  impl_->queue = scene::CommandQueue(static_cast<size_t>(impl_->def.max_queued_commands));
  setTimeStep(impl_->def.dt_ns);
}

Scene::~Scene() = default;

bool Scene::Impl::makeInstance(SpawnDef spawn, RagdollInstance* out, std::string* error) {
  RagdollDef& def = spawn.def;
  if (def.links.empty()) {
    *error = "the model has no links";
    return false;
  }
  RagdollInstance& r = *out;
  r.name = spawn.name;
  r.spawn_pose = spawn.pose;
  r.object = spawn.object;
  if (spawn.fixed_base) def.fixed_base = true;
  if (spawn.object) spawn.balance = false;  // an object has no ankles to balance on
  // Joint springs, break forces and motor gains (joint_defaults, joints) by joint name.
  r.axes = scene::AxisTable(def);
  scene::JointSettingsResult settings =
      applyJointSettings(&def, r.axes, this->def.joint_defaults, this->def.joints, this->def.motor);
  if (spawn.warn_unknown_joints)
    for (const std::string& w : settings.warnings) warn("", w);
  if (!settings.error.empty()) {
    *error = settings.error;
    return false;
  }
  if (!spawn.object) {
    const std::vector<std::string> unknown = scene::applyLinkDamping(&def, this->def.link_damping);
    if (spawn.warn_unknown_joints)
      for (const std::string& w : unknown) warn("", w);
  }
  r.def = std::move(def);
  r.gains = std::move(settings.gains);
  r.targets.assign(static_cast<size_t>(r.axes.size()), scene::AxisTarget());
  r.moving_targets.clear();
  r.links = scene::LinkTable(r.def);
  r.axis_names.clear();
  for (const scene::AxisInfo& a : r.axes.axes()) r.axis_names.push_back(a.name);
  r.balance_on = spawn.balance;
  for (const RagdollJointDef& j : r.def.joints) {
    if (j.spring.stiffness > 0.0 || std::isfinite(j.spring.break_force) ||
        std::isfinite(j.spring.break_torque))
      info(scene::format("%s: joint '%s': anchor stiffness %g N/m, damping %g N*s/m, break_force "
                         "%g N, break_torque %g N*m",
                         r.name.c_str(), j.name.c_str(), j.spring.stiffness, j.spring.damping,
                         j.spring.break_force, j.spring.break_torque));
  }
  // What the files set of the anatomy, so a start-up log shows it reached the simulation.
  for (const RagdollJointDef& j : r.def.joints)
    if (j.swing_twist)
      info(scene::format("%s: joint '%s': swing-twist limits, cone %g / %g rad, twist %g..%g rad",
                         r.name.c_str(), j.name.c_str(), j.swing_twist->cone_1,
                         j.swing_twist->cone_2, j.swing_twist->twist_lower,
                         j.swing_twist->twist_upper));
  for (const LinkDef& l : r.def.links)
    if (l.linear_damping > 0.0 || l.angular_damping > 0.0)
      info(scene::format("%s: link '%s': velocity damping linear %g 1/s, angular %g 1/s",
                         r.name.c_str(), l.name.c_str(), l.linear_damping, l.angular_damping));
  return true;
}

bool Scene::Impl::spawnInWorld(RagdollInstance& r, bool may_refuse, std::string* error) {
  try {  // the World refuses what it cannot simulate (e.g. a non-finite pose) by throwing
    r.ragdoll = spawnRagdoll(*world, r.def, r.spawn_pose);  // surfaces resolved in r.def
  } catch (const std::exception& e) {
    *error = e.what();
    return false;
  }
  if (r.ragdoll.bodies.size() != r.def.links.size() ||
      r.ragdoll.joints.size() != r.def.joints.size()) {
    *error = "spawnRagdoll returned " + std::to_string(r.ragdoll.bodies.size()) + " bodies / " +
             std::to_string(r.ragdoll.joints.size()) + " joints for a model with " +
             std::to_string(r.def.links.size()) + " links / " +
             std::to_string(r.def.joints.size()) + " joints";
    return false;
  }
  if (r.from_world) return true;
  // An object is lifted out of static geometry, never refused: a crate spawned into a table
  // is still a crate.
  return clearStatics(r, may_refuse ? "spawn" : "reset", may_refuse && !r.object,
                      /*spawn=*/true, error);
}

bool Scene::Impl::clearStatics(RagdollInstance& r, const std::string& what, bool may_refuse,
                               bool spawn, std::string* error) {
  if (r.def.fixed_base) return true;  // pinned where it was asked to be: the contacts push
  StaticOverlap o;
  if (!scene::overlapsStatics(*world, r.ragdoll.bodies, &o)) return true;
  std::string link = "?";
  for (size_t l = 0; l < r.ragdoll.bodies.size(); ++l)
    if (r.ragdoll.bodies[l] == o.body) link = r.def.links[l].name;
  const std::string into = scene::format(
      "%s: ragdoll '%s' reaches %.4g m into static geometry (link '%s' in '%s')", what.c_str(),
      r.name.c_str(), o.depth, link.c_str(), world->bodyDef(o.static_body).name.c_str());
  if (may_refuse && def.spawn_overlap == SpawnOverlap::Refuse) {
    *error = into + scene::format("; refused (spawn_overlap: refuse): place it at least %.4g m "
                                  "higher, clear of the static geometry", o.depth);
    return false;
  }
  const scene::StaticLift lift = scene::liftOutOfStatics(*world, r.ragdoll.bodies);
  if (!lift.clear) {
    const std::string e = into + scene::format("; lifted %.4g m, it is still inside static "
                                               "geometry: wedged where no lift frees it",
                                               lift.lift.norm());
    if (!may_refuse) {  // reset and moves keep the ragdoll: the contacts push it out
      warn(what + "/wedged", e);
      return true;
    }
    *error = e;
    return false;
  }
  if (spawn) r.spawn_pose.p += lift.lift;
  const Vec3& d = lift.first.direction;
  warn(what + "/lifted",
       into + scene::format("; lifted %.4g m along (%.3g, %.3g, %.3g) to rest on it%s",
                            lift.lift.norm(), d.x(), d.y(), d.z(),
                            spawn ? " (its spawn pose now)" : ""));
  return true;
}

bool Scene::Impl::buildWorld(bool may_refuse, std::string* error) {
  for (RagdollInstance& r : ragdolls) r.balance.reset();  // they drive the old world's joints

  try {  // validated before, and settings changed at run time keep their ranges: a guard
    world = std::make_unique<World>(def.world);
  } catch (const std::invalid_argument& e) {
    *error = e.what();
    return false;
  }
  ground = BodyId();
  bodiesChanged();  // every id is new
  applyImpactTracking();
  if (def.ground && !ground_replaced) makeDefaultGround();
  for (scene::StaticObject& o : statics)
    if (!createStaticBodies(o, error)) return false;
  for (RagdollInstance& r : ragdolls) {
    if (!spawnInWorld(r, may_refuse, error)) return false;
    setBalance(r, r.balance_on, /*log=*/false);
    startInjury(r);  // a new World: the records start afresh
  }
  return true;
}

void Scene::Impl::makeDefaultGround() {
  BodyDef gd;
  gd.type = BodyType::Static;
  gd.name = "ground";
  ground = world->createBody(gd);
  ShapeDef sd;
  sd.geometry = Geometry::plane(Vec3::UnitZ(), 0.0);
  sd.material = def.ground_surface;
  world->addShape(ground, sd);
}

int Scene::Impl::find(const std::string& name) const {
  if (name.empty()) {  // the first ragdoll, not a crate that happened to come first
    for (size_t k = 0; k < ragdolls.size(); ++k)
      if (!ragdolls[k].object) return static_cast<int>(k);
    return -1;
  }
  const auto it = ragdoll_index.find(name);
  return it == ragdoll_index.end() ? -1 : static_cast<int>(it->second);
}

std::string Scene::Impl::nameTaken(const std::string& name) const {
  const int k = find(name);
  if (k >= 0 && !name.empty())
    return std::string(ragdolls[static_cast<size_t>(k)].object ? "an object" : "a ragdoll") +
           " named '" + name + "' exists";
  if (static_index.count(name)) return "a static object named '" + name + "' exists";
  return "";
}

void Scene::Impl::reindexRagdolls(size_t from) {
  for (size_t k = from; k < ragdolls.size(); ++k) ragdoll_index[ragdolls[k].name] = k;
}

scene::SurfaceRules Scene::Impl::surfaceRules(bool object) const {
  scene::SurfaceRules rules;
  rules.table = &def.world.materials;
  rules.link_materials = object ? nullptr : &def.link_materials;
  rules.fallback = object ? def.object_surface : def.ragdoll_surface;
  rules.plane_fallback = def.ground_surface;
  return rules;
}

void Scene::Impl::resolveSurfaces(RagdollInstance& r, bool say_unknown) {
  const std::vector<std::string> w = scene::resolveSurfaces(&r.def, surfaceRules(r.object), r.written);
  if (say_unknown)
    for (const std::string& text : w) warn("", text);
}

SpawnResult Scene::Impl::addInstance(RagdollInstance r, std::string* error) {
  r.id.serial = next_serial++;
  ragdolls.push_back(std::move(r));
  ragdoll_index[ragdolls.back().name] = ragdolls.size() - 1;
  if (!world) return SpawnResult::Added;  // start() spawns it
  RagdollInstance& added = ragdolls.back();
  bodiesChanged();
  const int first_new = world->bodyCount();  // ids append, so what it created is above this
  if (!spawnInWorld(added, /*may_refuse=*/true, error)) {
    for (int b = first_new; b < world->bodyCount(); ++b)
      if (world->isValid(BodyId{b})) world->destroyBody(BodyId{b});
    ragdoll_index.erase(added.name);
    ragdolls.pop_back();
    return SpawnResult::WorldRefused;
  }
  rebindControllers();  // the vector may have moved the instances
  applyAllMotors(ragdolls.back());
  startInjury(ragdolls.back());
  return SpawnResult::Added;
}

SpawnResult Scene::addRagdoll(SpawnDef spawn, std::string* error) {
  Impl& s = *impl_;
  *error = scene::ragdollNameError(spawn.name);
  if (!error->empty()) return SpawnResult::BadName;
  *error = s.nameTaken(spawn.name);
  if (!error->empty()) return SpawnResult::NameInUse;
  if (spawn.object) return addObject(std::move(spawn), error);
  RagdollInstance r;
  if (!s.makeInstance(std::move(spawn), &r, error)) return SpawnResult::BadModel;
  s.resolveSurfaces(r, /*say_unknown=*/true);
  std::string unknown;  // SceneDef::injury names a link or joint this model lacks
  if (!s.resolveInjury(r, s.def.injury, /*say=*/true, &unknown))
    s.warn("injury/unknown", unknown + ": no injury record for it");
  return s.addInstance(std::move(r), error);
}

bool Scene::start(std::string* error) {
  Impl& s = *impl_;
  if (!s.buildWorld(/*may_refuse=*/true, error)) return false;
  for (RagdollInstance& r : s.ragdolls) s.setBalance(r, r.balance_on, /*log=*/true);
  return true;
}

// Its bodies (and with them its joints and contacts) leave the World; the other ragdolls keep
// their warm starts and their sleep.
bool Scene::removeRagdoll(const std::string& name, std::string* error) {
  Impl& s = *impl_;
  const int k = name.empty() ? -1 : s.find(name);
  if (k < 0) {
    *error = "no ragdoll named " + scene::quoted(name);
    return false;
  }
  RagdollInstance& r = s.ragdolls[static_cast<size_t>(k)];
  r.balance.reset();
  s.injuryRemoved(r);
  if (s.world)
    for (BodyId b : r.ragdoll.bodies)
      if (s.world->isValid(b)) s.world->destroyBody(b);
  s.ragdoll_index.erase(r.name);
  s.ragdolls.erase(s.ragdolls.begin() + k);
  s.bodiesChanged();
  s.reindexRagdolls(static_cast<size_t>(k));
  s.rebindControllers();  // the erase moved the instances behind it
  return true;
}

bool Scene::reset(std::string* error) {
  // A fresh world with every ragdoll at its spawn pose rejoins broken joints.
  for (RagdollInstance& r : impl_->ragdolls) {
    r.forces.clear();
    r.efforts.clear();
  }
  return impl_->buildWorld(/*may_refuse=*/false, error);
}

void Scene::setRagdollState(int k, const Transform& target, const Vec3& v, const Vec3& w) {
  World& world = *impl_->world;
  const RagdollInstance& r = impl_->ragdolls.at(static_cast<size_t>(k));
  const BodyId root = r.ragdoll.bodies[static_cast<size_t>(r.def.root)];
  // Rigid move: every link keeps its pose relative to the root link.
  const Transform move = target * world.bodyPose(root).inverse();
  std::vector<Transform> poses;
  for (BodyId b : r.ragdoll.bodies) poses.push_back(move * world.bodyPose(b));
  for (size_t i = 0; i < r.ragdoll.bodies.size(); ++i) {
    const BodyId b = r.ragdoll.bodies[i];
    const Vec3 com = poses[i].apply(world.bodyDef(b).com);
    world.setBodyState(b, poses[i], v + w.cross(com - target.p), w);
  }
  std::string unused;  // never refused: may_refuse is false
  impl_->clearStatics(impl_->ragdolls.at(static_cast<size_t>(k)), "set_ragdoll_state",
                      /*may_refuse=*/false, /*spawn=*/false, &unused);
}

LinkState Scene::linkState(int k, int link) const {
  const World& world = *impl_->world;
  const BodyId b = impl_->ragdolls.at(static_cast<size_t>(k)).ragdoll.bodies.at(static_cast<size_t>(link));
  const BodyState s = world.bodyState(b);
  LinkState out;
  out.pose = s.pose;
  out.linear_velocity = world.pointVelocity(b, s.pose.p);
  out.angular_velocity = s.angular_velocity;
  out.com = s.com_position;
  return out;
}

size_t Scene::ragdollCount() const { return impl_->ragdolls.size(); }
int Scene::find(const std::string& name) const { return impl_->find(name); }
int Scene::indexOf(RagdollId id) const {
  for (size_t k = 0; k < impl_->ragdolls.size(); ++k)
    if (impl_->ragdolls[k].id == id) return static_cast<int>(k);
  return -1;
}
RagdollId Scene::id(int k) const { return impl_->ragdolls.at(static_cast<size_t>(k)).id; }
const std::string& Scene::name(int k) const { return impl_->ragdolls.at(static_cast<size_t>(k)).name; }
const RagdollDef& Scene::def(int k) const { return impl_->ragdolls.at(static_cast<size_t>(k)).def; }
const Transform& Scene::spawnPose(int k) const {
  return impl_->ragdolls.at(static_cast<size_t>(k)).spawn_pose;
}
const Ragdoll& Scene::bodies(int k) const {
  return impl_->ragdolls.at(static_cast<size_t>(k)).ragdoll;
}
int Scene::findLink(int k, const std::string& link) const {
  return impl_->ragdolls.at(static_cast<size_t>(k)).links.find(link);
}
const std::vector<std::string>& Scene::axisNames(int k) const {
  return impl_->ragdolls.at(static_cast<size_t>(k)).axis_names;
}
int Scene::firstAxis(int k, int joint) const {
  return impl_->ragdolls.at(static_cast<size_t>(k)).axes.first(joint);
}
const std::vector<std::string>* Scene::balanceMissing(int k) const {
  const RagdollInstance& r = impl_->ragdolls.at(static_cast<size_t>(k));
  return r.balance ? &r.balance->missing() : nullptr;
}
bool Scene::balanceOn(int k) const { return impl_->ragdolls.at(static_cast<size_t>(k)).balance_on; }

World& Scene::world() { return *impl_->world; }
const World& Scene::world() const { return *impl_->world; }
BodyId Scene::ground() const { return impl_->ground; }
const SceneDef& Scene::def() const { return impl_->def; }

}  // namespace ragdoll_sim
