// Velocities of tracked bodies at the end of every substep (SubstepVelocities).
// PLACEHOLDER: the helper on branch i57-injury replaces it.
#include "ragdoll_sim/world.hpp"

#include "world_impl.hpp"

namespace ragdoll_sim {

void World::trackBody(BodyId, bool) {}
bool World::substepVelocities(BodyId, SubstepVelocities*) const { return false; }

}  // namespace ragdoll_sim
