// The simulation world: bodies, shapes, joints, contacts and one solver step.
// ROS-free; the node and the tests drive it through this API only.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "ragdoll_sim/body.hpp"
#include "ragdoll_sim/joint.hpp"
#include "ragdoll_sim/material.hpp"
#include "ragdoll_sim/shape.hpp"
#include "ragdoll_sim/world_reports.hpp"

// SolverSettings::lanes' default; a build may set it (CMake RAGDOLL_SIM_DEFAULT_LANES) to run
// the whole test suite on the other path.
#ifndef RAGDOLL_SIM_DEFAULT_LANES
#define RAGDOLL_SIM_DEFAULT_LANES 0
#endif

namespace ragdoll_sim {

// Sleeping and the rest substeps: read at every step, so World::setSleep changes them while the
// world runs.
struct SleepDef {
  bool enabled = true;
  double time = 0.5;    // s an island must stay slow before it sleeps
  double speed = 0.05;  // m/s, max(|v|, extent |w|) below this counts as slow (Box2D v3)
  // m/s: every body of an island counts as slow while the island's kinetic energy is below
  // that of its whole mass moving at island_speed (sum m v^2 + w.I.w < M island_speed^2). A
  // light limb turning about a frictionless joint in a resting ragdoll loses no energy, so
  // without it that island would never sleep; 0 turns this rule off.
  double island_speed = 0.05;
  // An island whose bodies have all been slow for rest_time is solved with rest_substeps
  // substeps of rest_relax_iterations relax sweeps each, until one of its bodies moves faster,
  // is woken or it sleeps: the last part of the sleep time costs less. A body that moved faster
  // on them keeps its islands on the full substeps until it sleeps. rest_substeps 0 (or not
  // below SolverSettings::substeps) turns it off; it needs `enabled` (it reads the sleep
  // timers). A split island shares its substep loop with the islands solved along with its
  // halves: it takes the rest substeps only when they all rest too.
  double rest_time = 0.05;
  int rest_substeps = 2;
  int rest_relax_iterations = 1;
  // Whether resting islands take the rest substeps under `substeps` full ones.
  bool restOn(int substeps) const {
    return enabled && rest_substeps > 0 && rest_substeps < substeps;
  }
};

// "" when the settings can be used, else what is wrong with the first field that cannot, named
// as in the struct ("speed must be a finite number >= 0, got -1"): time, speed, island_speed and
// rest_time finite and >= 0, rest_substeps and rest_relax_iterations >= 0.
std::string sleepDefError(const SleepDef& sleep);

// How the solver iterates and how soft and how far it corrects: the knobs one tunes while the
// world runs (World::setSolverSettings), apart from what describes the world itself (WorldDef).
struct SolverSettings {
  int substeps = 3;                     // solver substeps per step (soft step)
  int contact_relax_iterations = 4;     // relax sweeps over the contacts per substep
  int joint_relax_iterations = 2;       // of which the first this many also relax the joints
  // Position (non-linear Gauss-Seidel) sweeps after the substeps over penetrating contacts,
  // joint rotations (angle and slide limits, hinge axes, rotation locks) and joint anchors
  // (points, slider lines): they remove the error left by hard hits without adding velocity.
  int position_iterations = 3;
  // Sweeps over the joint anchors alone after those: along a limb each projection moves a body
  // that the next joint shares, so one sweep can leave an anchor at up to twice joint_slop.
  int anchor_iterations = 1;
  double position_factor = 0.5;           // share of a contact's penetration removed per sweep
  double max_position_correction = 0.05;  // m, the most one projection sweep moves a point
  // m, anchor error left to the soft velocity rows: projection moves bodies without velocity,
  // so friction cannot hold against it, and without a slop a resting ragdoll creeps.
  double joint_slop = 0.0005;
  // rad, how far outside its range a joint angle may stay before the projection turns it back
  // (left to the soft limit rows, like joint_slop), and the most one sweep turns it.
  double angular_slop = 0.02;
  double max_angular_correction = 0.2;
  double contact_hertz = 360.0;         // contact softness (capped at a quarter of the substep rate)
  double contact_damping_ratio = 10.0;
  double joint_hertz = 1000.0;          // joint position-error softness
  double joint_damping_ratio = 2.0;
  double max_push_velocity = 3.0;       // m/s, cap on the velocity used to push bodies apart
  double restitution_threshold = 1.0;   // m/s, no bounce below this approach speed
  double static_friction_speed = 0.02;  // m/s, below this tangential speed static friction holds
  double speculative_distance = 0.02;   // m, contacts are made this far before touching
  double linear_slop = 0.0005;          // m, penetration allowed to keep contacts warm
  // Clamps against blow-ups, applied to every body before the step (a huge impulse never
  // enters the solver), per substep and after it.
  double max_linear_speed = 100.0;      // m/s
  double max_angular_speed = 200.0;     // rad/s
  // Joint anchors solved exactly per joint tree after the sweeps, velocities every substep and
  // positions after the step (src/core/joint_tree.hpp): they hold at any mass ratio. Off: the
  // sweeps alone, which stretch where light links hang on heavy ones.
  bool exact_joints = true;
  // Contact rows (and, as they move over, the joint parts) solved in float lanes, many
  // constraints at once (docs/physics.md, the wide solver): 1 solves every row alone in double
  // (the reference); 0 takes the widest the CPU runs (8 with AVX2, two blocks of 8 at once with
  // AVX-512F, else 4) once a step's islands hold 24 awake bodies, and the double rows below
  // that (a lone ragdoll fills too few lanes to gain); 4 or 8 force a width at any size, as the
  // environment variable RAGDOLL_SIM_LANES=4|8 does for 0. 4 and 8 give the same bits, and 0
  // gives theirs from 24 awake bodies (World::laneWidth says which width runs).
  int lanes = RAGDOLL_SIM_DEFAULT_LANES;
};

// "" when the settings can be used, else what is wrong with the first field that cannot, named
// as in the struct ("contact_hertz must be ..."): the ranges are in src/core/world_def.cpp.
std::string solverSettingsError(const SolverSettings& solver);

struct WorldDef {
  Vec3 gravity = Vec3(0, 0, -9.81);
  SolverSettings solver;                // World::setSolverSettings
  SleepDef sleep;                       // sleeping and the rest substeps (World::setSleep)
  MaterialTable materials;              // pair coefficients and the combine rules (setMaterials)
  // Islands are solved in parallel on this many threads (0: all cores). The result does not
  // depend on it: islands share no bodies and each is solved in the same order. Default 1: on a
  // machine whose cores are busy, waiting for a preempted worker costs more than it gains.
  int threads = 1;
  static constexpr int kMaxThreads = 256;  // more is a typo: the step would start them all
};

// "" when the World can simulate with these settings, else what is wrong with the first field
// that it cannot, named as in the struct ("sleep.speed must be a finite number >= 0, got -1");
// the solver's fields are named without "solver.", as the node's flat parameters are. World's
// constructor throws std::invalid_argument with it.
std::string worldDefError(const WorldDef& def);

// A contact point for display and tests.
struct ContactInfo {
  BodyId body_a, body_b;
  Vec3 point;          // world, midway between the surfaces
  Vec3 normal;         // world, from A to B
  double separation;   // negative when penetrating
  double normal_impulse;
};

// What the last step solved (Box2D v3's b2World_GetCounters): for profiling and tests.
struct IslandCounters {
  int islands = 0;        // awake islands
  int split_islands = 0;  // of which solved in two halves (the biggest, when it is most of the work)
  int largest_island = 0; // bodies in the biggest awake island
  int bodies = 0;         // awake bodies in the islands
  int joints = 0;         // joints solved
  int contacts = 0;       // contact manifolds solved
  int resting_islands = 0;  // solved with the rest substeps (SleepDef::rest_substeps)
  int resting_bodies = 0;   // bodies in those
  // The wide solver (SolverSettings::lanes; all 0 in a step solved in double rows): the batches
  // the solve built (a range of whole islands of a thread's run, a split island's half or an
  // island attached to it, a group of its boundary; docs/physics.md, the wide solver), and the
  // contact manifolds and joint anchors in their float lanes against the lanes of their blocks
  // (rows / lanes: how full the lanes are). With more than one thread the batches follow the
  // threads' runs and what they stole, so they can differ between runs; the bits never do.
  int lane_batches = 0;
  int contact_lane_rows = 0, contact_lanes = 0;
  int joint_lane_rows = 0, joint_lanes = 0;
};

// Wall time of the last step's phases in microseconds (Box2D v3's b2World_GetProfile), while
// profiling is on (World::setProfiling); the parts of `collide` are within it, the other
// phases follow one another and add up to `step`. `solve` is the islands' whole solve (prepare,
// substeps, position sweeps, the bodies' new state) on all threads, as the caller waits for it.
struct StepProfile {
  double step = 0.0;         // the whole World::step
  double guard = 0.0;        // the fault guard on the inputs
  double collide = 0.0;      // boxes, pairs and manifolds, of which:
  double boxes = 0.0;        //   the moving shapes' boxes (and static ones when they changed)
  double pairs = 0.0;        //   broadphase, static tree, pair keys and their merge
  double narrowphase = 0.0;  //   manifolds, kept or new
  double islands = 0.0;      // union-find, active joints, islands' ranges, splits, thread runs
  double solve = 0.0;        // the islands' solve
  double finish = 0.0;       // joint breaks, bodies outside the islands, faults, sleep
  // Within solve, summed over its threads: the time a thread had nothing to solve in a parallel
  // region (before its start reached the thread, after the thread's last island) or waited for
  // the other half of a split island at a barrier. Not a phase: `step` leaves it out. 0 on one
  // thread.
  double solve_wait = 0.0;
};

// The deepest overlap of some bodies' shapes with static shapes (World::staticOverlap).
struct StaticOverlap {
  double depth = 0.0;              // m; 0 when no shape reaches into a static one
  Vec3 direction = Vec3::UnitZ();  // unit: the bodies moved by depth * direction clear that pair
  BodyId body;                     // the deepest pair: one of the bodies, its shape index in
  int shape = -1;                  // bodyShapes(body), and the static body
  BodyId static_body;
};

// A body whose state was not finite (NaN / inf), or whose centre of mass left the world range
// (a coordinate beyond +-kWorldRange, math.hpp), found and undone by World::step: the body is
// back at its last good pose (finite and in range) with zero velocity, its forces dropped, and
// the warm-start impulses of its joints and contacts cleared. The rest of the world goes on.
enum class BodyFaultCause : uint8_t {
  Input,   // before the step: its state, force or torque (set since the last step) was not finite
  Solver,  // the step itself produced it (overflow in the solver)
  // Its centre of mass is beyond kWorldRange: put there by setBodyState, or carried there by
  // the step (a body flung out, or a solve that diverged to huge but finite coordinates).
  OutOfRange,
};

struct BodyFault {
  BodyId body;
  BodyFaultCause cause = BodyFaultCause::Input;
  double time = 0.0;  // sim time at the start of the step that found it
};

class World {
 public:
  // Throws std::invalid_argument with worldDefError's message for settings it cannot use.
  explicit World(const WorldDef& def = WorldDef());
  ~World();
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  // --- building -------------------------------------------------------------------------
  // Throws std::invalid_argument, creating nothing, for a non-finite pose, velocity, centre of
  // mass or gravity_scale, a centre of mass beyond kWorldRange, a negative or non-finite
  // damping, or a dynamic body without a positive mass and a positive definite inertia.
  BodyId createBody(const BodyDef& def);
  // Throws std::invalid_argument, adding nothing, for a geometry that geometryError refuses, a
  // non-finite local pose, or a material that materialError refuses.
  void addShape(BodyId body, const ShapeDef& def);
  // The joints throw std::invalid_argument, creating nothing, for a def that jointDefError
  // refuses (joint.hpp), naming the two bodies and the field.
  JointId createBallJoint(const BallJointDef& def);
  JointId createHingeJoint(const HingeJointDef& def);
  JointId createFixedJoint(const FixedJointDef& def);
  JointId createPrismaticJoint(const PrismaticJointDef& def);
  // The pair never collides (joints also disable their pair unless collide_connected).
  void disableCollision(BodyId a, BodyId b);

