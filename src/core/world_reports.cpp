// World reports of the last step: contact forces per touching pair, joint wrenches and axis
// efforts (world_reports.hpp). PLACEHOLDER: the helper on branch i57-core replaces it.
#include "ragdoll_sim/world.hpp"

#include "world_impl.hpp"

namespace ragdoll_sim {

void World::setContactImpulseTracking(bool) {}
bool World::contactImpulseTracking() const { return false; }
void World::contactReports(std::vector<ContactReport>& out) const { out.clear(); }

}  // namespace ragdoll_sim
