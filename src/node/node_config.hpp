// All parameters of ragdoll_sim_node, read once at start-up from the private namespace (~).
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "joint_control.hpp"
#include "ragdoll_sim/material.hpp"
#include "ragdoll_sim/math.hpp"
#include "ragdoll_sim/shape.hpp"
#include "ragdoll_sim/scene.hpp"
#include "ragdoll_sim/world.hpp"
#include "rviz_settings.hpp"

namespace ros {
class NodeHandle;
}

namespace ragdoll_sim {
namespace node {

struct SpawnPose {
  double x = 0.0, y = 0.0, z = 1.1;  // root link origin, m (z = 1.1: feet ~0.1 m above ground)
  double roll = 0.0, pitch = 0.0, yaw = 0.0;  // rad
  // Initial velocity of every link (a push at start-up, world axes): m/s and rad/s.
  double vx = 0.0, vy = 0.0, vz = 0.0;
  double wx = 0.0, wy = 0.0, wz = 0.0;
};

// The Scene's settings (SceneDef: the World's, the surfaces, command limits, motors, joints,
// balance) with the defaults of their structs, and what only the node uses.
struct NodeConfig {
  SceneDef scene;                      // ~substeps, ~gravity, ~sleep/..., ~materials, ~motor/...
  double physics_rate = 1e9 / static_cast<double>(SceneDef().dt_ns);  // Hz, step = 1 / rate
  double real_time_factor = 1.0;       // sim s per wall s; 0 or inf = as fast as possible
  double clock_rate = 0.0;             // Hz of sim time for /clock (on /use_sim_time); 0 = every step
  double publish_rate = 60.0;          // Hz, TF / markers / joint_states
  SpawnPose spawn;
  bool paused = false;
  bool balance = false;                // ~balance/enabled: the launch-time ragdoll balances
  std::string world_file;              // Gazebo SDF world loaded at start-up; "" = none
  bool world_strict = false;           // an unresolved <include> in it is an error
  std::string urdf_file;               // "" -> URDF text from the robot_description param
  std::string ragdoll_name;            // launch-time ragdoll; "" = the URDF's robot name
  std::string tf_prefix;               // its TF prefix; "" = bare link names
  std::string world_frame = "world";
  std::string frame_prefix;            // before every TF frame of the node; "" = none
  std::string ragdoll_material;        // surface names in ~materials; "" = ~static_friction...
  std::string ground_material;
  double max_catchup = 0.1;            // s of physics run at most per loop iteration when late
  int max_steps_per_call = 100000;     // ~step refuses more steps than this in one call
  double max_position = 1e4;           // m from the origin: farther poses (~spawn,
                                       // ~set_ragdoll_state) are refused
  bool publish_markers = true;
  // Reports (report_topics.hpp); SceneDef::impacts and SceneDef::injury hold the rest.
  double contacts_rate = 0.0;          // Hz of sim time for ~contacts; 0 = every publish cycle
  double joint_effort_duration = -1.0; // s of sim time a ~joint_effort acts; < 0: until replaced
  std::string injury_head_link;        // every ragdoll's head and neck; "" = the Scene's guess
  std::string injury_neck_joint;
  struct HeadAndNeck {
    std::string head_link, neck_joint;
  };
  // ~injury/ragdolls: the head and neck of the ragdolls named here, before the two above.
  std::map<std::string, HeadAndNeck> injury_ragdolls;
  scene::MarkerSettings markers;              // ~markers/... (publish_markers switches them all)
  scene::PokeSettings poke;                   // ~poke/...
  scene::DragSettings drag;                   // ~drag/...
  // What loadNodeConfig read that differs from the defaults above, e.g. "~substeps 8
  // (default 3)": start-up logs it, so values inherited from the parameter server show.
  std::vector<std::string> differing_from_defaults;

  Transform spawnTransform() const;
  Vec3 spawnLinearVelocity() const { return Vec3(spawn.vx, spawn.vy, spawn.vz); }
  Vec3 spawnAngularVelocity() const { return Vec3(spawn.wx, spawn.wy, spawn.wz); }
};

// Reads every parameter (defaults above for the missing ones). Returns false and sets *error
// (naming the parameter) when a value is present but invalid; the physics settings that
// dynamic_reconfigure also sets are checked against the same ranges (physics_ranges.hpp).
bool loadNodeConfig(const ros::NodeHandle& pnh, NodeConfig* config, std::string* error);

// Range checks, ROS-free. Returns "" when valid, else a message naming the parameter. The
// parameters that go into the World are checked by the core's worldDefError (one rule each).
std::string validateNodeConfig(const NodeConfig& c);

}  // namespace node
}  // namespace ragdoll_sim
