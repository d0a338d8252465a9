// dynamic_reconfigure (cfg/Physics.cfg): gravity, time step, real-time factor, solver,
// friction and sleep, applied through the Scene between steps.
#pragma once

#include <cstdint>
#include <memory>

#include <boost/thread/recursive_mutex.hpp>
#include <dynamic_reconfigure/server.h>

#include "ragdoll_sim/PhysicsConfig.h"

namespace ragdoll_sim {
namespace node {

struct NodeContext;

class Reconfigure {
 public:
  // Starts the server with the node's current values (not the .cfg defaults).
  explicit Reconfigure(NodeContext& ctx);

 private:
  void onReconfigure(ragdoll_sim::PhysicsConfig& cfg, uint32_t level);
  ragdoll_sim::PhysicsConfig current() const;

  NodeContext& ctx_;
  boost::recursive_mutex mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<ragdoll_sim::PhysicsConfig>> server_;
  bool ready_ = false;  // the server's first (initial) callback has run
};

}  // namespace node
}  // namespace ragdoll_sim
