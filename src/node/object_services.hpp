// ~spawn_object and ~spawn_model: objects added at run time (message -> object_defs ->
// Scene::addObject -> publishers). A refusal answers success = false with a message naming the
// problem, and a WARN throttled per kind; nothing is added and the simulation goes on.
#pragma once

#include <string>

#include <ros/ros.h>

#include "object_defs.hpp"
#include "ragdoll_sim/scene.hpp"
#include "ragdoll_sim/SpawnModel.h"
#include "ragdoll_sim/SpawnObject.h"

namespace ragdoll_sim {
namespace node {

struct NodeContext;

class ObjectServices {
 public:
  explicit ObjectServices(NodeContext& ctx);

 private:
  bool onSpawnObject(ragdoll_sim::SpawnObject::Request& req,
                     ragdoll_sim::SpawnObject::Response& res);
  bool onSpawnModel(ragdoll_sim::SpawnModel::Request& req,
                    ragdoll_sim::SpawnModel::Response& res);
  // "" when `name` can be taken by a new object, else why not.
  std::string nameError(const std::string& name) const;
  // Scene::addObject, then the twist (dynamic only) and the publishers; "" or the refusal.
  std::string add(SpawnDef spawn, const Vec3& v, const Vec3& w, std::string* kind);

  NodeContext& ctx_;
  ros::ServiceServer spawn_object_srv_, spawn_model_srv_;
};

}  // namespace node
}  // namespace ragdoll_sim
