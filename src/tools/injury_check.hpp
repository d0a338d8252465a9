// ragdoll_check --injury: the head injury reports of a drop (injury.hpp), as readable lines and
// one key=value line per fall ("injury: status=rest peak_g=... hic15=...").
#pragma once

#include <vector>

#include "ragdoll_sim/injury.hpp"

namespace ragdoll_sim {

// Every fall that ended, then the record still running when none did (status=running).
void printInjury(const std::vector<InjuryReport>& falls, const InjuryReport& running);

}  // namespace ragdoll_sim
