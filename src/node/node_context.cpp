#include "node_context.hpp"

#include <algorithm>
#include <cmath>

namespace ragdoll_sim {
namespace node {

void NodeContext::stepOnce() {
  scene->step();
  clock.publish(scene->timeNs(), /*force=*/false, config.clock_rate);
  publishers->publishBrokenJoints();
  visualizer->recordStep(*scene);
  needImpacts(kImpactsMarkers, visualizer->wantsImpacts(scene->time()));
  reports->afterStep();
}

void NodeContext::needImpacts(unsigned reader, bool on) {
  const unsigned readers = on ? (impact_readers | reader) : (impact_readers & ~reader);
  if (readers == impact_readers) return;
  impact_readers = readers;
  ImpactDef def = scene->def().impacts;
  def.enabled = readers != 0;
  scene->setImpacts(def);
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
