// dynamic_reconfigure (cfg/Physics.cfg): gravity, time step, real-time factor, solver,
// friction and sleep, applied through the Scene between steps. The node serves the protocol
// itself (~set_parameters, ~parameter_descriptions, ~parameter_updates) because
// dynamic_reconfigure::Server clamps a request before its callback could refuse it: here a
// value outside its range (physics_ranges.hpp) refuses the whole request with a WARN.
#pragma once

#include <dynamic_reconfigure/Reconfigure.h>
#include <ros/ros.h>

#include "ragdoll_sim/PhysicsConfig.h"

namespace ragdoll_sim {
namespace node {

struct NodeContext;

class Reconfigure {
 public:
  // Starts the server with the node's current values (not the .cfg defaults).
  explicit Reconfigure(NodeContext& ctx);

 private:
  bool onSetParameters(dynamic_reconfigure::Reconfigure::Request& req,
                       dynamic_reconfigure::Reconfigure::Response& res);
  // Applies a configuration inside the ranges; logs what changed.
  void apply(const ragdoll_sim::PhysicsConfig& cfg);
  // The values in force to ~parameter_updates and the parameter server.
  void publish();
  ragdoll_sim::PhysicsConfig current() const;

  NodeContext& ctx_;
  ros::ServiceServer set_srv_;
  ros::Publisher descriptions_pub_, updates_pub_;
};

}  // namespace node
}  // namespace ragdoll_sim
