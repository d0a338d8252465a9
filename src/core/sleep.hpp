// Sleep's data (sleep.cpp). An island whose bodies have all been slow (max(|v|, extent |w|)
// below SleepDef::speed, or the island's kinetic energy below that of its mass moving at
// SleepDef::island_speed) for SleepDef::time goes to sleep as a whole: its bodies become identity
// solver bodies, are not integrated, and pairs of them are not collided or solved; their shapes
// keep their boxes. Before that, an island slow for rest_time takes the rest substeps.
#pragma once

#include <vector>

namespace ragdoll_sim {

struct SleepData {
  std::vector<double> island_slow;  // per island root: the island's shortest slow time
  // Per island root: sum of m |v|^2 + w.I.w (twice the kinetic energy) and of the masses.
  std::vector<double> island_energy, island_mass;
};

}  // namespace ragdoll_sim
