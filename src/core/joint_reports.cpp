// World reports of the last step: joint wrenches and axis efforts (world_reports.hpp).
// PLACEHOLDER: the helper on branch i57-joints replaces it.
#include "ragdoll_sim/world.hpp"

#include "world_impl.hpp"

namespace ragdoll_sim {

JointWrench World::jointWrench(JointId) const { return JointWrench(); }
int World::jointAxisEfforts(JointId, double out[3]) const {
  out[0] = out[1] = out[2] = 0.0;
  return 0;
}

}  // namespace ragdoll_sim
