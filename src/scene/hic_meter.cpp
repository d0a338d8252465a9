// HicMeter (injury.hpp). PLACEHOLDER: the helper on branch i57-injury replaces it.
#include "ragdoll_sim/injury.hpp"

namespace ragdoll_sim {

HicMeter::HicMeter(double window) : window_(window) {}
void HicMeter::reset() {}
void HicMeter::add(double, double) {}

}  // namespace ragdoll_sim
