// Scene: world files, objects and static objects.
#include <stdexcept>

#include "scene_impl.hpp"

namespace ragdoll_sim {

// Placeholder so that the API links while the implementation is written (issue 56).
bool Scene::loadWorld(const WorldFileDef&, std::string* error) {
  *error = "loadWorld is not implemented yet";
  return false;
}
SpawnResult Scene::addObject(SpawnDef, std::string* error) {
  *error = "addObject is not implemented yet";
  return SpawnResult::BadModel;
}
bool Scene::isObject(int) const { return false; }
size_t Scene::staticObjectCount() const { return 0; }
const std::string& Scene::staticObjectName(int) const { throw std::out_of_range("no static objects"); }
const RagdollDef& Scene::staticObjectDef(int) const { throw std::out_of_range("no static objects"); }
const Transform& Scene::staticObjectPose(int) const { throw std::out_of_range("no static objects"); }
const std::vector<BodyId>& Scene::staticObjectBodies(int) const {
  throw std::out_of_range("no static objects");
}
bool Scene::remove(const std::string& name, std::string* error) { return removeRagdoll(name, error); }

}  // namespace ragdoll_sim
