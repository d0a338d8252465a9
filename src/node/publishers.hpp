// The node's output: TF, joint_states (per ragdoll), ~link_states, ~markers, ~stats and
// ~joint_broken. Every stamp is the SimClock's stamp of the Scene's time. Per ragdoll it keeps
// the ROS side (TF prefix, joint_states publisher, message buffers) in the Scene's order.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <geometry_msgs/TransformStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <tf2_ros/transform_broadcaster.h>

#include "ragdoll_sim/LinkStates.h"
#include "ragdoll_sim/scene.hpp"
#include "ragdoll_view.hpp"
#include "visualization.hpp"

namespace ragdoll_sim {
namespace node {

struct NodeContext;

// TF frame names joined by "/": "a/b", or the one that is not empty.
inline std::string joinFrames(const std::string& a, const std::string& b) {
  return a.empty() ? b : b.empty() ? a : a + "/" + b;
}

// One ragdoll's topics and buffers.
struct RagdollTopics {
  std::string name;
  std::string tf_prefix;  // TF frames are "<tf_prefix>/<link>"; "" = the bare URDF link names
  bool spawned = false;   // by ~spawn (it owns the parameter <name>/robot_description)
  bool object = false;    // a dynamic object (Scene::isObject): TF and link_states, no joint_states
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

  std::string frame(const std::string& link) const { return joinFrames(tf_prefix, link); }
};

class Publishers {
 public:
  explicit Publishers(NodeContext& ctx);

  // The Scene's ragdoll `name` was added (its topics) or removed (returns its entry).
  void addRagdoll(RagdollTopics topics);
  RagdollTopics removeRagdoll(const std::string& name);
  const std::vector<RagdollTopics>& ragdolls() const { return ragdolls_; }
  // Buffers for the Scene's current ragdolls, dynamic objects and World (after a spawn, removal
  // or rebuild): the entries follow the Scene's order; a dynamic object without one gets TF
  // prefix <name>.
  void rebuild();
  // Ragdolls only (objects are left out), for the Interaction and the Visualizer's palette.
  std::vector<scene::RagdollView> views() const;
  // Dynamic and static objects, for the Visualizer.
  std::vector<ObjectView> objectViews() const;
  void deleteAllMarkers() { markers_delete_all_ = true; }

  void publish();  // TF, joint_states, link_states when sim time advanced; markers, stats
  void publishBrokenJoints();  // ~joint_broken + INFO for joints that broke in the last step

 private:
  // The TF frame of `link` of `r`: "<~frame_prefix>/<tf_prefix>/<link>", empty parts left out.
  std::string frameId(const RagdollTopics& r, const std::string& link) const;
  void buildTf(RagdollTopics& r, int k);
  void buildJointState(RagdollTopics& r, int k);
  void buildLinkStates();
  void publishTf(const ros::Time& stamp);
  void publishMarkers(const ros::Time& stamp);
  void publishJointStates(const ros::Time& stamp);
  void publishLinkStates(const ros::Time& stamp);
  void publishStats(const ros::Time& stamp);

  NodeContext& ctx_;
  std::vector<RagdollTopics> ragdolls_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  std::vector<geometry_msgs::TransformStamped> tf_all_;  // all ragdolls' TF, one message
  bool markers_delete_all_ = false;  // the next marker message first clears the old ones
  ragdoll_sim::LinkStates link_states_;
  std::vector<BodyId> link_state_bodies_;
  int64_t last_publish_step_ = -1;
  ros::Publisher markers_pub_, broken_pub_, link_states_pub_, stats_pub_;
};

}  // namespace node
}  // namespace ragdoll_sim
