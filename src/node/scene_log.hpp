// The Scene's listener in the node: its messages go to rosconsole (warnings throttled per kind,
// WarnThrottle), the impulses and forces it applies become arrows of the Visualizer.
#pragma once

#include <string>

#include "ragdoll_sim/scene.hpp"
#include "warn_throttle.hpp"

namespace ragdoll_sim {
namespace node {

class Visualizer;

class SceneLog : public SceneListener {
 public:
  void setVisualizer(Visualizer* v) { visualizer_ = v; }
  // WARN `text`, throttled per `kind` (a fixed name, never message contents): every kind of
  // problem is named at least once per second however many of another kind arrive.
  void warn(const std::string& kind, const std::string& text);

  void message(const SceneMessage& m) override;
  void impulseApplied(const World& world, BodyId body, const Vec3& point, const Vec3& impulse,
                      double sim_time) override;
  void forceApplied(const World& world, BodyId body, const Vec3& point, const Vec3& force,
                    double sim_time, double duration) override;

 private:
  scene::WarnThrottle throttle_{1.0};
  Visualizer* visualizer_ = nullptr;
};

}  // namespace node
}  // namespace ragdoll_sim
