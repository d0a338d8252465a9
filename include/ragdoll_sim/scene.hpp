// Scene: the ROS-free simulation layer above the World (as tf2 sits under tf2_ros). It owns the
// World, the ragdolls by name, the queue of stamped commands, impulses, timed forces, joint
// motor targets (moving ones too), the balance controllers, the clock of the fixed step and
// the reports (body faults, broken joints, command counters). ragdoll_sim_node is a set of
// ROS adapters on top of it: message -> Scene call -> publishers.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "ragdoll_sim/balance.hpp"
#include "ragdoll_sim/injury.hpp"
#include "ragdoll_sim/material.hpp"
#include "ragdoll_sim/math.hpp"
#include "ragdoll_sim/ragdoll.hpp"
#include "ragdoll_sim/scene_reports.hpp"
#include "ragdoll_sim/world.hpp"
#include "ragdoll_sim/world_file.hpp"

namespace ragdoll_sim {

// Caps on what one command may ask for, and on what the active forces on one link add up to.
struct CommandLimits {
  double max_impulse = 1000.0;   // N*s
  double max_force = 1e5;        // N
  double max_torque = 1e5;       // N*m
  double max_lever_arm = 10.0;   // m, distance of the application point from the link origin
  // Each step, the sums of |force| and of |torque| of the active forces on one link; above
  // them every force (torque) on that link is scaled down by the same factor.
  double max_body_force = 1e5;   // N
  double max_body_torque = 1e5;  // N*m
};

// Gains of the position motors that drive joints to their targets (and hold the pose when the
// balance controller is on): soft constraint of natural frequency `hertz` and damping ratio
// `damping_ratio` (relative to the joint's effective rotational inertia, see
// src/core/part_angle_motor.hpp), torque capped at `max_torque`.
struct MotorGains {
  double hertz = 120.0;         // Hz
  double damping_ratio = 1.0;
  double max_torque = 5000.0;   // N m
};

// Per-joint settings (config/joints.yaml): only the fields that are present are set.
struct JointSettings {
  // Anchor (JointSpring): stiffness N/m (0 = rigid), damping N s/m, break_force N (.inf = never);
  // break_torque N m (.inf = never), the rotation lock of a fixed joint.
  std::optional<double> stiffness, damping, break_force, break_torque;
  // Motor gains (the entry's `motor` map).
  std::optional<double> hertz, damping_ratio, max_torque;
  // Ball joints only: swing-twist limits (RagdollJointDef::swing_twist) replacing the Euler
  // limits, rad: cone half-angles about the joint's axes[1] and axes[2], twist range about
  // axes[0] (each over the URDF's <limit cone_y ...>, the other side kept or free).
  std::optional<std::array<double, 2>> cone, twist;
};

// Velocity damping of one link, 1/s (LinkDef linear_damping / angular_damping), over the
// URDF's <gazebo> dampingFactor; a field left out keeps the URDF's value.
struct LinkDamping {
  std::optional<double> linear, angular;
};

// An impulse on one link. frame "" or "world": point and impulse in world coordinates; "link":
// point relative to the link origin, impulse in link axes.
struct ImpulseCommand {
  std::string link;
  std::string frame;
  Vec3 point = Vec3::Zero();
  Vec3 impulse = Vec3::Zero();
};

// A force (and torque) on one link, re-applied every step for `duration`; frames as above. The
// point stays fixed in the link, the vectors fixed in world axes.
struct ForceCommand {
  std::string link;
  std::string frame;
  Vec3 point = Vec3::Zero();
  Vec3 force = Vec3::Zero();
  Vec3 torque = Vec3::Zero();
  double duration = 0.0;  // s of sim time; < 0: until cleared; 0: one physics step
};

// Joint targets by joint_states name (sensor_msgs/JointState's fields): per name a position
// (rad, moving at `velocity` when both are given) or a velocity.
struct TargetPoseCommand {
  std::vector<std::string> names;
  std::vector<double> position, velocity;
};

using SceneCommandVariant =
    std::variant<ImpulseCommand, ForceCommand, TargetPoseCommand, JointEffortCommand>;

// The surface of ragdolls and ground unless ~materials name others.
inline Material defaultSurface() { return Material{0.8, 0.6, 0.0, 0.05}; }

// What becomes of a ragdoll placed into static geometry (the ground plane, static shapes):
// found with World::staticOverlap at its spawn pose, deeper than 5 mm (shallower overlaps are
// left to the contacts).
enum class SpawnOverlap {
  Lift,    // moved up rigidly until its lowest shape point rests on it (along a plane's
           // normal), with a WARN naming the ragdoll and the lift; reset() goes back there
  Refuse,  // addRagdoll (and start, for those added before it) refuses it with a message
};

struct SceneDef {
  WorldDef world;                  // gravity, solver, speed caps, sleep, material table, threads
  int64_t dt_ns = 1000000;         // fixed step, ns
  bool ground = true;              // static ground plane z = 0
  SpawnOverlap spawn_overlap = SpawnOverlap::Lift;  // a spawn into static geometry
  Material material = defaultSurface();  // the shared surface (setMaterials replaces it)
  Material ragdoll_surface = defaultSurface();
  Material ground_surface = defaultSurface();
  CommandLimits limits;
  int max_queued_commands = 4096;  // waiting commands; beyond, a submit is dropped
  int max_forces_per_ragdoll = 64;  // active forces of one ragdoll; beyond, refused
  int max_active_forces = 4096;     // over all ragdolls (against a flood of ragdolls)
  MotorGains motor;                // every joint's target / hold motor unless `joints` say else
  JointSettings joint_defaults;    // springs and gains of every joint
  std::vector<std::pair<std::string, JointSettings>> joints;  // joint name -> settings
  // Link name -> material table name for ragdoll links that name none themselves (a rubber sole
  // on the feet); "*" matches every link.
  std::vector<std::pair<std::string, std::string>> link_materials;
  // Link name -> velocity damping of ragdoll links; "*" matches every link (a named entry wins).
  std::vector<std::pair<std::string, LinkDamping>> link_damping;
  Material object_surface = defaultSurface();  // objects' links that name no material
  // The balance controllers' law (their hold motors use `motor`, then the per-joint gains).
  BalanceDef balance;
  ImpactDef impacts;
  InjuryDef injury;  // every ragdoll's head and neck unless setInjury names others
};

struct SpawnDef {
  std::string name;            // unique; a ROS graph name token of <= 128 characters
  RagdollDef def;
  Transform pose;              // root link in the world (reset() goes back here)
  bool balance = false;        // balance controller (SceneDef::balance) on from the start
  bool warn_unknown_joints = false;  // SceneDef::joints entries naming no joint of it: WARN
  // An object (a crate, a door, a world file's model) rather than a ragdoll: no balance, no
  // per-link material map, counted apart. A dynamic object is indexed like a ragdoll (bodies,
  // link states, commands); a static one (is_static) is a set of static bodies that costs
  // nothing per step, listed by staticObjectCount().
  bool object = false;
  bool is_static = false;  // objects only: every link a static body where it is placed
  bool fixed_base = false; // the root link pinned at `pose` (as RagdollDef::fixed_base)
};

enum class SpawnResult {
  Added,
  BadName,       // not a valid name (src/scene/names.hpp)
  BadModel,      // no links, or joint settings that conflict
  NameInUse,
  WorldRefused,  // the World cannot simulate it there (e.g. a non-finite pose)
};

// A ragdoll's handle that stays valid while the ragdoll exists (indices shift on removal).
struct RagdollId {
  uint64_t serial = 0;
  bool valid() const { return serial != 0; }
  bool operator==(const RagdollId& o) const { return serial == o.serial; }
  bool operator!=(const RagdollId& o) const { return serial != o.serial; }
};

// What the scene tells its user: kind "" = always shown; else the key of a per-kind throttle
// (a fixed short name, never message contents).
struct SceneMessage {
  enum class Level { Debug, Info, Warn, Error };
  Level level = Level::Info;
  std::string kind;
  std::string text;
};

// A joint that broke in the last step.
struct BrokenJointReport {
  std::string ragdoll, joint, parent_link, child_link;
  double force = 0.0;          // N, anchor force when it broke
  double torque = 0.0;         // N m, lock torque
  double break_force = 0.0, break_torque = 0.0;
};

// received = applied + rejected + dropped + queued; of the applied, `impulses` and `forces`
// were impulse and force commands.
struct SceneCounters {
  uint64_t received = 0, applied = 0, rejected = 0, dropped = 0, body_faults = 0;
  uint64_t impulses = 0, forces = 0;
  size_t queued = 0, max_queued = 0, queue_capacity = 0;
  size_t active_forces = 0;  // acting now
};

// A link's state for get_link_state.
struct LinkState {
  Transform pose;
  Vec3 linear_velocity = Vec3::Zero();   // of the link origin
  Vec3 angular_velocity = Vec3::Zero();
  Vec3 com = Vec3::Zero();               // world centre of mass
};

// Observers of what commands did (display of arrows).
struct SceneListener {
  virtual ~SceneListener() = default;
  virtual void message(const SceneMessage&) {}
  virtual void impulseApplied(const World&, BodyId, const Vec3& point, const Vec3& impulse,
                              double sim_time) {}
  // duration < 0: until cleared
  virtual void forceApplied(const World&, BodyId, const Vec3& point, const Vec3& force,
                            double sim_time, double duration) {}
};

class Scene {
 public:
  explicit Scene(SceneDef def, SceneListener* listener = nullptr);
  ~Scene();
  Scene(const Scene&) = delete;
  Scene& operator=(const Scene&) = delete;

