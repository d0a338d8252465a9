// ragdoll_sim_node: loads a URDF ragdoll, simulates it in real time, publishes TF / markers /
// joint_states and takes impulse / force commands. Its topics, services and parameters:
// docs/interface.md.
#include <atomic>
#include <csignal>

#include <ros/ros.h>

#include "sim_node.hpp"

namespace {

// Set by SIGINT / SIGTERM: the loop ends while the master still answers, so the node can
// delete its spawned ragdolls' parameters (roscpp's own handler would shut ROS down first).
std::atomic<bool> g_stop{false};

// A second signal (the loop did not end, e.g. start-up waits for the master) stops roscpp.
void onSignal(int) {
  if (g_stop.exchange(true)) ros::requestShutdown();
}

}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "ragdoll_sim", ros::init_options::NoSigintHandler);
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  ragdoll_sim::node::SimNode node(ros::NodeHandle(), ros::NodeHandle("~"));
  std::string error;
  if (!node.init(&error)) {
    ROS_FATAL("ragdoll_sim: %s", error.c_str());
    return 1;
  }
  const int rc = node.run(g_stop);
  ros::shutdown();
  return rc;
}