  // --- removing --------------------------------------------------------------------------
  // Nothing is rebuilt: every other id keeps its index, other islands keep their warm starts
  // and their sleep. A destroyed id's slot is not reused (later creates append), so a stale id
  // is refused like any bad id (std::out_of_range, isValid false) instead of naming another.
  // The body with its shapes, the joints on it and its contacts; the bodies it touched or was
  // joined to wake.
  void destroyBody(BodyId body);
  // The joint; its pair collides again (as after breakJoint) and its bodies wake.
  void destroyJoint(JointId joint);
  // Shape `index` of bodyShapes(body) with its contacts; the body's later shapes move down by
  // one. The body and what it touched wake.
  void removeShape(BodyId body, int index);
  // Gives shape `index` of bodyShapes(body) a new material; its kept contacts take the new
  // coefficients before the next step (no body wakes). Throws std::invalid_argument for a
  // material that materialError refuses, std::out_of_range for a bad body or index.
  void setShapeMaterial(BodyId body, int index, const Material& material);

  // --- stepping -------------------------------------------------------------------------
  // Advances by dt seconds. Forces and torques applied since the last step act during it and
  // are then cleared.
  void step(double dt);
  double time() const;
  const WorldDef& def() const;
  // The width the solver's rows run at, as SolverSettings::lanes chose it on this CPU: 1
  // (double rows), 4 or 8 (float lanes; see lanesAutomatic).
  int laneWidth() const;
  // With the width left to the solver (SolverSettings::lanes 0, RAGDOLL_SIM_LANES unset), a step
  // whose islands hold fewer awake bodies than this solves its rows in double: a lone ragdoll's
  // 15 bodies fill about half of the lanes, and the blocks then cost more than the double rows.
  static constexpr int kLanesMinBodies = 24;
  bool lanesAutomatic() const;
  void setGravity(const Vec3& g);
  // Changes the solver settings on the running world without rebuilding it: warm starts carry
  // over (rescaled to a new substep, solver_context.hpp) and no body wakes. Throws
  // std::invalid_argument with solverSettingsError's message, changing nothing, for settings
  // out of range.
  void setSolverSettings(const SolverSettings& solver);
  // Times the phases of each step from now on (off: the profile stays zero; on, ten clock
  // reads cost ~0.2 µs per step). Profiling changes no result.
  void setProfiling(bool on);
  const StepProfile& stepProfile() const;  // of the last step
  // Replaces the material table: contacts made from now on take the new coefficients, and every
  // kept contact is given them before the next step (no body wakes). Throws
  // std::invalid_argument with MaterialTable::error()'s message, changing nothing.
  void setMaterials(const MaterialTable& materials);
  // WorldDef::sleep changed while the world runs: nothing is rebuilt and no body wakes,
  // except that turning sleep off wakes every sleeping body (it would never wake by itself).
  // Turning it on restarts every body's slow time, so an island sleeps `time` after that at the
  // earliest and takes the rest substeps rest_time after it. New rest settings apply from the
  // next step (warm starts are rescaled to a new substep, solver_context.hpp). Throws
  // std::invalid_argument with sleepDefError's message, changing nothing, for settings out of
  // range.
  void setSleep(const SleepDef& sleep);
  // Bodies reset since the last call, oldest first (at most kMaxPendingFaults are kept between
  // calls; bodyFaultCount() counts them all).
  std::vector<BodyFault> takeBodyFaults();
  int64_t bodyFaultCount() const;
  static constexpr size_t kMaxPendingFaults = 256;

