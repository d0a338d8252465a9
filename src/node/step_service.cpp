#include "step_service.hpp"

#include "node_context.hpp"

namespace ragdoll_sim {
namespace node {

StepService::StepService(NodeContext& ctx) : ctx_(ctx) {}

StepService::~StepService() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (active_) {
      active_ = false;
      reply_.success = false;
      reply_.message = "the node is shutting down";
    }
  }
  done_cv_.notify_all();
  if (spinner_) spinner_->stop();
}

void StepService::advertise() {
  ros::AdvertiseServiceOptions o = ros::AdvertiseServiceOptions::create<ragdoll_sim::Step>(
      "step", [this](ragdoll_sim::Step::Request& req, ragdoll_sim::Step::Response& res) {
        return onStep(req, res);
      }, ros::VoidConstPtr(), &queue_);
  srv_ = ctx_.pnh.advertiseService(o);
  // One thread: a second ~step call waits for the first, every other service does not.
  spinner_ = std::make_unique<ros::AsyncSpinner>(1, &queue_);
  spinner_->start();
}

bool StepService::onStep(ragdoll_sim::Step::Request& req, ragdoll_sim::Step::Response& res) {
  std::unique_lock<std::mutex> lock(mutex_);
  active_ = true;
  started_ = false;
  requested_ = req.steps;
  done_ = 0;
  reply_ = ragdoll_sim::Step::Response();
  lock.unlock();
  ctx_.wakeup.notify();
  lock.lock();
  // Polled so that a node shutting down (the loop gone) still answers.
  while (active_ && ros::ok()) done_cv_.wait_for(lock, std::chrono::milliseconds(100));
  if (active_) {
    active_ = false;
    reply_.success = false;
    reply_.message = "the node is shutting down";
  }
  res = reply_;
  return true;
}

bool StepService::busy() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return active_;
}

void StepService::serve(Clock::time_point until) {
  uint32_t left = 0;
  bool too_many = false, running = false;  // a new call refused: beyond the cap, not paused
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!active_) return;
    if (!started_) {
      too_many = requested_ > static_cast<uint32_t>(ctx_.config.max_steps_per_call);
      running = !too_many && !ctx_.paused;
      started_ = !too_many && !running;
    }
    left = requested_ - done_;
  }
  if (too_many) {
    const std::string m = "step rejected: " + std::to_string(left) +
                          " steps exceed ~max_steps_per_call = " +
                          std::to_string(ctx_.config.max_steps_per_call);
    ctx_.warn("step/too many", m);
    return finish(false, m);
  }
  if (running) return finish(false, "the simulation is running; call ~pause first");
  uint32_t n = 0;
  do {
    if (n == left) break;
    ctx_.stepOnce();
    ++n;
  } while (Clock::now() < until && ros::ok());
  {
    std::lock_guard<std::mutex> lock(mutex_);
    done_ += n;
    if (done_ < requested_) return;
  }
  finish(true, "stepped " + std::to_string(requested_) + " step(s)");
}

void StepService::end(const std::string& why) {
  uint32_t done, requested;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!active_ || !started_) return;  // not taken yet: the loop answers it (or refuses it)
    done = done_;
    requested = requested_;
  }
  finish(false, "ended by " + why + " after " + std::to_string(done) + " of " +
                    std::to_string(requested) + " step(s)");
}

void StepService::finish(bool success, const std::string& message) {
  const Scene& scene = *ctx_.scene;
  std::lock_guard<std::mutex> lock(mutex_);
  reply_.success = success;
  reply_.message = message;
  reply_.steps_done = done_;
  reply_.sim_time = scene.time();
  reply_.pending_commands = static_cast<uint32_t>(scene.counters().queued);
  reply_.awake_bodies = static_cast<uint32_t>(scene.world().awakeBodyCount());
  reply_.resting_bodies = static_cast<uint32_t>(scene.world().islandCounters().resting_bodies);
  active_ = false;
  done_cv_.notify_all();
}

}  // namespace node
}  // namespace ragdoll_sim
