// Scene: world files, objects and static objects.
#include <stdexcept>
#include <unordered_set>

#include "names.hpp"
#include "object_check.hpp"
#include "scene_impl.hpp"

namespace ragdoll_sim {

using scene::RagdollInstance;
using scene::StaticObject;

namespace {

// A world file's model as a spawn: the RagdollDef of modelRagdollDef with what it does not
// carry (material names, colours, the file's own coefficients) and its joints to the world.
struct ModelSpawn {
  SpawnDef spawn;
  std::vector<std::vector<uint8_t>> written;
};

ModelSpawn modelSpawn(const WorldModelDef& m, const std::string& name) {
  ModelSpawn out;
  SpawnDef& s = out.spawn;
  s.name = name;
  s.object = true;
  s.def = modelRagdollDef(m);
  s.def.name = name;
  bool all_static = true;
  for (size_t l = 0; l < m.links.size(); ++l) {
    const WorldLinkDef& wl = m.links[l];
    LinkDef& link = s.def.links[l];
    all_static = all_static && wl.is_static;
    if (!link.has_color && wl.has_color) {
      link.has_color = true;
      link.color = wl.color;
    }
    if (link.material.empty()) link.material = wl.visual_material;  // "Gazebo/Wood"
    link.shape_materials.resize(wl.collisions.size());
    out.written.emplace_back(wl.collisions.size(), 0);
    for (size_t c = 0; c < wl.collisions.size(); ++c) {
      const WorldCollisionDef& col = wl.collisions[c];
      if (link.shape_materials[c].empty()) link.shape_materials[c] = col.material;
      out.written[l][c] = static_cast<uint8_t>((col.has_friction ? scene::kWrittenFriction : 0) |
                                               (col.has_restitution ? scene::kWrittenRestitution : 0));
    }
  }
  s.is_static = m.is_static || all_static;
  s.pose = m.links.empty() ? m.pose : m.links[0].pose;
  if (s.is_static) return out;
  std::vector<const RagdollJointDef*> to_world;
  for (const RagdollJointDef& j : m.joints)
    if (j.parent < 0) to_world.push_back(&j);
  if (to_world.empty()) return out;
  if (to_world.size() == 1 && to_world[0]->kind == RagdollJointKind::Fixed) {
    // Welded to the world: that link is the static root, exact and cheaper than a weld.
    s.def.root = to_world[0]->child;
    s.def.fixed_base = true;
    s.pose = m.links.at(static_cast<size_t>(s.def.root)).pose;
    return out;
  }
  // A hinge (a door) or several joints to the world: a static anchor link at the world origin
  // carries them, their frames being world frames.
  LinkDef anchor;
  anchor.name = "world";
  anchor.rest_pose = m.links[0].pose.inverse();
  const int a = static_cast<int>(s.def.links.size());
  s.def.links.push_back(anchor);
  out.written.emplace_back();
  for (const RagdollJointDef* j : to_world) {
    RagdollJointDef joint = *j;
    joint.parent = a;
    s.def.joints.push_back(joint);
  }
  s.def.root = a;
  s.def.fixed_base = true;
  s.pose = Transform();
  return out;
}

}  // namespace

bool Scene::Impl::createStaticBodies(StaticObject& o, std::string* error) {
  o.bodies.clear();
  const Transform root_rest_inv = o.def.links.at(static_cast<size_t>(o.def.root)).rest_pose.inverse();
  try {  // checked before; a guard against what the World still refuses
    for (const LinkDef& l : o.def.links) {
      BodyDef bd;
      bd.type = BodyType::Static;
      bd.name = o.name + "/" + l.name;
      bd.pose = o.pose * root_rest_inv * l.rest_pose;
      o.bodies.push_back(world->createBody(bd));
      for (const ShapeDef& shape : l.shapes) world->addShape(o.bodies.back(), shape);
    }
  } catch (const std::exception& e) {
    for (BodyId b : o.bodies) world->destroyBody(b);
    o.bodies.clear();
    *error = "static object '" + o.name + "': " + e.what();
    return false;
  }
  if (o.name == ground_object) ground = o.bodies.at(static_cast<size_t>(o.plane_link));
  return true;
}

bool Scene::Impl::addStatic(StaticObject o, std::string* error) {
  for (size_t l = 0; l < o.def.links.size() && o.plane_link < 0; ++l)
    for (const ShapeDef& shape : o.def.links[l].shapes)
      if (shape.geometry.type == ShapeType::Plane) o.plane_link = static_cast<int>(l);
  if (world && !createStaticBodies(o, error)) return false;
  bodiesChanged();
  static_index[o.name] = statics.size();
  statics.push_back(std::move(o));
  const StaticObject& added = statics.back();
  if (added.plane_link >= 0 && ground_object.empty()) {
    // The first static plane is the ground from now on, in place of the default plane.
    if (world && ground.valid() && !ground_replaced) world->destroyBody(ground);
    ground_replaced = true;
    ground_object = added.name;
    ground = world ? added.bodies.at(static_cast<size_t>(added.plane_link)) : BodyId();
  }
  return true;
}

void Scene::Impl::removeStatic(size_t i) {
  bodiesChanged();
  StaticObject& o = statics.at(i);
  if (world)
    for (BodyId b : o.bodies)
      if (world->isValid(b)) world->destroyBody(b);
  if (o.name == ground_object) {  // the default plane does not come back: no ground
    ground_object.clear();
    ground = BodyId();
  }
  static_index.erase(o.name);
  if (i + 1 != statics.size()) {
    statics[i] = std::move(statics.back());
    static_index[statics[i].name] = i;
  }
  statics.pop_back();
}

bool Scene::loadWorld(const WorldFileDef& w, std::string* error) {
  Impl& s = *impl_;
  const std::string where = "world '" + w.name + "'";
  std::vector<ModelSpawn> spawns;
  std::unordered_set<std::string> names;
  for (const WorldModelDef& m : w.models) {
    if (m.links.empty()) {
      s.info(where + ": model '" + m.name + "' has no links; nothing to simulate");
      continue;
    }
    std::string name = scene::sanitizedName(m.name);
    for (int k = 2; names.count(name); ++k) name = scene::sanitizedName(m.name) + "_" + std::to_string(k);
    if (name != m.name)
      s.info(where + ": model '" + m.name + "' is named '" + name + "' in the scene");
    names.insert(name);
    const std::string taken = s.nameTaken(name);
    if (!taken.empty()) {
      *error = where + ": model '" + name + "': " + taken + "; nothing of the world added";
      return false;
    }
    spawns.push_back(modelSpawn(m, name));
    const SpawnDef& sp = spawns.back().spawn;
    std::string bad = scene::objectModelError(sp.def, sp.is_static);
    if (bad.empty()) bad = scene::objectPoseError(sp.pose);
    if (!bad.empty()) {
      *error = where + ": model '" + name + "': " + bad + "; nothing of the world added";
      return false;
    }
  }
  const Vec3 old_gravity = s.def.world.gravity;
  const bool old_replaced = s.ground_replaced;
  s.def.world.gravity = w.gravity;
  if (s.world) s.world->setGravity(w.gravity);
  std::vector<std::string> added;
  for (ModelSpawn& m : spawns) {
    const std::string name = m.spawn.name;
    std::string e;
    bool ok = true;
    if (m.spawn.is_static) {
      StaticObject o;
      o.name = name;
      o.def = std::move(m.spawn.def);
      o.pose = m.spawn.pose;
      o.written = std::move(m.written);
      for (const std::string& t : scene::resolveSurfaces(&o.def, s.surfaceRules(true), o.written))
        s.warn("", t);
      ok = s.addStatic(std::move(o), &e);
    } else {
      RagdollInstance r;
      ok = s.makeInstance(std::move(m.spawn), &r, &e);
      if (ok) {
        r.written = std::move(m.written);
        r.from_world = true;
        s.resolveSurfaces(r, /*say_unknown=*/true);
        ok = s.addInstance(std::move(r), &e) == SpawnResult::Added;
      }
    }
    if (!ok) {  // nothing of the world stays
      for (const std::string& n : added) remove(n, &e);
      s.def.world.gravity = old_gravity;
      if (s.world) s.world->setGravity(old_gravity);
      if (!old_replaced && s.ground_replaced) {  // the default plane back in its place
        s.ground_replaced = false;
        if (s.world && s.def.ground) s.makeDefaultGround();
      }
      *error = where + ": model '" + name + "': " + e + "; nothing of the world added";
      return false;
    }
    added.push_back(name);
  }
  s.info(where + ": " + std::to_string(spawns.size()) + " model(s) added");
  return true;
}

SpawnResult Scene::addObject(SpawnDef spawn, std::string* error) {
  Impl& s = *impl_;
  spawn.object = true;
  spawn.balance = false;
  *error = scene::nameError(spawn.name, "object name");
  if (!error->empty()) return SpawnResult::BadName;
  *error = s.nameTaken(spawn.name);
  if (!error->empty()) return SpawnResult::NameInUse;
  const std::string what = "object '" + spawn.name + "': ";
  *error = scene::objectModelError(spawn.def, spawn.is_static);
  if (!error->empty()) {
    *error = what + *error;
    return SpawnResult::BadModel;
  }
  *error = scene::objectPoseError(spawn.pose);
  if (!error->empty()) {
    *error = what + *error;
    return SpawnResult::WorldRefused;
  }
  if (spawn.is_static) {
    StaticObject o;
    o.name = spawn.name;
    o.def = std::move(spawn.def);
    o.pose = spawn.pose;
    for (const std::string& t : scene::resolveSurfaces(&o.def, s.surfaceRules(true), o.written))
      s.warn("", t);
    return s.addStatic(std::move(o), error) ? SpawnResult::Added : SpawnResult::WorldRefused;
  }
  RagdollInstance r;
  if (!s.makeInstance(std::move(spawn), &r, error)) {
    *error = what + *error;
    return SpawnResult::BadModel;
  }
  s.resolveSurfaces(r, /*say_unknown=*/true);
  return s.addInstance(std::move(r), error);
}

bool Scene::isObject(int k) const { return impl_->ragdolls.at(static_cast<size_t>(k)).object; }
size_t Scene::staticObjectCount() const { return impl_->statics.size(); }
const std::string& Scene::staticObjectName(int i) const {
  return impl_->statics.at(static_cast<size_t>(i)).name;
}
const RagdollDef& Scene::staticObjectDef(int i) const {
  return impl_->statics.at(static_cast<size_t>(i)).def;
}
const Transform& Scene::staticObjectPose(int i) const {
  return impl_->statics.at(static_cast<size_t>(i)).pose;
}
const std::vector<BodyId>& Scene::staticObjectBodies(int i) const {
  return impl_->statics.at(static_cast<size_t>(i)).bodies;
}

bool Scene::remove(const std::string& name, std::string* error) {
  Impl& s = *impl_;
  const auto it = s.static_index.find(name);
  if (it != s.static_index.end()) {
    s.removeStatic(it->second);
    return true;
  }
  if (!name.empty() && s.find(name) >= 0) return removeRagdoll(name, error);
  *error = "no ragdoll or object named " + scene::quoted(name);
  return false;
}

}  // namespace ragdoll_sim
