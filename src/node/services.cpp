#include "services.hpp"

#include <cmath>
#include <sstream>

#include "commands.hpp"
#include "msg_checks.hpp"
#include "msg_convert.hpp"
#include "node_context.hpp"
#include "ragdoll_sim/urdf_loader.hpp"

namespace ragdoll_sim {
namespace node {

Services::Services(NodeContext& ctx) : ctx_(ctx) {
  ros::NodeHandle& pnh = ctx_.pnh;
  balance_srv_ = pnh.advertiseService("set_balance", &Services::onSetBalance, this);
  clear_targets_srv_ = pnh.advertiseService("clear_targets", &Services::onClearTargets, this);
  spawn_srv_ = pnh.advertiseService("spawn", &Services::onSpawn, this);
  delete_srv_ = pnh.advertiseService("delete", &Services::onDelete, this);
  set_state_srv_ = pnh.advertiseService("set_ragdoll_state", &Services::onSetState, this);
  get_link_srv_ = pnh.advertiseService("get_link_state", &Services::onGetLinkState, this);
  pause_srv_ = pnh.advertiseService("pause", &Services::onPause, this);
  unpause_srv_ = pnh.advertiseService("unpause", &Services::onUnpause, this);
  reset_srv_ = pnh.advertiseService("reset", &Services::onReset, this);
  clear_srv_ = pnh.advertiseService("clear_forces", &Services::onClearForces, this);
}

void Services::advertiseStep() { ctx_.steps->advertise(); }

template <class Res>
bool Services::refuse(Res& res, const std::string& kind, const std::string& message) {
  res.success = false;
  res.message = message;
  ctx_.warn(kind, message);
  return true;  // the call itself worked; success says what happened
}

bool Services::onSetBalance(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res) {
  Scene& scene = *ctx_.scene;
  res.success = true;
  res.message = req.data ? "balance on" : "balance off";
  scene.setBalance(req.data);
  for (size_t k = 0; k < scene.ragdollCount(); ++k) {
    const std::vector<std::string>* missing = scene.balanceMissing(static_cast<int>(k));
    if (missing && !missing->empty()) {
      res.message += "; '" + scene.name(static_cast<int>(k)) +
                     "': joints hold the pose, but the balance law is off: missing";
      for (const std::string& m : *missing) res.message += " " + m;
    }
  }
  ROS_INFO("%s at sim time %.3f s", res.message.c_str(), scene.time());
  return true;
}

bool Services::onClearTargets(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  ctx_.scene->clearTargets();
  ROS_INFO("joint targets cleared at sim time %.3f s", ctx_.scene->time());
  return true;
}

bool Services::onPause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  ctx_.steps->end("~pause");  // paused already: a pause during ~step stops it
  ctx_.paused = true;
  ROS_INFO("paused at sim time %.3f s", ctx_.scene->time());
  return true;
}

bool Services::onUnpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  ctx_.steps->end("~unpause");
  ctx_.paused = false;
  ROS_INFO("unpaused at sim time %.3f s", ctx_.scene->time());
  return true;
}

bool Services::onReset(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  ctx_.steps->end("~reset");
  std::string error;
  if (!ctx_.scene->reset(&error)) ROS_ERROR("reset: %s", error.c_str());
  ctx_.structureChanged();
  ROS_INFO("%zu ragdoll(s) reset to their spawn poses at sim time %.3f s",
           ctx_.scene->ragdollCount(), ctx_.scene->time());
  return true;
}

bool Services::onClearForces(std_srvs::Empty::Request&, std_srvs::Empty::Response&) {
  ROS_INFO("cleared %zu active force(s)", ctx_.scene->clearForces());
  ctx_.visualizer->endForces(ctx_.scene->time());
  return true;
}

