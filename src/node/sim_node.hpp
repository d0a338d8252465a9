// SimNode: ragdoll_sim_node's start-up and main loop. It builds the Scene from the parameters
// and the launch-time URDF, then the adapters (command topics, services, reconfigure,
// publishers; node_context.hpp), and steps the Scene at a fixed rate, paced by the wall clock
// at a real-time factor or as fast as possible.
#pragma once

#include <atomic>
#include <memory>
#include <string>

#include <ros/ros.h>

#include "command_topics.hpp"
#include "node_context.hpp"
#include "object_services.hpp"
#include "reconfigure.hpp"
#include "services.hpp"

namespace ragdoll_sim {
namespace node {

class SimNode {
 public:
  // nh: public namespace (robot_description, joint_states); pnh: private (~) namespace.
  SimNode(const ros::NodeHandle& nh, const ros::NodeHandle& pnh);
  ~SimNode();

  // Reads the parameters, loads the URDF, builds the Scene and the ROS interface. Returns
  // false with *error naming the problem.
  bool init(std::string* error);

  // Steps until ROS shuts down or `stop` (SIGINT, SIGTERM), then deletes the spawned
  // ragdolls' parameters. Returns the process exit code.
  int run(const std::atomic<bool>& stop);

 private:
  // The parameters read that differ from the defaults (an inherited value shows here).
  void logParameters() const;
  // The launch-time ragdoll from ~urdf_file or robot_description.
  bool loadLaunchRagdoll(SpawnDef* spawn, std::string* source, std::string* error);

  NodeContext ctx_;
  std::unique_ptr<CommandTopics> topics_;
  std::unique_ptr<Services> services_;
  std::unique_ptr<ObjectServices> object_services_;
  std::unique_ptr<Reconfigure> reconfigure_;
};

}  // namespace node
}  // namespace ragdoll_sim
