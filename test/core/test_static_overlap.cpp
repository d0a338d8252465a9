// World::staticOverlap: how deep bodies reach into static shapes (the Scene's spawn check).
// Against a plane it is exact (the lowest point of the shape, along the normal), also when the
// shape is far below it; against a static box it is the narrowphase's deepest point and normal.
#include <gtest/gtest.h>

#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

TEST(StaticOverlap, PlaneIsExactAtAnyDepth) {
  World w;
  const BodyId ground = addGround(w);
  const BodyId ball = addSphere(w, 0.1, 1.0, Vec3(0, 0, 0.5));
  const BodyId box = addBox(w, Vec3(0.2, 0.1, 0.05), 1.0, Vec3(1, 0, 0.5));
  EXPECT_EQ(w.staticOverlap({ball, box}).depth, 0.0) << "both above the ground";
  w.setBodyState(ball, Transform(Vec3(0, 0, -50), Quat::Identity()), Vec3::Zero(), Vec3::Zero());
  w.setBodyState(box, Transform(Vec3(1, 0, 0.02), quatFromRpy(0.0, M_PI / 2, 0.0)), Vec3::Zero(),
                 Vec3::Zero());
  StaticOverlap o = w.staticOverlap({box});
  EXPECT_NEAR(o.depth, 0.18, 1e-9) << "an upright box's lowest corner (2^-32 m position grid)";
  EXPECT_EQ(o.body, box);
  EXPECT_EQ(o.static_body, ground);
  EXPECT_EQ(o.shape, 0);
  EXPECT_NEAR((o.direction - Vec3::UnitZ()).norm(), 0.0, 1e-12);
  o = w.staticOverlap({ball, box});
  EXPECT_NEAR(o.depth, 50.1, 1e-9) << "the deepest of the two";
  EXPECT_EQ(o.body, ball);
  EXPECT_THROW(w.staticOverlap({BodyId{99}}), std::out_of_range);
}

TEST(StaticOverlap, StaticBoxGivesDepthAndDirectionOut) {
  World w;
  const BodyId floor = addStatic(w, Transform(Vec3(0, 0, -0.5), Quat::Identity()));
  w.addShape(floor, {Geometry::box(Vec3(2, 2, 0.5)), Transform(), Material()});
  const BodyId ball = addSphere(w, 0.1, 1.0, Vec3(0.3, 0.2, 0.05));  // 5 cm into its top
  const StaticOverlap o = w.staticOverlap({ball});
  EXPECT_NEAR(o.depth, 0.05, 1e-9);
  EXPECT_NEAR((o.direction - Vec3::UnitZ()).norm(), 0.0, 1e-9);
  EXPECT_EQ(o.static_body, floor);
}
