// What the node's adapters share: the parameters, the Scene, the clock, the publishers and
// the loop's pause flag. Each adapter (command topics, services, reconfigure, publishers)
// turns ROS input into Scene calls or Scene state into messages; none holds scene rules.
#pragma once

#include <chrono>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>

#include <ros/ros.h>

#include "interaction.hpp"
#include "node_config.hpp"
#include "pacing.hpp"
#include "publishers.hpp"
#include "report_topics.hpp"
#include "ragdoll_sim/scene.hpp"
#include "scene_log.hpp"
#include "sim_clock.hpp"
#include "spawned_params.hpp"
#include "step_service.hpp"
#include "visualization.hpp"

namespace ragdoll_sim {
namespace node {

// The loop's sleep between iterations, cut short when a ~step call arrives on its thread.
class LoopWakeup {
 public:
  void notify() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      pending_ = true;
    }
    cv_.notify_one();
  }
  void sleepUntil(std::chrono::steady_clock::time_point t) {
    std::unique_lock<std::mutex> lock(mutex_);
    cv_.wait_until(lock, t, [this] { return pending_; });
    pending_ = false;
  }

 private:
  std::mutex mutex_;
  std::condition_variable cv_;
  bool pending_ = false;
};

struct NodeContext {
  ros::NodeHandle nh, pnh;
  NodeConfig config;
  SceneLog log;                  // the Scene's messages and arrows; outlives the Scene
  std::unique_ptr<Scene> scene;
  SimClock clock;
  std::unique_ptr<Visualizer> visualizer;     // ~markers: shapes, contacts, arrows
  std::unique_ptr<Interaction> interaction;   // /clicked_point pokes, ~drag marker
  std::unique_ptr<Publishers> publishers;
  std::unique_ptr<ReportTopics> reports;       // ~contacts, ~link_loads, ~impacts, ~injury
  std::unique_ptr<SpawnedParams> spawned_params;  // <name>/robot_description of ~spawn
  scene::Pacer pacer;
  bool paused = false;
  bool pacing_dirty = false;     // restart the pacer at the next loop iteration
  LoopWakeup wakeup;
  std::unique_ptr<StepService> steps;  // last: its thread stops before the rest goes

  NodeContext(const ros::NodeHandle& n, const ros::NodeHandle& p) : nh(n), pnh(p) {}

  // One Scene step, then /clock, ~joint_broken, the markers' record and the reports of the
  // step.
  void stepOnce();
  // Publishing buffers, markers and drag handles follow a change of the ragdolls or the World.
  void structureChanged();
  void restartPacing();
  void warn(const std::string& kind, const std::string& text) { log.warn(kind, text); }
};

}  // namespace node
}  // namespace ragdoll_sim