  // --- ragdolls ---
  // Before start(): readies the ragdoll (joint settings); after: spawns it into the World,
  // lifted out of static geometry or refused there (SceneDef::spawn_overlap).
  // False with *error (the model, its joint settings, a name in use, a pose the World refuses).
  SpawnResult addRagdoll(SpawnDef spawn, std::string* error);
  // Builds the World: the ground and every ragdoll added so far, balance as they asked; those
  // placed into static geometry are lifted or, with SpawnOverlap::Refuse, fail the start.
  bool start(std::string* error);
  // Removes `name` and its bodies; other ragdolls keep their state and broken joints.
  bool removeRagdoll(const std::string& name, std::string* error);

  // --- world files and objects ---
  // A loaded world file, before or after start(): static models become static objects, dynamic
  // ones objects (joints to the world pin them), its gravity the World's; a static plane in it
  // replaces the default ground. False with *error naming the model, nothing added.
  bool loadWorld(const WorldFileDef& world, std::string* error);
  // spawn.object is implied. Names share one namespace with the ragdolls.
  SpawnResult addObject(SpawnDef spawn, std::string* error);
  bool isObject(int k) const;                // ragdoll index k is a dynamic object
  size_t staticObjectCount() const;
  const std::string& staticObjectName(int i) const;
  const RagdollDef& staticObjectDef(int i) const;
  const Transform& staticObjectPose(int i) const;              // its root link
  const std::vector<BodyId>& staticObjectBodies(int i) const;  // one per link
  // Removes the ragdoll, dynamic object or static object `name`.
  bool remove(const std::string& name, std::string* error);
  // Every ragdoll back at its spawn pose with its joints whole; active forces and joint
  // efforts end. A ragdoll
  // that overlaps static geometry there is lifted (WARN), whatever spawn_overlap says.
  bool reset(std::string* error);
  // Rigid move of ragdoll k: root link to `root`, every body with linear velocity
  // v + w x (com - root.p) and angular velocity w. A pose into static geometry is lifted out of
  // it (WARN), whatever spawn_overlap says: the ragdoll exists, only its pose is corrected.
  void setRagdollState(int k, const Transform& root, const Vec3& v, const Vec3& w);
  LinkState linkState(int k, int link) const;

