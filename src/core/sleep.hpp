// Sleep's data (sleep.cpp). An island whose bodies have all been slow (max(|v|, extent |w|)
// below SleepDef::speed, or the island's kinetic energy below that of its mass moving at
// SleepDef::island_speed) for SleepDef::time goes to sleep as a whole: its bodies become identity
// solver bodies, are not integrated, and pairs of them are not collided or solved; their shapes
// keep their boxes. Before that, an island slow for rest_time takes the rest substeps.
#pragma once

#include <atomic>
#include <vector>

namespace ragdoll_sim {

struct SleepData {
  // An island went to sleep on an island thread this step (sleepIslands): the schedule changes.
  std::atomic<bool> islands_slept{false};
  std::vector<int> sleep_order;  // updateSleep's scratch: a split island's bodies, ascending
};

}  // namespace ragdoll_sim
