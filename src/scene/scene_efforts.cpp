// Scene: joint loads and axis efforts, and joint effort commands (scene_reports.hpp).
// PLACEHOLDER: the helper on branch i57-joints replaces it.
#include "scene_impl.hpp"

namespace ragdoll_sim {

void Scene::loads(int, std::vector<LinkLoad>& links, std::vector<JointLoad>& joints) const {
  links.clear();
  joints.clear();
}
void Scene::jointEfforts(int k, std::vector<double>& out) const {
  out.assign(axisNames(k).size(), 0.0);
}
size_t Scene::activeEffortCount() const { return 0; }

bool Scene::Impl::applyJointEffort(scene::RagdollInstance&, const JointEffortCommand&) {
  warn("joint effort/unsupported", "joint effort rejected: not implemented yet");
  return false;
}
void Scene::Impl::applyActiveEfforts(scene::RagdollInstance&) {}

}  // namespace ragdoll_sim
