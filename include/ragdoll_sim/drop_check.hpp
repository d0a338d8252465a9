// Drop test of a RagdollDef (ROS-free): spawn it just above a ground plane, let it fall and
// measure how well the solver holds it together. Used by ragdoll_check and the URDF zoo test;
// measureDrop takes the measurements in a World that someone else builds and steps (a Scene with
// a world file: ragdoll_check --world).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "ragdoll_sim/ragdoll.hpp"

namespace ragdoll_sim {

struct DropSettings {
  double seconds = 3.0;      // sim time
  double dt = 1e-3;          // s, physics step (the node's default rate)
  int substeps = SolverSettings().substeps;  // the node's default
  double clearance = 0.05;   // m between the lowest shape point and the ground at spawn
};

struct DropReport {
  bool finite = true;            // every body state stayed finite (no NaN / inf)
  double spawn_z = 0;            // m, root link height at spawn (rest pose, upright)
  double spawn_top_z = 0;        // m, highest body centre of mass at spawn (measureDrop sets it)
  double max_penetration = 0;    // m, deepest contact of the ragdoll (ground, obstacle or self) over the run
  double max_anchor_error = 0;   // m, largest joint anchor separation over the run
  double rest_height = 0;        // m, root link origin z at the end
  // Lowest shape point, counting a link without shapes by its centre of mass, m:
  double lowest_point = 0;       // at the end
  double min_lowest_point = 0;   // over the run
  double final_speed = 0;        // m/s, fastest body (COM speed + angular speed x 0.1 m) at the end
  // As final_speed, over the bodies that touch something at the end (a contact within 1 mm):
  // a limb left hanging in the air swings on without joint damping, a body lying on the
  // ground or on another limb must be still.
  double final_contact_speed = 0;
  // J, mechanical energy (kinetic + gravity) at the end minus that 2 s before (half the run
  // when shorter): a solver that pumps energy into resting contacts makes it positive.
  double late_energy_change = 0;
  double seconds = 0;            // sim time actually run (less when a state went non-finite)
  double max_speed = 0;          // m/s, fastest body COM speed over the run
  double final_anchor_error = 0; // m, largest joint anchor separation at the end
};

// Whether a drop held together, and for each rule it broke one reason naming the rule and the
// numbers ("joints stretched: anchor error 11.4 mm > 5 mm").
struct DropVerdict {
  bool pass = true;
  std::vector<std::string> reasons;
};

struct VerdictRules {
  double max_sink = 0.05;          // m a shape may reach below the ground before it fell through
  double max_anchor_error = 0.005; // m of joint anchor separation over the run
  double speed_margin = 1.0;       // m/s a body may exceed the free-fall speed from the spawn height
  double rest_speed = 0.1;         // m/s of the bodies that touch something at the end
  bool expect_rest = true;         // false: a run too short to settle is not asked to be still
  double ground_z = 0.0;           // m, the lowest surface the model may land on
};

// The verdict on a drop: fell through (min_lowest_point below ground_z - max_sink), joints
// stretched, exploded (max_speed above sqrt(2 g h) + speed_margin, h the height of the higher of
// spawn_z and spawn_top_z above ground_z: no body gets faster falling than from there), NaN,
// not at rest (expect_rest and final_contact_speed above rest_speed).
DropVerdict judgeDrop(const DropReport& d, const VerdictRules& rules = VerdictRules());

// The rules for a drop run with `settings` onto a ground at `ground_z`: rest is asked of a run
// long enough to settle (2 s of sim time), not of a shorter one.
VerdictRules dropRules(const DropSettings& settings, double ground_z = 0.0);

// Lowest world z of a shape (planes: +inf) whose body frame is at `body_pose`.
double lowestPoint(const ShapeDef& shape, const Transform& body_pose);
// Highest world z of a shape (planes: -inf).
double highestPoint(const ShapeDef& shape, const Transform& body_pose);
// Lowest z of the model's shapes in its rest pose with the root link at the origin (a model
// without shapes: of its link centres of mass).
double restLowestPoint(const RagdollDef& def);

// The world dropTest drops in: a ground plane at z = 0 and the model spawned upright with its
// lowest shape point settings.clearance above it.
struct DropWorld {
  explicit DropWorld(const RagdollDef& def, const DropSettings& settings = DropSettings());
  World world;
  Ragdoll ragdoll;
  double spawn_z = 0;  // m, the root link's height at spawn
};

DropReport dropTest(const RagdollDef& def, const DropSettings& settings = DropSettings());

// The metrics of ragdoll `r` (spawned from `def`) in `world` while `step` advances the world by
// settings.dt, for settings.seconds of sim time or until a body state of the ragdoll goes
// non-finite. Only the ragdoll's bodies and contacts count (other objects may share the world);
// spawn_z is left to the caller.
DropReport measureDrop(const World& world, const Ragdoll& r, const RagdollDef& def,
                       const std::function<void()>& step, const DropSettings& settings);

}  // namespace ragdoll_sim
