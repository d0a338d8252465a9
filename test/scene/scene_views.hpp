// A small scene for the node's display / interaction tests: a ground plane and two ragdolls of
// a 2-link model (pelvis: box, torso: capsule above it, hinge between), side by side in y.
#pragma once

#include <memory>
#include <vector>

#include "ragdoll_sim/ragdoll.hpp"
#include "ragdoll_view.hpp"

namespace ragdoll_sim {
namespace test {

inline RagdollDef stickModel() {
  RagdollDef def;
  def.name = "stick";
  LinkDef pelvis;
  pelvis.name = "pelvis";
  pelvis.mass = 10.0;
  pelvis.inertia = Mat3::Identity() * 0.1;
  pelvis.shapes.push_back({Geometry::box(Vec3(0.15, 0.1, 0.1)), Transform(), Material()});
  LinkDef torso;
  torso.name = "torso";
  torso.mass = 20.0;
  torso.com = Vec3(0, 0, 0.3);
  torso.inertia = Mat3::Identity() * 0.3;
  torso.shapes.push_back(
      {Geometry::capsule(0.12, 0.15), Transform(Vec3(0, 0, 0.3), Quat::Identity()), Material()});
  torso.rest_pose = Transform(Vec3(0, 0, 0.1), Quat::Identity());
  def.links = {pelvis, torso};
  RagdollJointDef hinge;
  hinge.name = "waist";
  hinge.kind = RagdollJointKind::Hinge;
  hinge.parent = 0;
  hinge.child = 1;
  hinge.frame_parent = Transform(Vec3(0, 0, 0.1), Quat::Identity());
  hinge.axes = {Vec3::UnitY()};
  def.joints = {hinge};
  return def;
}

struct TwoRagdolls {
  RagdollDef def = stickModel();
  World world;
  BodyId ground;
  Ragdoll a, b;

  // Pelvis origins at (0, 0, z) and (0, 2, z); gravity off unless `gravity`.
  explicit TwoRagdolls(double z = 1.0, bool gravity = false)
      : world([&] {
          WorldDef wd;
          if (!gravity) wd.gravity = Vec3::Zero();
          return wd;
        }()) {
    BodyDef gd;
    gd.type = BodyType::Static;
    ground = world.createBody(gd);
    world.addShape(ground, {Geometry::plane(Vec3::UnitZ(), 0.0), Transform(), Material()});
    a = spawnRagdoll(world, def, Transform(Vec3(0, 0, z), Quat::Identity()));
    b = spawnRagdoll(world, def, Transform(Vec3(0, 2, z), Quat::Identity()));
  }

  std::vector<scene::RagdollView> views() const {
    return {{"first", "", &def, &a}, {"second", "b/", &def, &b}};
  }
};

}  // namespace test
}  // namespace ragdoll_sim