  size_t ragdollCount() const;
  int find(const std::string& name) const;  // index ("" = the first), or -1
  int indexOf(RagdollId id) const;          // -1 when removed
  RagdollId id(int k) const;
  const std::string& name(int k) const;
  const RagdollDef& def(int k) const;
  // Root link pose reset() goes back to: the spawn pose, lifted out of static geometry.
  const Transform& spawnPose(int k) const;
  const Ragdoll& bodies(int k) const;       // ids in the World (new ids after a rebuild)
  int findLink(int k, const std::string& link) const;   // RagdollDef::links index, or -1
  const std::vector<std::string>& axisNames(int k) const;  // joint_states names
  int firstAxis(int k, int joint) const;    // first axis of a RagdollDef joint
  // The balance controller's unknown ankles and feet (nullptr when balance is off).
  const std::vector<std::string>* balanceMissing(int k) const;

  // --- commands ---
  // Queues `command` for ragdoll `ragdoll` ("" = the first) until sim time due_ns; the ragdoll
  // is resolved now. False (and a WARN) when it is unknown or the queue is full.
  bool submit(const std::string& ragdoll, SceneCommandVariant command, int64_t due_ns);
  // A command refused before submit (counted as received and rejected, WARN `kind`).
  void reject(const std::string& kind, const std::string& text);
  void applyDueCommands();  // those due at the current sim time
  size_t activeForceCount() const;
  // Ends every active force and joint effort (JointEffortCommand); returns how many ended
  // (forces plus effort axes).
  size_t clearForces();
  void clearTargets();
  void setBalance(bool on);  // every ragdoll
  bool balanceOn(int k) const;

