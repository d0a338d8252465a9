// Scene reports of the last step by name: contacts, link and joint loads, impacts, joint
// efforts. PLACEHOLDER: the helper on branch i57-scene replaces it.
#include "scene_impl.hpp"

namespace ragdoll_sim {

std::string Scene::bodyName(const BodyRef&) const { return "ground"; }
BodyRef Scene::bodyRef(BodyId) const { return BodyRef(); }
void Scene::contacts(std::vector<SceneContact>& out) const { out.clear(); }
void Scene::loads(int, std::vector<LinkLoad>& links, std::vector<JointLoad>& joints) const {
  links.clear();
  joints.clear();
}
void Scene::jointEfforts(int k, std::vector<double>& out) const {
  out.assign(axisNames(k).size(), 0.0);
}
size_t Scene::activeEffortCount() const { return 0; }
void Scene::setImpacts(const ImpactDef& def) { impl_->def.impacts = def; }
const std::vector<ImpactEvent>& Scene::impacts() const {
  static const std::vector<ImpactEvent> none;
  return none;
}

bool Scene::Impl::applyJointEffort(scene::RagdollInstance&, const JointEffortCommand&) {
  warn("joint effort/unsupported", "joint effort rejected: not implemented yet");
  return false;
}
void Scene::Impl::applyActiveEfforts(scene::RagdollInstance&) {}
void Scene::Impl::findImpacts() {}

}  // namespace ragdoll_sim
