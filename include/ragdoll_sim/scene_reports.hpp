// What the Scene reports about its last step, by name: contacts between links and objects,
// the loads on each link and joint, impact events and joint effort commands. Scene (scene.hpp)
// fills them; the node publishes them as ~contacts, ~link_loads, ~impacts, joint_states.effort.
#pragma once

#include <string>
#include <vector>

#include "ragdoll_sim/math.hpp"
#include "ragdoll_sim/world_reports.hpp"

namespace ragdoll_sim {

// A body as users name it: link `link` of ragdoll (or dynamic object) `ragdoll`, link `link`
// of static object `static_object`, or the default ground (all three -1).
struct BodyRef {
  int ragdoll = -1;        // Scene index
  int static_object = -1;  // Scene::staticObject* index
  int link = -1;           // RagdollDef::links index
};

// One touching shape pair, its bodies named (Scene::bodyName: "ragdoll/link", "object/link",
// "ground").
struct SceneContact {
  BodyRef a, b;
  ContactReport report;  // a is report.body_a
};

// The loads on one link in the last step: the sum of its contacts' wrenches (world axes,
// torque about its centre of mass).
struct LinkLoad {
  Vec3 contact_force = Vec3::Zero();   // N
  Vec3 contact_torque = Vec3::Zero();  // N m
};

// What one RagdollDef joint holds: JointWrench on the child link (the parent takes the
// opposite), and its axis efforts in joint_states order (motor + limit + commanded effort).
struct JointLoad {
  JointWrench wrench;
  int axes = 0;
  double effort[3] = {0.0, 0.0, 0.0};  // N m or N
};

// Impact events (Scene::impacts): a link's contact with one other body in one step whose
// normal impulse reaches min_impulse or whose closing speed reaches min_speed. Off unless
// enabled (it turns on World::setContactImpulseTracking).
struct ImpactDef {
  bool enabled = false;
  double min_impulse = 2.0;  // N s
  double min_speed = 1.0;    // m/s
};

struct ImpactEvent {
  std::string ragdoll, link;  // the ragdoll's (or dynamic object's) link that was hit
  std::string other;          // Scene::bodyName of the other body
  double time = 0.0;          // s of sim time at the end of the step
  Vec3 point = Vec3::Zero();  // world: the impulse-weighted mean of the pair's points
  Vec3 normal = Vec3::UnitZ();  // world, unit, from the other body into the link
  // The design document's equations: v_c = -(v_a - v_b).n before, v_s' after (for a
  // restitution e, v_s' = -e v_s of the approach).
  double closing_speed = 0.0;     // m/s, the largest of the pair's points
  double separating_speed = 0.0;  // m/s
  double impulse = 0.0;           // N s, summed over the pair's points and the step
  double peak_force = 0.0;        // N, the largest substep normal force of the pair
};

// Torques (forces for a prismatic joint) about joint axes by joint_states name, applied equal
// and opposite to the joint's two links every step for `duration`. The caps of
// CommandLimits::max_torque (max_force for a prismatic axis) hold; a later command for an
// axis replaces its effort.
struct JointEffortCommand {
  std::vector<std::string> names;
  std::vector<double> efforts;
  double duration = -1.0;  // s of sim time; < 0: until replaced or cleared; 0: one step
};

}  // namespace ragdoll_sim
