// Substep samples' data (substep_samples.cpp): the tracked bodies (World::trackBody) and their
// velocities at the end of each substep of the last step (SubstepVelocities).
//
// The solve writes a tracked body's samples on the thread that solves its island (each body
// has its own vectors, so threads never share one); it only reads the solver bodies, so
// tracking changes no result. With nothing tracked the step tests `tracks.empty()` and nothing
// more.
#pragma once

#include <vector>

#include "ragdoll_sim/world_reports.hpp"

namespace ragdoll_sim {

struct BodyTrack {
  int body = -1;
  int pos = -1;        // this step: its index in island_bodies, -1 when no island solves it
  bool valid = false;  // a step ran since it was tracked
  SubstepVelocities samples;  // sized once per substep count, then reused
};

struct SubstepSampleData {
  std::vector<BodyTrack> tracks;  // few (a head per ragdoll): searched linearly
};

}  // namespace ragdoll_sim
