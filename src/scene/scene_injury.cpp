// Scene: one injury record per ragdoll (injury.hpp). PLACEHOLDER: the helper on branch
// i57-injury replaces it.
#include "scene_impl.hpp"

namespace ragdoll_sim {

bool Scene::setInjury(int, const InjuryDef&, std::string*) { return true; }
const std::string& Scene::headLink(int) const {
  static const std::string none;
  return none;
}
const std::string& Scene::neckJoint(int) const {
  static const std::string none;
  return none;
}
InjuryReport Scene::injury(int) const { return InjuryReport(); }
InjuryReport Scene::resetInjury(int) { return InjuryReport(); }
const std::vector<InjuryReport>& Scene::injuryReports() const {
  static const std::vector<InjuryReport> none;
  return none;
}
void Scene::Impl::updateInjury() {}

}  // namespace ragdoll_sim
