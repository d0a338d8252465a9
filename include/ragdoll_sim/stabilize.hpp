// Mass and inertia conditioning of a ragdoll (as Jolt's Ragdoll::Stabilize): sequential
// impulses converge slowly when a light link hangs on a heavy one (a 0.1 kg hand on a 30 kg
// torso chain) or a body's principal moments differ by orders of magnitude, so the anchors
// drift apart under hard hits. Opt-in: it changes the physics (mass moves along the tree).
#pragma once

#include <string>
#include <vector>

#include "ragdoll_sim/ragdoll.hpp"

namespace ragdoll_sim {

struct StabilizeSettings {
  double max_mass_ratio = 4.0;      // heavier / lighter, for every jointed parent-child pair
  double max_inertia_ratio = 10.0;  // largest / smallest principal moment of each link
  int max_passes = 50;
};

// Adjusts def.links[*].mass and .inertia in place: a pair out of ratio shares its joint mass
// so that the ratio is exactly max_mass_ratio (the pair's total kept, so the ragdoll's total is
// kept), repeated over the tree until no pair is out of ratio; inertias are scaled with their
// mass (same radii of gyration); then small principal moments are raised to
// largest / max_inertia_ratio (principal axes kept). Returns one line per change (also
// appended to def.notes).
std::vector<std::string> stabilizeRagdoll(RagdollDef& def, const StabilizeSettings& s = {});

}  // namespace ragdoll_sim