  // --- commands (world frame) ------------------------------------------------------------
  void applyLinearImpulse(BodyId body, const Vec3& impulse, const Vec3& world_point);
  void applyLinearImpulseToCenter(BodyId body, const Vec3& impulse);
  void applyAngularImpulse(BodyId body, const Vec3& impulse);
  void applyForce(BodyId body, const Vec3& force, const Vec3& world_point);
  void applyTorque(BodyId body, const Vec3& torque);
  // A non-finite state, or a centre of mass beyond kWorldRange, is undone by the next step as
  // a BodyFault (Input, OutOfRange).
  void setBodyState(BodyId body, const Transform& pose, const Vec3& com_velocity,
                    const Vec3& angular_velocity);

  // --- queries ---------------------------------------------------------------------------
  // Slots, destroyed ones included: every id is below these; isValid tells the live ones.
  int bodyCount() const;
  int jointCount() const;
  bool isValid(BodyId body) const;
  bool isValid(JointId joint) const;
  BodyState bodyState(BodyId body) const;
  Transform bodyPose(BodyId body) const;  // link frame in world
  const BodyDef& bodyDef(BodyId body) const;
  const std::vector<ShapeDef>& bodyShapes(BodyId body) const;
  Vec3 comPosition(BodyId body) const;
  Vec3 pointVelocity(BodyId body, const Vec3& world_point) const;
  bool isAwake(BodyId body) const;
  void wake(BodyId body);
  int awakeBodyCount() const;
  IslandCounters islandCounters() const;  // of the last step

