// Small object models and scenes shared by the Scene's object and fixed-base tests.
#pragma once

#include <string>

#include "ragdoll_sim/scene.hpp"
#include "ragdoll_sim/urdf_loader.hpp"

namespace ragdoll_sim {
namespace test {

inline Mat3 solidBoxInertia(const Vec3& half, double mass) {
  const Vec3 s = 2.0 * half;
  return (mass / 12.0 * Vec3(s.y() * s.y() + s.z() * s.z(), s.x() * s.x() + s.z() * s.z(),
                             s.x() * s.x() + s.y() * s.y()))
      .asDiagonal();
}

// One link holding one box.
inline RagdollDef boxModel(const Vec3& half, double mass) {
  RagdollDef def;
  def.name = "box";
  LinkDef link;
  link.name = "body";
  link.mass = mass;
  link.inertia = solidBoxInertia(half, mass);
  link.shapes.push_back({Geometry::box(half), Transform(), Material()});
  def.links.push_back(link);
  return def;
}

inline SpawnDef boxObject(const std::string& name, const Vec3& half, double mass, const Vec3& at,
                          bool is_static = false) {
  SpawnDef s;
  s.name = name;
  s.def = boxModel(half, mass);
  s.pose = Transform(at, Quat::Identity());
  s.is_static = is_static;
  return s;
}

inline RagdollDef bundledRagdoll() {
  const UrdfLoadResult r = loadUrdfFile(std::string(RAGDOLL_SIM_SOURCE_DIR) + "/urdf/ragdoll.urdf");
  EXPECT_TRUE(r.ok) << r.error;
  return r.def;
}

// Largest linear speed of the centres of mass of `bodies`.
inline double maxSpeed(const World& w, const std::vector<BodyId>& bodies) {
  double v = 0.0;
  for (BodyId b : bodies) v = std::max(v, w.bodyState(b).linear_velocity.norm());
  return v;
}

}  // namespace test
}  // namespace ragdoll_sim
