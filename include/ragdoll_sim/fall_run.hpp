// One fall from start to end in C++: a Scene with an optional world file, one ragdoll spawned
// moving, one push, `steps` steps sampled by a FallRecorder. The batch runner (ragdoll_batch)
// calls it once per run with the model and world parsed once per process.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "ragdoll_sim/fall_record.hpp"
#include "ragdoll_sim/ragdoll.hpp"
#include "ragdoll_sim/scene.hpp"
#include "ragdoll_sim/world_file.hpp"

namespace ragdoll_sim {

struct FallRunDef {
  SceneDef scene;                              // step, gravity, surfaces, joints
  std::shared_ptr<const WorldFileDef> world;   // nullptr: the ground plane alone
  std::shared_ptr<const RagdollDef> model;     // required
  std::string name = "ragdoll";
  Transform pose;                              // root link in the world
  Vec3 linear_velocity = Vec3::Zero();         // m/s of the root link origin, at the start
  Vec3 angular_velocity = Vec3::Zero();        // rad/s
  // A push at the start: `push_impulse` (N s, world axes) at the centre of mass of link
  // `push_link`; "" = none.
  std::string push_link;
  Vec3 push_impulse = Vec3::Zero();
  int64_t steps = 0;
  FallRecordDef record;
};

// Throws std::invalid_argument naming what the scene refused (the world, the spawn, the push's
// link or size).
FallRecord runFall(const FallRunDef& def);

}  // namespace ragdoll_sim
