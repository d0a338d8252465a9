// All parameters of ragdoll_sim_node, read once at start-up from the private namespace (~).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "joint_control.hpp"
#include "ragdoll_sim/material.hpp"
#include "ragdoll_sim/math.hpp"
#include "ragdoll_sim/shape.hpp"
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
};

// Active ragdoll: ragdoll_sim::BalanceController (include/ragdoll_sim/balance.hpp).
struct BalanceConfig {
  bool enabled = false;  // on at start-up (~set_balance switches it later)
  double kp = 2.0;       // rad of ankle target per m of centre-of-mass offset from the feet
  double kd = 0.5;       // rad per m/s of centre-of-mass velocity
  std::vector<std::string> ankles{"ankle_l", "ankle_r"};  // hinge joints
  std::vector<std::string> feet{"foot_l", "foot_r"};      // support links
};

struct NodeConfig {
  double physics_rate = 1000.0;        // Hz, fixed physics step = 1 / physics_rate
  double real_time_factor = 1.0;       // sim s per wall s; 0 or inf = as fast as possible
  double clock_rate = 0.0;             // Hz of sim time for /clock (on /use_sim_time); 0 = every step
  int position_iterations = SolverSettings().position_iterations;
  double publish_rate = 60.0;          // Hz, TF / markers / joint_states
  int substeps = SolverSettings().substeps;  // solver substeps per physics step
  int threads = WorldDef().threads;    // islands in parallel (0 = all cores)
  Vec3 gravity = Vec3(0.0, 0.0, -9.81);
  SpawnPose spawn;
  Material material{0.8, 0.6, 0.0, 0.05};  // static/kinetic friction, restitution, rolling
  MaterialTable materials;             // ~materials (config/materials.yaml)
  std::string ragdoll_material;        // surface names in `materials`; "" = `material`
  std::string ground_material;
  Material ragdoll_surface, ground_surface;  // resolved from the two names above
  bool paused = false;
  std::string urdf_file;               // "" -> URDF text from the robot_description param
  std::string ragdoll_name;            // launch-time ragdoll; "" = the URDF's robot name
  std::string tf_prefix;               // its TF prefix; "" = bare link names
  std::string world_frame = "world";
  bool ground = true;                  // static ground plane z = 0
  double max_impulse = 1000.0;         // N*s
  double max_force = 1e5;              // N
  double max_torque = 1e5;             // N*m
  double max_lever_arm = 10.0;         // m
  double max_catchup = 0.1;            // s of physics run at most per loop iteration when late
  double max_linear_speed = 100.0;     // m/s, every body's speed is clamped to it (WorldDef)
  double max_angular_speed = 200.0;    // rad/s
  int max_steps_per_call = 100000;     // ~step refuses more steps than this in one call
  double max_position = 1e4;           // m from the origin: farther poses (~spawn,
                                       // ~set_ragdoll_state) are refused
  int max_queued_commands = 4096;      // commands waiting (zero stamps: until the next loop
                                       // iteration; future stamps: until due); beyond: dropped
  bool publish_markers = true;
  MotorGains motor;                    // ~motor/{hertz, damping_ratio, max_torque}
  JointSettings joint_defaults;        // ~joint_defaults (config/joints.yaml)
  std::vector<std::pair<std::string, JointSettings>> joints;  // ~joints: name -> settings
  BalanceConfig balance;               // ~balance/...
  SleepDef sleep;                      // ~sleep/... (WorldDef::sleep)
  MarkerSettings markers;              // ~markers/... (publish_markers switches them all)
  PokeSettings poke;                   // ~poke/...
  DragSettings drag;                   // ~drag/...

  Transform spawnTransform() const;
};

// Reads every parameter (defaults above for the missing ones). Returns false and sets *error
// (naming the parameter) when a value is present but invalid.
bool loadNodeConfig(const ros::NodeHandle& pnh, NodeConfig* config, std::string* error);

// The World's settings from the parameters (the rest keep WorldDef's defaults).
WorldDef worldDefOf(const NodeConfig& c);

// Range checks, ROS-free. Returns "" when valid, else a message naming the parameter. The
// parameters that go into the World are checked by the core's worldDefError (one rule each).
std::string validateNodeConfig(const NodeConfig& c);

}  // namespace node
}  // namespace ragdoll_sim
