// SimNode: owns the World and the ragdolls, steps them at a fixed rate (paced by the wall clock
// at a real-time factor, or as fast as possible), publishes TF / markers / joint_states /
// link_states (and /clock when it is the ROS clock) and serves the command topics, the
// services and dynamic_reconfigure. Its methods live in several files, one concept each:
//   sim_node.cpp      start-up, main loop, time, one physics step
//   sim_world.cpp     ragdoll instances, building / rebuilding the World, joint motors
//   sim_commands.cpp  command topics and the queue of stamped commands
//   sim_services.cpp  services and dynamic_reconfigure
//   sim_publish.cpp   TF, markers, joint_states, link_states, /clock, joint_broken
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <boost/thread/recursive_mutex.hpp>
#include <dynamic_reconfigure/server.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <std_srvs/Empty.h>
#include <std_srvs/SetBool.h>
#include <tf2_ros/transform_broadcaster.h>
#include <visualization_msgs/MarkerArray.h>

#include "command_queue.hpp"
#include "commands.hpp"
#include "interaction.hpp"
#include "joint_control.hpp"
#include "node_config.hpp"
#include "pacing.hpp"
#include "ragdoll_instance.hpp"
#include "ragdoll_sim/ApplyForce.h"
#include "ragdoll_sim/ApplyImpulse.h"
#include "ragdoll_sim/DeleteRagdoll.h"
#include "ragdoll_sim/GetLinkState.h"
#include "ragdoll_sim/JointBroken.h"
#include "ragdoll_sim/LinkStates.h"
#include "ragdoll_sim/NodeStats.h"
#include "ragdoll_sim/PhysicsConfig.h"
#include "ragdoll_sim/SetRagdollState.h"
#include "ragdoll_sim/SpawnRagdoll.h"
#include "ragdoll_sim/Step.h"
#include "ragdoll_sim/world.hpp"
#include "visualization.hpp"
#include "warn_throttle.hpp"

namespace ragdoll_sim {
namespace node {

class SimNode {
 public:
  // nh: public namespace (robot_description, joint_states); pnh: private (~) namespace.
  SimNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh);
  ~SimNode();

  // Reads the parameters, loads the URDF, builds the world and the ROS interface. Returns
  // false with *error naming the problem.
  bool init(std::string* error);

  // Steps until ROS shuts down. Returns the process exit code.
  int run();

  // The ragdolls, the first being the launch-time one (for the visualizer).
  const std::vector<RagdollInstance>& ragdolls() const { return ragdolls_; }
  const World& world() const { return *world_; }

 private:
  // --- time and stepping (sim_node.cpp) ---
  void stepOnce();               // due commands, motors, forces, one World::step, events
  ros::Time simStamp() const;    // stamp of the current sim time (see stamp_origin_)
  double simTime() const { return static_cast<double>(sim_ns_) * 1e-9; }
  void restartPacing();
  // WARN `text`, throttled per `kind` (a fixed name, never message contents): every kind of
  // problem is named at least once per second however many of another kind arrive.
  void warn(const std::string& kind, const std::string& text);
  void reportBodyFaults();  // WARN naming the links World::step reset (non-finite state)

  // --- ragdolls and the World (sim_world.cpp) ---
  // A ready instance (joint settings, tables, buffers) of `def`; false with *error.
  bool makeInstance(RagdollDef def, const std::string& name, const std::string& tf_prefix,
                    const Transform& spawn, bool warn_unknown_joints, RagdollInstance* out,
                    std::string* error);
  // A new World with the ground and every ragdoll: at its spawn pose (joints whole), or, with
  // carry_state, in the pose and velocity it has now with its broken joints still broken.
  bool buildWorld(bool carry_state, std::string* error);
  bool spawnInWorld(RagdollInstance& r, std::string* error);  // bodies at r.spawn_pose
  void setBalance(RagdollInstance& r, bool on, bool log);
  // Rebuilds every balance controller (they refer into the instances, which may have moved).
  void rebindControllers();
  void applyAxisMotor(RagdollInstance& r, int axis);
  void applyAllMotors(RagdollInstance& r);
  void resetAll();
  // Index of the ragdoll `name` ("" = the first), or -1.
  int findRagdoll(const std::string& name) const;
  void structureChanged();  // markers and link_states rebuilt after a spawn / delete / rebuild
  std::vector<RagdollView> ragdollViews() const;  // for the Visualizer and the Interaction

  // --- commands (sim_commands.cpp) ---
  void onImpulse(const ragdoll_sim::ApplyImpulse::ConstPtr& msg);
  void onForce(const ragdoll_sim::ApplyForce::ConstPtr& msg);
  void onTargetPose(const sensor_msgs::JointState::ConstPtr& msg);
  // Queues until the stamp's sim time (a zero stamp: until the next loop iteration).
  void submit(QueuedCommand cmd, const ros::Time& stamp, const char* what);
  void applyCommand(const QueuedCommand& cmd);
  void applyDueCommands();
  bool applyImpulse(RagdollInstance& r, const ImpulseCommand& cmd);
  bool applyForce(RagdollInstance& r, const ForceCommand& cmd);
  bool applyTargetPose(RagdollInstance& r, const TargetPoseCommand& cmd);
  size_t activeForceCount() const;