bool Services::onSpawn(ragdoll_sim::SpawnRagdoll::Request& req,
                       ragdoll_sim::SpawnRagdoll::Response& res) {
  Scene& scene = *ctx_.scene;
  const std::string what = "spawn " + scene::quoted(req.name) + " rejected: ";
  std::string e = scene::ragdollNameError(req.name);
  if (!e.empty()) return refuse(res, "spawn/bad name", what + e);
  if (!(e = scene::tfPrefixError(req.tf_prefix)).empty())
    return refuse(res, "spawn/bad tf_prefix", what + e);
  if (scene.find(req.name) >= 0)
    return refuse(res, "spawn/name in use", what + "a ragdoll of that name exists");
  const std::string prefix = req.tf_prefix.empty() ? req.name : req.tf_prefix;
  for (const RagdollTopics& r : ctx_.publishers->ragdolls())
    if (r.tf_prefix == prefix)
      return refuse(res, "spawn/prefix in use",
                    what + "ragdoll '" + r.name + "' already has TF prefix '" + prefix + "'");
  SpawnDef spawn;
  std::string problem;
  e = poseFromMsg(req.pose, ctx_.config.max_position, &spawn.pose, &problem);
  if (!e.empty()) return refuse(res, "spawn/" + problem, what + e);
  UrdfLoadResult loaded;
  std::string xml = req.urdf;
  if (!xml.empty()) {
    loaded = loadUrdfString(xml);
  } else if (!req.urdf_file.empty()) {
    loaded = loadUrdfFile(req.urdf_file, {}, &xml);  // xml: the text read, for robot_description
  } else {
    return refuse(res, "spawn/no urdf", what + "neither urdf nor urdf_file is set");
  }
  if (!loaded.ok)
    return refuse(res, "spawn/bad urdf", what + "failed to load the URDF: " + loaded.error);

  spawn.name = req.name;
  spawn.def = std::move(loaded.def);
  spawn.fixed_base = req.fixed_base || spawn.def.fixed_base;
  const Vec3 at = spawn.pose.p;
  const SpawnResult added = scene.addRagdoll(std::move(spawn), &e);
  if (added == SpawnResult::WorldRefused) ctx_.structureChanged();  // the World was rebuilt
  if (added != SpawnResult::Added)
    return refuse(res, added == SpawnResult::WorldRefused ? "spawn/failed" : "spawn/bad model",
                  what + e);
  const int k = scene.find(req.name);
  RagdollTopics topics;
  topics.name = req.name;
  topics.tf_prefix = prefix;
  topics.spawned = true;
  const std::string ns = ctx_.nh.resolveName(req.name);
  topics.joint_states_pub = ctx_.nh.advertise<sensor_msgs::JointState>(req.name + "/joint_states", 10);
  ctx_.publishers->addRagdoll(std::move(topics));
  ctx_.spawned_params->add(req.name, xml);
  ctx_.structureChanged();
  res.success = true;
  const RagdollDef& def = scene.def(k);
  const Vec3 p = scene.spawnPose(k).p;
  std::ostringstream msg;
  msg << "spawned '" << req.name << "' (" << def.links.size() << " links, "
      << def.joints.size() << " joints, " << def.totalMass() << " kg) at (" << p.x() << ", "
      << p.y() << ", " << p.z() << ")";
  if (p != at)
    msg << ", lifted " << (p - at).norm() << " m out of static geometry from (" << at.x() << ", "
        << at.y() << ", " << at.z() << ")";
  msg << ", TF prefix '" << prefix << "', joint_states on " << ns
      << "/joint_states, at sim time " << scene.time() << " s";
  res.message = msg.str();
  ROS_INFO("%s", res.message.c_str());
  return true;
}

