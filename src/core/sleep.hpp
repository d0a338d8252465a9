// Sleep's data (sleep.cpp). An island whose bodies have all been slow (max(|v|, extent |w|)
// below SleepDef::speed) for SleepDef::time goes to sleep as a whole: its bodies become identity
// solver bodies, are not integrated, and pairs of them are not collided or solved; their shapes
// keep their boxes. Before that, an island slow for rest_time takes the rest substeps.
#pragma once

#include <vector>

namespace ragdoll_sim {

struct SleepData {
  std::vector<double> island_slow;  // per island root: the island's shortest slow time
};

}  // namespace ragdoll_sim
