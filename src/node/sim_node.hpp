// SimNode: owns the World and the ragdoll, steps it at a fixed rate in real time on the calling
// thread, publishes TF / markers / joint_states and serves the command topics and services.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <geometry_msgs/TransformStamped.h>
#include <ros/ros.h>
#include <sensor_msgs/JointState.h>
#include <std_srvs/Empty.h>
#include <std_srvs/SetBool.h>
#include <tf2_ros/transform_broadcaster.h>
#include <visualization_msgs/MarkerArray.h>

#include "commands.hpp"
#include "joint_control.hpp"
#include "node_config.hpp"
#include "ragdoll_sim/ApplyForce.h"
#include "ragdoll_sim/ApplyImpulse.h"
#include "ragdoll_sim/JointBroken.h"
#include "ragdoll_sim/Step.h"
#include "ragdoll_sim/balance.hpp"
#include "ragdoll_sim/ragdoll.hpp"
#include "ragdoll_sim/world.hpp"

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

  // Steps in real time until ROS shuts down. Returns the process exit code.
  int run();

 private:
  // --- simulation ---
  void stepOnce();                 // one physics step with the active forces
  ros::Time simStamp() const;      // start stamp + sim time (exact, integer nanoseconds)
  double simTime() const;
  void resetRagdoll();
  // A new World with the ground and the ragdoll at its spawn pose (joints as configured, none
  // broken), then the joint motors: targets, balance, passive URDF dynamics.
  bool buildWorld(std::string* error);
  void setBalance(bool on);
  // Puts the motor of one axis in the world: its target, else the balance hold, else passive.
  void applyAxisMotor(int axis);
  void publishBrokenJoints();      // ~joint_broken + INFO for joints that broke in the last step

  // --- publishing ---
  void buildTfMessages();
  void buildMarkers();
  void buildJointState();
  void publish();                  // TF + joint_states when sim time advanced; markers always
  void publishTf(const ros::Time& stamp);
  void publishMarkers(const ros::Time& stamp);
  void publishJointState(const ros::Time& stamp);

  // --- ROS callbacks ---
  void onImpulse(const ragdoll_sim::ApplyImpulse::ConstPtr& msg);
  void onForce(const ragdoll_sim::ApplyForce::ConstPtr& msg);
  void onTargetPose(const sensor_msgs::JointState::ConstPtr& msg);
  bool onSetBalance(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res);
  bool onClearTargets(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onPause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onUnpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onReset(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onClearForces(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onStep(ragdoll_sim::Step::Request& req, ragdoll_sim::Step::Response& res);

  Transform linkPose(int link) const;

  ros::NodeHandle nh_, pnh_;
  NodeConfig config_;

  // Model and world.
  RagdollDef def_;
  std::unique_ptr<World> world_;
  Ragdoll ragdoll_;
  BodyId ground_;
  LinkTable links_;
  CommandLimits limits_;

  // Joint control: every joint angle (joint_states names), its motor gains and target.
  AxisTable axes_;
  std::vector<MotorGains> gains_;      // per axis (~motor, ~joint_defaults, ~joints)
  std::vector<AxisTarget> targets_;    // per axis (~target_pose)
  std::vector<int> moving_targets_;    // axes whose target moves (position + velocity)
  std::unique_ptr<BalanceController> balance_;  // active ragdoll, when on
  bool balance_on_ = false;

  // Time: sim time = steps_ * dt_ns_ nanoseconds.
  int64_t dt_ns_ = 1000000;
  double dt_ = 1e-3;
  int64_t steps_ = 0;
  ros::Time start_stamp_;
  bool paused_ = false;

  // Forces re-applied every step (capacity reserved up front).
  static constexpr size_t kMaxActiveForces = 256;
  std::vector<ActiveForce> forces_;

  // Publishing buffers, built once and updated in place.
  std::unique_ptr<tf2_ros::TransformBroadcaster> tf_broadcaster_;
  std::vector<geometry_msgs::TransformStamped> tf_msgs_;
  std::vector<int> ball_joints_;         // indices of ball joints with chain links
  std::vector<int> ball_tf_offset_;      // first tf_msgs_ slot of each ball joint's chain links

  struct MarkerSource {
    BodyId body;
    Transform local;   // marker frame in the body frame
  };
  visualization_msgs::MarkerArray markers_;
  std::vector<MarkerSource> marker_sources_;

  struct JointSource {
    JointId id;
    RagdollJointKind kind = RagdollJointKind::Hinge;
    int first = 0;     // index into joint_state_.position
  };
  sensor_msgs::JointState joint_state_;
  std::vector<JointSource> joint_sources_;
  std::vector<double> prev_positions_;
  int64_t prev_joint_step_ = -1;

  int64_t last_tf_step_ = -1;

  ros::Publisher markers_pub_, joints_pub_, broken_pub_;
  ros::Subscriber impulse_sub_, force_sub_, target_sub_;
  ros::ServiceServer pause_srv_, unpause_srv_, reset_srv_, clear_srv_, step_srv_;
  ros::ServiceServer balance_srv_, clear_targets_srv_;
};

}  // namespace node
}  // namespace ragdoll_sim