bool Services::onDelete(ragdoll_sim::DeleteRagdoll::Request& req,
                        ragdoll_sim::DeleteRagdoll::Response& res) {
  Scene& scene = *ctx_.scene;
  const int k = req.name.empty() ? -1 : scene.find(req.name);
  std::string kind = k < 0 ? "" : scene.isObject(k) ? "object" : "ragdoll";
  for (size_t i = 0; kind.empty() && i < scene.staticObjectCount(); ++i)
    if (scene.staticObjectName(static_cast<int>(i)) == req.name) kind = "static object";
  if (kind.empty())
    return refuse(res, "delete/unknown name",
                  "delete rejected: no ragdoll named " + scene::quoted(req.name) +
                      " and no object of that name");
  std::string e;
  const bool removed = scene.remove(req.name, &e);
  const RagdollTopics topics = ctx_.publishers->removeRagdoll(req.name);
  if (!removed) {
    res.success = false;
    res.message = "delete: " + e;
    ROS_ERROR("%s", res.message.c_str());
    ctx_.structureChanged();
    return true;
  }
  if (topics.spawned) ctx_.spawned_params->remove(req.name);
  ctx_.publishers->deleteAllMarkers();
  ctx_.structureChanged();
  res.success = true;
  res.message = "deleted " + kind + " '" + req.name + "' at sim time " +
                std::to_string(scene.time()) + " s; " + std::to_string(scene.ragdollCount()) +
                " ragdoll(s) and dynamic object(s), " + std::to_string(scene.staticObjectCount()) +
                " static object(s) left";
  ROS_INFO("%s", res.message.c_str());
  return true;
}

bool Services::onSetState(ragdoll_sim::SetRagdollState::Request& req,
                          ragdoll_sim::SetRagdollState::Response& res) {
  Scene& scene = *ctx_.scene;
  const NodeConfig& c = ctx_.config;
  const int k = scene.find(req.ragdoll);
  if (k < 0)
    return refuse(res, "set_ragdoll_state/unknown ragdoll",
                  "set_ragdoll_state rejected: no ragdoll named " + scene::quoted(req.ragdoll));
  Transform target;
  std::string problem;
  const std::string e = poseFromMsg(req.pose, c.max_position, &target, &problem);
  if (!e.empty())
    return refuse(res, "set_ragdoll_state/" + problem, "set_ragdoll_state rejected: " + e);
  Vec3 v, w;
  const std::string te =
      twistFromMsg(req.twist, scene.def().world.solver.max_linear_speed,
                   scene.def().world.solver.max_angular_speed, &v, &w, &problem);
  if (!te.empty())
    return refuse(res, "set_ragdoll_state/" + problem, "set_ragdoll_state rejected: " + te);
  scene.setRagdollState(k, target, v, w);
  res.success = true;
  res.message = "moved '" + scene.name(k) + "'";
  ROS_INFO("set_ragdoll_state: '%s' root at (%.3f, %.3f, %.3f), v (%.3f, %.3f, %.3f), "
           "w (%.3f, %.3f, %.3f) at sim time %.3f s", scene.name(k).c_str(), target.p.x(),
           target.p.y(), target.p.z(), v.x(), v.y(), v.z(), w.x(), w.y(), w.z(), scene.time());
  return true;
}

bool Services::onGetLinkState(ragdoll_sim::GetLinkState::Request& req,
                              ragdoll_sim::GetLinkState::Response& res) {
  const Scene& scene = *ctx_.scene;
  res.sim_time = scene.time();
  const int k = scene.find(req.ragdoll);
  if (k < 0)
    return refuse(res, "get_link_state/unknown ragdoll",
                  "get_link_state: no ragdoll named " + scene::quoted(req.ragdoll));
  const int link = scene.findLink(k, req.link);
  if (link < 0)
    return refuse(res, "get_link_state/unknown link",
                  "get_link_state: ragdoll '" + scene.name(k) + "' has no simulated link " +
                      scene::quoted(req.link));
  const LinkState s = scene.linkState(k, link);
  toMsg(s.pose, &res.pose);
  toMsg(s.linear_velocity, &res.twist.linear);
  toMsg(s.angular_velocity, &res.twist.angular);
  res.com.x = s.com.x();
  res.com.y = s.com.y();
  res.com.z = s.com.z();
  res.success = true;
  return true;
}

}  // namespace node
}  // namespace ragdoll_sim
