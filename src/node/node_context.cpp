#include "node_context.hpp"

#include <algorithm>
#include <cmath>

namespace ragdoll_sim {
namespace node {

void NodeContext::stepOnce() {
  scene->step();
  visualizer->recordStep(*scene);  // impact flashes, injury texts
  clock.publish(scene->timeNs(), /*force=*/false, config.clock_rate);
  publishers->publishBrokenJoints();
  reports->afterStep();
}

void NodeContext::structureChanged() {
  publishers->rebuild();
  reports->rebuild();
  const std::vector<scene::RagdollView> views = publishers->views();
  visualizer->setScene(scene->world(), views, scene->ground(), publishers->objectViews());
  interaction->setScene(&scene->world(), views);
}

void NodeContext::restartPacing() {
  const int max_catchup_steps =
      std::max(1, static_cast<int>(std::ceil(config.max_catchup / scene->dt())));
  pacer.configure(scene->dtNs(), config.real_time_factor, max_catchup_steps);
  pacing_dirty = true;
}

}  // namespace node
}  // namespace ragdoll_sim