  JointType jointType(JointId joint) const;
  double hingeAngle(JointId joint) const;
  std::array<double, 3> ballAngles(JointId joint) const;  // Euler angles about the def's axes
  // Ball: {swing, twist} (rad) about the twist axis axes[0], whatever the limit mode.
  std::array<double, 2> ballSwingTwist(JointId joint) const;
  double prismaticPosition(JointId joint) const;  // m along the axis (0 for other types)
  // World anchor B - anchor A (prismatic: its part off the axis).
  Vec3 jointAnchorError(JointId joint) const;
  double jointForce(JointId joint) const;                 // N, in the anchor, last substep
  double jointTorque(JointId joint) const;  // N m, fixed joint's rotation lock, last substep
  bool isJointBroken(JointId joint) const;
  // Joints broken since the last call, in the order they broke (for events).
  std::vector<JointId> takeBrokenJoints();
  // Breaks a joint as if its break force had been passed (its pair collides again), without an
  // event: for restoring a saved state whose joints had broken.
  void breakJoint(JointId joint);
  // Motor of one joint angle (hinge: axis 0; ball: Euler axes 0..2; prismatic: axis 0, linear).
  // Throws std::invalid_argument, changing nothing, for a motor that jointMotorError refuses.
  void setJointMotor(JointId joint, int axis, const JointMotor& motor);

