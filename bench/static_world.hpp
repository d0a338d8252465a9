// static_world.hpp -- the static box world of bench scenes w and v (bench_ragdoll):
// kSide x kSide static 0.5 m cubes resting on the ground plane on a grid of kPitch, centred on
// the origin, so that the ragdoll dropped at the origin lands on the plane between four of them.
//   w: each box its own static body (a world file of many static models);
//   v: all of them shapes of one static body (one static model with many collisions).
#pragma once

#include "ragdoll_sim/world.hpp"

namespace static_world {

constexpr int kSide = 100;           // boxes per row: kSide^2 = 10 000
constexpr double kPitch = 2.0;       // m between box centres
constexpr double kHalf = 0.25;       // m, half the box side

// Adds the boxes to world: as kSide^2 static bodies, or as one static body with kSide^2 shapes.
inline void addBoxes(ragdoll_sim::World& world, bool one_body, const ragdoll_sim::Material& mat) {
  using namespace ragdoll_sim;
  const auto centre = [](int i, int j) {
    return Vec3((i - 0.5 * (kSide - 1)) * kPitch, (j - 0.5 * (kSide - 1)) * kPitch, kHalf);
  };
  const Geometry box = Geometry::box(Vec3::Constant(kHalf));
  BodyDef def;
  def.type = BodyType::Static;
  if (one_body) {
    const BodyId b = world.createBody(def);
    for (int i = 0; i < kSide; ++i)
      for (int j = 0; j < kSide; ++j) {
        Transform local;
        local.p = centre(i, j);
        world.addShape(b, {box, local, mat});
      }
    return;
  }
  for (int i = 0; i < kSide; ++i)
    for (int j = 0; j < kSide; ++j) {
      def.pose.p = centre(i, j);
      world.addShape(world.createBody(def), {box, Transform(), mat});
    }
}

}  // namespace static_world
