#include "scene_log.hpp"

#include <chrono>

#include <ros/console.h>

#include "visualization.hpp"

namespace ragdoll_sim {
namespace node {

void SceneLog::warn(const std::string& kind, const std::string& text) {
  const double now = std::chrono::duration<double>(
                         std::chrono::steady_clock::now().time_since_epoch()).count();
  uint64_t held = 0;
  if (!throttle_.allow(kind, now, &held)) return;
  if (held == 0) ROS_WARN("%s", text.c_str());
  else ROS_WARN("%s (%llu more like it in the last second not shown)", text.c_str(),
                static_cast<unsigned long long>(held));
}

void SceneLog::message(const SceneMessage& m) {
  switch (m.level) {
    case SceneMessage::Level::Debug: ROS_DEBUG("%s", m.text.c_str()); break;
    case SceneMessage::Level::Info: ROS_INFO("%s", m.text.c_str()); break;
    case SceneMessage::Level::Warn:
      if (m.kind.empty()) ROS_WARN("%s", m.text.c_str());
      else warn(m.kind, m.text);
      break;
    case SceneMessage::Level::Error: ROS_ERROR("%s", m.text.c_str()); break;
  }
}

void SceneLog::impulseApplied(const World& world, BodyId body, const Vec3& point,
                              const Vec3& impulse, double sim_time) {
  if (visualizer_) visualizer_->addImpulse(world, body, point, impulse, sim_time);
}

void SceneLog::forceApplied(const World& world, BodyId body, const Vec3& point, const Vec3& force,
                            double sim_time, double duration) {
  if (visualizer_) visualizer_->addForce(world, body, point, force, sim_time, duration);
}

}  // namespace node
}  // namespace ragdoll_sim
