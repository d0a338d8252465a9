// One ragdoll of the simulation: its model, its bodies in the World, its joint control, its
// active forces and its publishing buffers. SimNode holds a std::vector<RagdollInstance>; the
// first is the launch-time ragdoll, the others come from ~spawn.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <geometry_msgs/TransformStamped.h>
#include <ros/publisher.h>
#include <sensor_msgs/JointState.h>

#include "commands.hpp"
#include "joint_control.hpp"
#include "ragdoll_sim/balance.hpp"
#include "ragdoll_sim/ragdoll.hpp"

namespace ragdoll_sim {
namespace node {

using namespace scene;  // the node's ROS-free helpers moved to src/scene

struct RagdollInstance {
  std::string name;       // unique; commands name it in their `ragdoll` field ("" = the first)
  std::string tf_prefix;  // TF frames are "<tf_prefix>/<link>"; "" = the bare URDF link names
  RagdollDef def;         // with the ~joints settings applied
  Transform spawn_pose;   // root link in the world frame (~reset goes back here)
  Ragdoll ragdoll;        // body and joint ids in the current World (new ids after a rebuild)
  LinkTable links;
  int color_index = 0;    // marker colour, fixed for the ragdoll's lifetime
  bool spawned = false;   // by ~spawn (it owns the parameter <name>/robot_description)

  // Joint control: every joint angle (joint_states names), its motor gains and target.
  AxisTable axes;
  std::vector<MotorGains> gains;     // per axis
  std::vector<AxisTarget> targets;   // per axis (~target_pose)
  std::vector<int> moving_targets;   // axes whose target moves (position + velocity)
  // Refers to `def` and `ragdoll`: SimNode rebuilds it whenever the vector of instances or the
  // World changes.
  std::unique_ptr<BalanceController> balance;
  bool balance_on = false;

  std::vector<ActiveForce> forces;   // re-applied every step

  // joint_states: `joint_states` (launch-time ragdoll) or `<name>/joint_states`.
  ros::Publisher joint_states_pub;
  sensor_msgs::JointState joint_state;
  struct JointSource {
    JointId id;
    RagdollJointKind kind = RagdollJointKind::Hinge;
    int first = 0;  // index into joint_state.position
  };
  std::vector<JointSource> joint_sources;
  std::vector<double> prev_positions;
  int64_t prev_joint_ns = -1;  // sim time of prev_positions; -1: none yet

  // TF: one transform per link, then the ball joints' dummy chain links, then the links the
  // loader lumped into bodies (RagdollDef::fixed_frames).
  std::vector<geometry_msgs::TransformStamped> tf_msgs;
  std::vector<int> ball_joints;     // indices of ball joints with chain links
  std::vector<int> ball_tf_offset;  // first tf_msgs slot of each one's chain links
  size_t fixed_tf_offset = 0;       // tf_msgs slot of fixed_frames[0]

  // The TF frame of a URDF link.
  std::string frame(const std::string& link) const {
    return tf_prefix.empty() ? link : tf_prefix + "/" + link;
  }
};

}  // namespace node
}  // namespace ragdoll_sim
