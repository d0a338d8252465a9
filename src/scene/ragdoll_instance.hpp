// One ragdoll of a Scene: its model, its bodies in the World, its joint control and its active
// forces. The Scene holds them in a std::vector; indices shift on removal, ids do not.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "injury_record.hpp"
#include "joint_control.hpp"
#include "ragdoll_sim/balance.hpp"
#include "ragdoll_sim/ragdoll.hpp"
#include "ragdoll_sim/scene.hpp"

namespace ragdoll_sim {
namespace scene {

// A joint effort command's effort on one axis (scene_efforts.cpp), applied every step until
// steps_left reaches 0; one that reached 0 stays listed until the next step, so that the
// efforts reported after its last step include it.
struct ActiveEffort {
  int axis = -1;          // AxisTable index
  double effort = 0.0;    // N m (N for a prismatic axis), on the child about +axis
  int64_t steps_left = 1; // < 0: until replaced or cleared
};

struct RagdollInstance {
  std::string name;       // unique; commands name it ("" = the first)
  RagdollId id;
  RagdollDef def;         // with the joint settings applied
  Transform spawn_pose;   // root link in the world frame (reset() goes back here)
  Ragdoll ragdoll;        // body and joint ids in the current World (new ids after a rebuild)
  bool object = false;    // a dynamic object: no balance, no per-link material map
  // Placed by a world file: left where its author put it, as Gazebo does (and a world of
  // thousands of models is not checked model by model against every static shape).
  bool from_world = false;
  // Per link, per shape: coefficients the model file wrote itself (surfaces.hpp bits).
  std::vector<std::vector<uint8_t>> written;
  LinkTable links;

  // Joint control: every joint angle (joint_states names), its motor gains and target.
  AxisTable axes;
  std::vector<std::string> axis_names;
  std::vector<MotorGains> gains;     // per axis
  std::vector<AxisTarget> targets;   // per axis
  std::vector<int> moving_targets;   // axes whose target moves (position + velocity)
  // Refers to `def` and `ragdoll`: the Scene rebuilds it whenever the vector of instances or
  // the World changes.
  std::unique_ptr<BalanceController> balance;
  bool balance_on = false;

  std::vector<ActiveForce> forces;   // re-applied every step
  std::vector<ActiveEffort> efforts; // joint effort commands, at most one per axis
  bool forces_capped_said = false;   // the cap's WARN for this set of forces was given

  InjuryRecord injury;  // ragdolls only (scene_injury.cpp)
};

}  // namespace scene
}  // namespace ragdoll_sim