  // --- services and dynamic_reconfigure (sim_services.cpp) ---
  // success = false, message, and a WARN throttled per kind; returns true (the call worked).
  template <class Res>
  bool refuse(Res& res, const std::string& kind, const std::string& message);
  bool onSetBalance(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res);
  bool onClearTargets(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onPause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onUnpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onReset(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onClearForces(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onStep(ragdoll_sim::Step::Request& req, ragdoll_sim::Step::Response& res);
  bool onSpawn(ragdoll_sim::SpawnRagdoll::Request& req, ragdoll_sim::SpawnRagdoll::Response& res);
  bool onDelete(ragdoll_sim::DeleteRagdoll::Request& req, ragdoll_sim::DeleteRagdoll::Response& res);
  bool onSetState(ragdoll_sim::SetRagdollState::Request& req,
                  ragdoll_sim::SetRagdollState::Response& res);
  bool onGetLinkState(ragdoll_sim::GetLinkState::Request& req,
                      ragdoll_sim::GetLinkState::Response& res);
  void startReconfigure();
  void onReconfigure(ragdoll_sim::PhysicsConfig& cfg, uint32_t level);
  ragdoll_sim::PhysicsConfig currentPhysics() const;

  // --- publishing (sim_publish.cpp) ---
  void buildTf(RagdollInstance& r);
  void buildJointState(RagdollInstance& r);
  void buildLinkStates();
  void publish();  // TF, joint_states, link_states when sim time advanced; markers always
  void publishTf(const ros::Time& stamp);
  void publishMarkers(const ros::Time& stamp);
  void publishJointStates(const ros::Time& stamp);
  void publishLinkStates(const ros::Time& stamp);
  void publishClock(bool force);   // at ~clock_rate, or every step; force: now if not yet sent
  void publishBrokenJoints();      // ~joint_broken + INFO for joints that broke in the last step
  void publishStats(const ros::Time& stamp);  // ~stats (command counters, faults)

  ros::NodeHandle nh_, pnh_;
  NodeConfig config_;

  std::unique_ptr<World> world_;
  BodyId ground_;
  std::vector<RagdollInstance> ragdolls_;
  int next_color_ = 0;
  CommandLimits limits_;
  CommandQueue queue_;
  static constexpr size_t kMaxActiveForces = 256;  // over all ragdolls
  // roscpp's queue per command topic: the callbacks only queue (queue_), so it holds what
  // arrives during one loop iteration or one long service call (0.1 s at 10 kHz).
  static constexpr uint32_t kCommandTopicQueue = 1000;
  // ~stats: received = applied + rejected + queue_.dropped() + queue_.size()
  uint64_t received_ = 0, applied_ = 0, rejected_ = 0, body_faults_ = 0;
  WarnThrottle warn_throttle_{1.0};

  // Time: sim time sim_ns_ advances by dt_ns_ per step (dt_ns_ may change at run time).
  int64_t dt_ns_ = 1000000;
  double dt_ = 1e-3;
  int64_t sim_ns_ = 0;
  int64_t steps_ = 0;
  // Stamp of sim time 0: 0 when the node runs on /use_sim_time (stamps are sim time), else
  // the wall time at start-up (stamp differences still equal sim-time differences).
  ros::Time stamp_origin_;
  bool sim_time_ = false;       // /use_sim_time
  bool publish_clock_ = false;  // this node publishes /clock
  int64_t last_clock_ns_ = -1, next_clock_ns_ = 0;
  bool paused_ = false;
  Pacer pacer_;
  bool pacing_dirty_ = false;   // restart the pacer at the next loop iteration

  // Publishing buffers.
  std::unique_ptr<tf2_ros::TransformBroadcaster> tf_broadcaster_;
  std::vector<geometry_msgs::TransformStamped> tf_all_;  // all ragdolls' TF, one message
  std::unique_ptr<Visualizer> visualizer_;     // ~markers: shapes, contacts, arrows
  std::unique_ptr<Interaction> interaction_;   // /clicked_point pokes, ~drag marker
  bool markers_delete_all_ = false;  // the next marker message first clears the old ones
  ragdoll_sim::LinkStates link_states_;
  std::vector<BodyId> link_state_bodies_;
  int64_t last_publish_step_ = -1;

  ros::Publisher markers_pub_, broken_pub_, link_states_pub_, clock_pub_, stats_pub_;
  ros::Subscriber impulse_sub_, force_sub_, target_sub_;
  ros::ServiceServer pause_srv_, unpause_srv_, reset_srv_, clear_srv_, step_srv_;
  ros::ServiceServer balance_srv_, clear_targets_srv_;
  ros::ServiceServer spawn_srv_, delete_srv_, set_state_srv_, get_link_srv_;

  boost::recursive_mutex reconfigure_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<ragdoll_sim::PhysicsConfig>> reconfigure_;
  bool reconfigure_ready_ = false;  // the server's first (initial) callback has run
};

}  // namespace node
}  // namespace ragdoll_sim
