#include "object_services.hpp"

#include <sstream>

#include "msg_checks.hpp"
#include "names.hpp"
#include "node_context.hpp"

namespace ragdoll_sim {
namespace node {

namespace {

template <class Res>
bool refuse(NodeContext& ctx, Res& res, const std::string& kind, const std::string& message) {
  res.success = false;
  res.message = message;
  ctx.warn(kind, message);
  return true;  // the call itself worked; success says what happened
}

std::string at(const Vec3& p) {
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

}  // namespace

ObjectServices::ObjectServices(NodeContext& ctx) : ctx_(ctx) {
  spawn_object_srv_ =
      ctx_.pnh.advertiseService("spawn_object", &ObjectServices::onSpawnObject, this);
  spawn_model_srv_ = ctx_.pnh.advertiseService("spawn_model", &ObjectServices::onSpawnModel, this);
}

std::string ObjectServices::nameError(const std::string& name) const {
  const std::string e = scene::ragdollNameError(name);
  if (!e.empty()) return e;
  const Scene& scene = *ctx_.scene;
  if (scene.find(name) >= 0)
    return std::string("a ") + (scene.isObject(scene.find(name)) ? "dynamic object" : "ragdoll") +
           " of that name exists";
  for (size_t i = 0; i < scene.staticObjectCount(); ++i)
    if (scene.staticObjectName(static_cast<int>(i)) == name)
      return "a static object of that name exists";
  return "";
}

std::string ObjectServices::add(SpawnDef spawn, const Vec3& v, const Vec3& w, std::string* kind) {
  Scene& scene = *ctx_.scene;
  const std::string name = spawn.name;
  const bool is_static = spawn.is_static;
  spawn.object = true;
  std::string e;
  const SpawnResult added = scene.addObject(std::move(spawn), &e);
  if (added == SpawnResult::WorldRefused) ctx_.structureChanged();  // the World was rebuilt
  if (added != SpawnResult::Added) {
    *kind = added == SpawnResult::NameInUse ? "name in use"
            : added == SpawnResult::BadName ? "bad name"
            : added == SpawnResult::WorldRefused ? "failed" : "bad model";
    return e.empty() ? "the Scene refused it" : e;
  }
  const int k = scene.find(name);
  if (!is_static && k >= 0 && (v.squaredNorm() > 0 || w.squaredNorm() > 0))
    scene.setRagdollState(k, scene.spawnPose(k), v, w);
  ctx_.structureChanged();
  return "";
}

bool ObjectServices::onSpawnObject(ragdoll_sim::SpawnObject::Request& req,
                                   ragdoll_sim::SpawnObject::Response& res) {
  Scene& scene = *ctx_.scene;
  const std::string what = "spawn_object " + scene::quoted(req.name) + " rejected: ";
  std::string e = nameError(req.name);
  if (!e.empty()) return refuse(ctx_, res, "spawn_object/bad name", what + e);
  SpawnDef spawn;
  std::string problem;
  if (!(e = poseFromMsg(req.pose, ctx_.config.max_position, &spawn.pose, &problem)).empty())
    return refuse(ctx_, res, "spawn_object/" + problem, what + e);
  Vec3 v, w;
  const SolverSettings& solver = scene.def().world.solver;
  if (!(e = twistFromMsg(req.twist, solver.max_linear_speed, solver.max_angular_speed, &v, &w,
                         &problem)).empty())
    return refuse(ctx_, res, "spawn_object/" + problem, what + e);
  if (req.is_static && (v.squaredNorm() > 0 || w.squaredNorm() > 0))
    return refuse(ctx_, res, "spawn_object/static twist",
                  what + "a static object never moves: its twist must be zero");
  const MaterialTable& table = scene.world().def().materials;
  if (!req.material.empty() && table.find(req.material) < 0) {
    std::string known;
    for (int id = 1; id < table.size(); ++id) known += (known.empty() ? "" : ", ") + table.name(id);
    return refuse(ctx_, res, "spawn_object/unknown material",
                  what + "material " + scene::quoted(req.material) +
                      " is not in ~materials/surfaces (known: " +
                      (known.empty() ? "none" : known) + ")");
  }
  PrimitiveObject o;
  o.shape = req.shape;
  o.dimensions = req.dimensions;
  o.is_static = req.is_static;
  o.mass = req.mass;
  o.density = req.density;
  o.material = req.material;
  o.has_color = req.color.a > 0;
  o.color = {req.color.r, req.color.g, req.color.b, req.color.a};
  if (!(e = primitiveObjectDef(o, &spawn.def)).empty())
    return refuse(ctx_, res, "spawn_object/bad shape", what + e);
  spawn.name = req.name;
  spawn.def.name = req.name;
  spawn.is_static = req.is_static;
  const double mass = spawn.def.totalMass();
  std::string kind;
  if (!(e = add(std::move(spawn), v, w, &kind)).empty())
    return refuse(ctx_, res, "spawn_object/" + kind, what + e);
  std::ostringstream m;
  m << "spawned " << (req.is_static ? "static " : "dynamic ") << req.shape << " '" << req.name
    << "'";
  if (!req.is_static) m << " (" << mass << " kg), TF " << req.name << "/" << kObjectLink;
  m << " at " << at(Vec3(req.pose.position.x, req.pose.position.y, req.pose.position.z))
    << ", at sim time " << scene.time() << " s";
  res.success = true;
  res.message = m.str();
  ROS_INFO("%s", res.message.c_str());
  return true;
}

bool ObjectServices::onSpawnModel(ragdoll_sim::SpawnModel::Request& req,
                                  ragdoll_sim::SpawnModel::Response& res) {
  Scene& scene = *ctx_.scene;
  std::string what = "spawn_model " + scene::quoted(req.name) + " rejected: ";
  SpawnDef spawn;
  std::string problem;
  std::string e = poseFromMsg(req.pose, ctx_.config.max_position, &spawn.pose, &problem);
  if (!e.empty()) return refuse(ctx_, res, "spawn_model/" + problem, what + e);
  std::string xml = req.model_xml, file;
  if (xml.empty()) {
    if (req.model_file.empty())
      return refuse(ctx_, res, "spawn_model/no model",
                    what + "neither model_xml nor model_file is set");
    file = req.model_file;
    if (!(e = readModelFile(file, &xml)).empty())
      return refuse(ctx_, res, "spawn_model/unreadable file", what + e);
  }
  LoadedModel model;
  if (!(e = loadModelText(xml, file, &model)).empty())
    return refuse(ctx_, res, "spawn_model/bad model", what + e);
  spawn.name = req.name.empty() ? model.def.name : req.name;
  if (req.name.empty()) what = "spawn_model " + scene::quoted(spawn.name) + " rejected: ";
  if (!(e = nameError(spawn.name)).empty())
    return refuse(ctx_, res, "spawn_model/bad name",
                  what + e + (req.name.empty() ? " (the model's own name; set `name`)" : ""));
  for (const std::string& n : model.def.notes) ROS_INFO("spawn_model '%s': %s", spawn.name.c_str(), n.c_str());
  for (const std::string& n : model.def.warnings) ROS_WARN("spawn_model '%s': %s", spawn.name.c_str(), n.c_str());
  spawn.pose = spawn.pose * model.root_in_model;
  spawn.is_static = req.is_static || model.is_static;
  spawn.fixed_base = !spawn.is_static && (req.fixed_base || model.fixed_base);
  spawn.def = std::move(model.def);
  spawn.def.name = spawn.name;
  spawn.def.fixed_base = spawn.fixed_base;
  const size_t links = spawn.def.links.size(), joints = spawn.def.joints.size();
  const double mass = spawn.def.totalMass();
  const Vec3 p = spawn.pose.p;
  const std::string name = spawn.name;
  const bool is_static = spawn.is_static, fixed = spawn.fixed_base;
  std::string kind;
  if (!(e = add(std::move(spawn), Vec3::Zero(), Vec3::Zero(), &kind)).empty())
    return refuse(ctx_, res, "spawn_model/" + kind, what + e);
  std::ostringstream m;
  m << "spawned " << (is_static ? "static " : fixed ? "fixed-base " : "dynamic ") << model.format
    << " model '" << name << "' (" << links << " links, " << joints << " joints";
  if (!is_static) m << ", " << mass << " kg";
  m << ") with its root link at " << at(p);
  if (!is_static) m << ", TF " << name << "/<link>";
  m << ", at sim time " << scene.time() << " s";
  res.success = true;
  res.message = m.str();
  ROS_INFO("%s", res.message.c_str());
  return true;
}

}  // namespace node
}  // namespace ragdoll_sim
