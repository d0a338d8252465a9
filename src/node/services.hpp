// The node's services: pause / unpause / step (the loop), reset, clear_forces, clear_targets,
// set_balance, and the ragdoll services spawn, delete, set_ragdoll_state and get_link_state.
// Each checks what is ROS-specific (message poses, ~max_* parameters, URDF sources, TF
// prefixes) and calls the Scene; a refusal answers success = false with a message and a WARN
// throttled per kind.
#pragma once

#include <string>

#include <ros/ros.h>
#include <std_srvs/Empty.h>
#include <std_srvs/SetBool.h>

#include "ragdoll_sim/DeleteRagdoll.h"
#include "ragdoll_sim/GetLinkState.h"
#include "ragdoll_sim/SetRagdollState.h"
#include "ragdoll_sim/SpawnRagdoll.h"

namespace ragdoll_sim {
namespace node {

struct NodeContext;

class Services {
 public:
  explicit Services(NodeContext& ctx);
  // ~step (step_service.hpp), advertised last: tests take it as "the node is up".
  void advertiseStep();

 private:
  // success = false, message, and a WARN throttled per kind; returns true (the call worked).
  template <class Res>
  bool refuse(Res& res, const std::string& kind, const std::string& message);
  bool onSetBalance(std_srvs::SetBool::Request& req, std_srvs::SetBool::Response& res);
  bool onClearTargets(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onPause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onUnpause(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onReset(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onClearForces(std_srvs::Empty::Request&, std_srvs::Empty::Response&);
  bool onSpawn(ragdoll_sim::SpawnRagdoll::Request& req, ragdoll_sim::SpawnRagdoll::Response& res);
  bool onDelete(ragdoll_sim::DeleteRagdoll::Request& req, ragdoll_sim::DeleteRagdoll::Response& res);
  bool onSetState(ragdoll_sim::SetRagdollState::Request& req,
                  ragdoll_sim::SetRagdollState::Response& res);
  bool onGetLinkState(ragdoll_sim::GetLinkState::Request& req,
                      ragdoll_sim::GetLinkState::Response& res);

  NodeContext& ctx_;
  ros::ServiceServer balance_srv_, clear_targets_srv_, spawn_srv_, delete_srv_, set_state_srv_;
  ros::ServiceServer get_link_srv_, pause_srv_, unpause_srv_, reset_srv_, clear_srv_;
};

}  // namespace node
}  // namespace ragdoll_sim
