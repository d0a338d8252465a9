// runFall (fall_run.hpp): the Scene of one run, built, pushed and stepped; a refusal of the
// Scene becomes an exception carrying its message.
#include "ragdoll_sim/fall_run.hpp"

#include <stdexcept>

namespace ragdoll_sim {

namespace {

// The scene's warnings and errors, the last one kept: what a refused push says.
struct LastProblem : SceneListener {
  std::string text;
  void message(const SceneMessage& m) override {
    if (m.level == SceneMessage::Level::Warn || m.level == SceneMessage::Level::Error)
      text = m.text;
  }
};

}  // namespace

FallRecord runFall(const FallRunDef& d) {
  if (!d.model) throw std::invalid_argument("fall run: no model");
  if (d.steps < 0)
    throw std::invalid_argument("fall run: steps must be >= 0, got " + std::to_string(d.steps));
  const std::string settings = worldDefError(d.scene.world);
  if (!settings.empty()) throw std::invalid_argument("fall run: " + settings);
  LastProblem problems;
  Scene scene(d.scene, &problems);
  std::string error;
  if (d.world && !scene.loadWorld(*d.world, &error))
    throw std::invalid_argument("world '" + d.world->name + "': " + error);
  SpawnDef spawn;
  spawn.name = d.name;
  spawn.def = *d.model;
  spawn.pose = d.pose;
  if (scene.addRagdoll(std::move(spawn), &error) != SpawnResult::Added)
    throw std::invalid_argument("spawn: " + error);
  if (!scene.start(&error)) throw std::invalid_argument("spawn: " + error);
  const int k = scene.find(d.name);
  if (!d.linear_velocity.isZero() || !d.angular_velocity.isZero())
    scene.setRagdollState(k, scene.spawnPose(k), d.linear_velocity, d.angular_velocity);
  if (!d.push_link.empty()) {
    const int link = scene.findLink(k, d.push_link);
    if (link < 0)
      throw std::invalid_argument("push: ragdoll '" + d.name + "' has no link '" + d.push_link +
                                  "'");
    ImpulseCommand push;
    push.link = d.push_link;
    push.frame = "world";
    push.point = scene.linkState(k, link).com;
    push.impulse = d.push_impulse;
    const uint64_t rejected = scene.counters().rejected;
    scene.submit(d.name, push, scene.timeNs());
    scene.applyDueCommands();
    if (scene.counters().rejected != rejected)
      throw std::invalid_argument("push: " + problems.text);
  }
  FallRecorder recorder(scene, d.name, d.record);
  recorder.run(scene, d.steps);
  return recorder.record(scene);
}

}  // namespace ragdoll_sim
