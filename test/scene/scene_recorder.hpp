// A SceneListener for the Scene's tests: keeps every message and counts the applied impulses and
// forces.
#pragma once

#include <string>
#include <vector>

#include "ragdoll_sim/scene.hpp"

namespace ragdoll_sim {
namespace test {

struct Recorder : SceneListener {
  std::vector<SceneMessage> messages;
  int impulses = 0, forces = 0;
  void message(const SceneMessage& m) override { messages.push_back(m); }
  void impulseApplied(const World&, BodyId, const Vec3&, const Vec3&, double) override {
    ++impulses;
  }
  void forceApplied(const World&, BodyId, const Vec3&, const Vec3&, double, double) override {
    ++forces;
  }
  const SceneMessage* find(const std::string& kind) const {
    for (const SceneMessage& m : messages)
      if (m.kind == kind) return &m;
    return nullptr;
  }
  bool saw(const std::string& kind) const { return find(kind) != nullptr; }
};

}  // namespace test
}  // namespace ragdoll_sim
