// ragdoll_sim_node: loads a URDF ragdoll, simulates it in real time, publishes TF / markers /
// joint_states and takes impulse / force commands. Its topics, services and parameters:
// docs/interface.md.
#include <ros/ros.h>

#include "sim_node.hpp"

int main(int argc, char** argv) {
  ros::init(argc, argv, "ragdoll_sim");
  ragdoll_sim::node::SimNode node(ros::NodeHandle(), ros::NodeHandle("~"));
  std::string error;
  if (!node.init(&error)) {
    ROS_FATAL("ragdoll_sim: %s", error.c_str());
    return 1;
  }
  return node.run();
}
