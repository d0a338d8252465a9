// The Scene's state and its internal steps, shared by the files that implement it, one concept
// each: scene.cpp (ragdolls and the World), scene_commands.cpp (queue and commands),
// scene_forces.cpp (timed forces, their budgets and caps), scene_motors.cpp (targets and
// balance), scene_step.cpp (settings, the step, reports), scene_objects.cpp (world files,
// objects, static objects), scene_reports.cpp (contacts and impacts by name),
// scene_efforts.cpp (joint loads, efforts and effort commands),
// scene_injury.cpp (injury records).
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

#include "command_queue.hpp"
#include "ragdoll_instance.hpp"
#include "ragdoll_sim/scene.hpp"
#include "static_object.hpp"
#include "surfaces.hpp"

namespace ragdoll_sim {

namespace scene {
// printf-style text, for messages that keep the node's printf formats.
std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));
}  // namespace scene

struct Scene::Impl {
  SceneDef def;
  SceneListener* listener = nullptr;
  std::unique_ptr<World> world;
  BodyId ground;
  std::vector<scene::RagdollInstance> ragdolls;  // dynamic objects too (RagdollInstance::object)
  std::unordered_map<std::string, size_t> ragdoll_index;  // name -> index in `ragdolls`
  std::vector<scene::StaticObject> statics;
  std::unordered_map<std::string, size_t> static_index;   // name -> index in `statics`
  // A static plane was added (a world's ground): the default plane is not built any more.
  bool ground_replaced = false;
  std::string ground_object;  // the static object whose plane is ground(); "" = none
  uint64_t next_serial = 1;
  scene::CommandQueue queue;
  uint64_t received = 0, applied = 0, rejected = 0, body_faults = 0;
  uint64_t impulses = 0, forces = 0;  // applied commands of each kind
  std::vector<double> force_sum, torque_sum;  // per link, scratch of applyActiveForces
  int64_t sim_ns = 0, steps = 0;
  double dt = 1e-3;
  std::function<void(World&, double)> before_forces;
  std::vector<BrokenJointReport> broken;

  double simTime() const { return static_cast<double>(sim_ns) * 1e-9; }
  void say(SceneMessage::Level level, const std::string& kind, const std::string& text) const;
  void debug(const std::string& text) const { say(SceneMessage::Level::Debug, "", text); }
  void info(const std::string& text) const { say(SceneMessage::Level::Info, "", text); }
  void warn(const std::string& kind, const std::string& text) const {
    say(SceneMessage::Level::Warn, kind, text);
  }

  // scene.cpp
  bool makeInstance(SpawnDef spawn, scene::RagdollInstance* out, std::string* error);
  // A new World with the ground and every ragdoll at its spawn pose, joints whole (start, reset).
  // may_refuse: spawn_overlap's Refuse applies (start), else overlaps are lifted (reset).
  bool buildWorld(bool may_refuse, std::string* error);
  void makeDefaultGround();  // the static plane z = 0 as ground
  bool spawnInWorld(scene::RagdollInstance& r, bool may_refuse, std::string* error);
  // The ragdoll's bodies out of static geometry: lifted (a WARN naming `what`, the spawn pose
  // moved with them when `spawn`), or false with *error when refused or wedged.
  bool clearStatics(scene::RagdollInstance& r, const std::string& what, bool may_refuse,
                    bool spawn, std::string* error);
  int find(const std::string& name) const;
  // "" when `name` is free, else which ragdoll or object has it.
  std::string nameTaken(const std::string& name) const;
  void reindexRagdolls(size_t from);
  // Pushes a made instance and, once started, spawns it; nothing is kept when it fails.
  SpawnResult addInstance(scene::RagdollInstance r, std::string* error);
  // The surface rules for a ragdoll or an object; every shape of `r` by them (warnings said
  // when `say_unknown`).
  scene::SurfaceRules surfaceRules(bool object) const;
  void resolveSurfaces(scene::RagdollInstance& r, bool say_unknown);

  // scene_objects.cpp
  // The bodies of a static object in the World (and, for its plane, the ground); false with
  // *error when the World refuses them, creating none.
  bool createStaticBodies(scene::StaticObject& o, std::string* error);
  // Adds a static object (made and checked): bodies when started, the ground when its plane.
  bool addStatic(scene::StaticObject o, std::string* error);
  void removeStatic(size_t i);

  // scene_motors.cpp
  void setBalance(scene::RagdollInstance& r, bool on, bool log);
  // Rebuilds every balance controller (they refer into the instances, which may have moved).
  void rebindControllers();
  void applyAxisMotor(scene::RagdollInstance& r, int axis);
  void applyAllMotors(scene::RagdollInstance& r);
  bool applyTargetPose(scene::RagdollInstance& r, const TargetPoseCommand& cmd);

  // scene_commands.cpp
  void applyCommand(const scene::QueuedCommand& cmd);
  // `link`: the command's link and frame as resolved on receipt
  bool applyImpulse(scene::RagdollInstance& r, const ImpulseCommand& cmd,
                    const scene::CommandCheck& link);

  // scene_forces.cpp
  bool applyForce(scene::RagdollInstance& r, const ForceCommand& cmd,
                  const scene::CommandCheck& link);
  size_t activeForceCount() const;
  // Every active force of `r` on the World, each link's sums capped; then one step less left.
  void applyActiveForces(scene::RagdollInstance& r);
  void expireForces(scene::RagdollInstance& r);

  // scene_step.cpp
  void reportBodyFaults();
  void collectBrokenJoints();

  // scene_efforts.cpp: joint effort commands
  bool applyJointEffort(scene::RagdollInstance& r, const JointEffortCommand& cmd);
  void applyActiveEfforts(scene::RagdollInstance& r);  // each step, before World::step
  size_t activeEffortCount() const;
  std::vector<ContactReport> contact_scratch;  // Scene::loads, capacity kept

  // scene_reports.cpp: contacts by name, impacts
  void findImpacts();  // after World::step

  // scene_injury.cpp
  std::vector<InjuryReport> injury_reports;
  SubstepVelocities samples_scratch;  // the head's, reused every step
  size_t injury_reports_old = 0;  // those made before or in the last step (updateInjury drops them)
  void updateInjury();  // after World::step: the head's samples, falls that ended
  // r's head and neck by `def` (names checked, "" guessed); false with *error, r unchanged.
  bool resolveInjury(scene::RagdollInstance& r, const InjuryDef& def, bool say,
                     std::string* error);
  void startInjury(scene::RagdollInstance& r);  // r is in the World: track its head, new record
  InjuryReport endInjury(const scene::RagdollInstance& r, const char* reason) const;
  void injuryRemoved(scene::RagdollInstance& r);  // a fall under way is reported
};

}  // namespace ragdoll_sim