  // How deep the shapes of `bodies` reach into the shapes of static bodies, at their current
  // poses: the deepest pair (for spawn checks; Scene lifts a ragdoll out by it). Against a
  // plane it is exact: the depth of the shape's lowest point below it, along its normal; other
  // pairs take the narrowphase's deepest point and normal. Throws std::out_of_range for an
  // invalid body.
  StaticOverlap staticOverlap(const std::vector<BodyId>& bodies) const;

  Vec3 linearMomentum() const;
  Vec3 angularMomentum(const Vec3& about) const;
  double kineticEnergy() const;
  std::vector<ContactInfo> contacts() const;

  // --- reports of the last step (world_reports.hpp) --------------------------------------
  // The step sums each contact point's normal impulse over its substeps (step_impulse,
  // peak_force) only while this is on: nobody pays for what nobody reads. Off by default.
  void setContactImpulseTracking(bool on);
  bool contactImpulseTracking() const;
  // Touching shape pairs after the last step, into `out` (cleared; its capacity is reused, so
  // a caller that keeps `out` allocates nothing once it is large enough).
  void contactReports(std::vector<ContactReport>& out) const;
  // Throws std::out_of_range for an invalid joint. A broken joint reports zero.
  JointWrench jointWrench(JointId joint) const;
  // Efforts about the joint's axes in the last substep, into out[0..n): hinge 1 (N m about its
  // axis), prismatic 1 (N along its axis), ball 3 (N m about each Euler axis as the chain of
  // revolute joints it stands for has it at the current angles), fixed 0. Each is motor (with
  // its damping) + limit, on B about +axis: the effort of that joint's actuator in the sign
  // robot_state_publisher and ros_control use. Returns n.
  int jointAxisEfforts(JointId joint, double out[3]) const;
  // A tracked body's velocities are kept at the end of every substep (substepVelocities).
  // Throws std::out_of_range for an invalid body.
  void trackBody(BodyId body, bool on);
  // False when `body` is not tracked or no step ran since it was.
  bool substepVelocities(BodyId body, SubstepVelocities* out) const;

 private:
  friend struct WorldInternals;  // src/core: the switches that check an optimisation
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ragdoll_sim