  // --- settings ---
  void setGravity(const Vec3& g);
  void setTimeStep(int64_t dt_ns);
  void setSleep(const SleepDef& sleep);
  // Every solver setting, on the live World (nothing wakes); false with *error naming the first
  // field out of range, changing nothing.
  bool setSolverSettings(const SolverSettings& solver, std::string* error);
  // One surface for every ragdoll shape and the ground, and the pair table.
  void setMaterials(const Material& surface, const MaterialTable& table);

  // --- reports of the last step (scene_reports.hpp, injury.hpp) ---
  // "ragdoll/link", "object/link" (static objects too) or "ground".
  std::string bodyName(const BodyRef& body) const;
  BodyRef bodyRef(BodyId body) const;  // all -1 for a body of no ragdoll, object or ground
  // Touching pairs after the last step, into `out` (cleared, capacity reused).
  void contacts(std::vector<SceneContact>& out) const;
  // Ragdoll k's loads after the last step: one LinkLoad per RagdollDef link, one JointLoad per
  // RagdollDef joint (into the vectors, cleared, capacity reused).
  void loads(int k, std::vector<LinkLoad>& links, std::vector<JointLoad>& joints) const;
  // The link half of loads(): what a per-step sampler needs without the joints' wrenches.
  void linkLoads(int k, std::vector<LinkLoad>& links) const;
  // Ragdoll k's axis efforts in axisNames(k) order (motor + limit + commanded effort).
  void jointEfforts(int k, std::vector<double>& out) const;
  size_t activeEffortCount() const;  // axes with a commanded effort acting now
  void setImpacts(const ImpactDef& def);
  const std::vector<ImpactEvent>& impacts() const;  // found in the last step()
  // Head and neck of ragdoll k: "" names are guessed as InjuryDef says. False with *error
  // naming an unknown link or joint, changing nothing.
  bool setInjury(int k, const InjuryDef& def, std::string* error);
  const std::string& headLink(int k) const;   // "" when it has none (no injury record)
  const std::string& neckJoint(int k) const;  // "" when none
  // The fall record of ragdoll k so far (reason "").
  InjuryReport injury(int k) const;
  // Ends ragdoll k's record now (reason "reset") and starts a new one; returns the ended one.
  InjuryReport resetInjury(int k);
  // Falls that ended in the last step() (reason "rest") or with their ragdoll's removal.
  const std::vector<InjuryReport>& injuryReports() const;

  // --- stepping ---
  // Called every step after the due commands and before the forces (the node's drag springs).
  void setBeforeForces(std::function<void(World&, double sim_time)> fn);
  // Due commands, drags, forces, motors, balance, one World::step, reports.
  void step();
  // Joints broken in the last step().
  const std::vector<BrokenJointReport>& brokenJoints() const;

  int64_t timeNs() const;
  double time() const;      // s
  int64_t steps() const;
  int64_t dtNs() const;
  double dt() const;
  SceneCounters counters() const;
  const SceneDef& def() const;

  World& world();
  const World& world() const;
  BodyId ground() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ragdoll_sim
