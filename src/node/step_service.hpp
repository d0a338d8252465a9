// ~step: the service thread hands the call to the main loop, which runs the steps between its
// usual spinOnce calls, so every other service (get_link_state, pause, ...) is answered while
// a long call runs; the reply still comes once the steps are done. ~pause, ~unpause, ~reset and
// shutdown end a call early: the reply then says so and how many steps ran.
#pragma once

#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

#include <ros/callback_queue.h>
#include <ros/ros.h>

#include "ragdoll_sim/Step.h"

namespace ragdoll_sim {
namespace node {

struct NodeContext;

class StepService {
 public:
  using Clock = std::chrono::steady_clock;

  explicit StepService(NodeContext& ctx);
  ~StepService();
  // Advertises ~step on its own callback queue and thread.
  void advertise();

  // Main loop: whether a call waits for steps (the loop must not sleep then).
  bool busy() const;
  // Main loop: runs the steps of the call in progress until `until` (at least one), and
  // answers it once they are done.
  void serve(Clock::time_point until);
  // Main loop: ends the call in progress early (`why`: e.g. "~pause"), answering how many
  // steps ran.
  void end(const std::string& why);

 private:
  bool onStep(ragdoll_sim::Step::Request& req, ragdoll_sim::Step::Response& res);
  // Fills the reply's state fields from the Scene (main loop) and wakes the caller.
  void finish(bool success, const std::string& message);

  NodeContext& ctx_;
  ros::CallbackQueue queue_;
  std::unique_ptr<ros::AsyncSpinner> spinner_;
  ros::ServiceServer srv_;

  mutable std::mutex mutex_;
  std::condition_variable done_cv_;
  bool active_ = false;      // a call waits for the loop
  bool started_ = false;     // the loop has taken it (the node was paused)
  uint32_t requested_ = 0, done_ = 0;
  ragdoll_sim::Step::Response reply_;
};

}  // namespace node
}  // namespace ragdoll_sim
