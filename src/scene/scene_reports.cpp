// Scene reports of the last step by name: contacts and impacts (scene_reports.hpp).
// PLACEHOLDER: the helper on branch i57-impacts replaces it.
#include "scene_impl.hpp"

namespace ragdoll_sim {

std::string Scene::bodyName(const BodyRef&) const { return "ground"; }
BodyRef Scene::bodyRef(BodyId) const { return BodyRef(); }
void Scene::contacts(std::vector<SceneContact>& out) const { out.clear(); }
void Scene::setImpacts(const ImpactDef& def) { impl_->def.impacts = def; }
const std::vector<ImpactEvent>& Scene::impacts() const {
  static const std::vector<ImpactEvent> none;
  return none;
}
void Scene::Impl::findImpacts() {}

}  // namespace ragdoll_sim
