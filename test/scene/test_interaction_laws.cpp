// Unit tests of the ROS-free laws behind poking and dragging from rviz
// (src/scene/interaction_laws.*) and of the rviz settings checks (src/scene/rviz_settings.*).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "interaction_laws.hpp"
#include "scene_views.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::scene;

namespace {

ShapeDef shape(const Geometry& g, const Transform& local = Transform()) {
  return {g, local, Material()};
}

const Transform kPose(Vec3(1, 2, 3), quatFromRpy(0.3, -0.2, 0.7));

// The world point of `local` (in the shape frame) for a shape at kPose * shape.local.
Vec3 at(const ShapeDef& s, const Vec3& local) { return (kPose * s.local).apply(local); }

}  // namespace

TEST(ShapeDistance, SphereCapsuleBoxCylinderSigned) {
  const ShapeDef sphere = shape(Geometry::sphere(0.2), Transform(Vec3(0.1, 0, 0), Quat::Identity()));
  EXPECT_NEAR(shapeDistance(sphere, kPose, at(sphere, Vec3(0, 0.5, 0))), 0.3, 1e-12);
  EXPECT_NEAR(shapeDistance(sphere, kPose, at(sphere, Vec3::Zero())), -0.2, 1e-12);

  const ShapeDef capsule = shape(Geometry::capsule(0.1, 0.3));
  EXPECT_NEAR(shapeDistance(capsule, kPose, at(capsule, Vec3(0.5, 0, 0.2))), 0.4, 1e-12);  // side
  EXPECT_NEAR(shapeDistance(capsule, kPose, at(capsule, Vec3(0, 0, 0.7))), 0.3, 1e-12);    // end
  EXPECT_NEAR(shapeDistance(capsule, kPose, at(capsule, Vec3(0, 0.05, 0))), -0.05, 1e-12);

  const ShapeDef box = shape(Geometry::box(Vec3(0.1, 0.2, 0.3)));
  EXPECT_NEAR(shapeDistance(box, kPose, at(box, Vec3(0.5, 0, 0))), 0.4, 1e-12);            // face
  EXPECT_NEAR(shapeDistance(box, kPose, at(box, Vec3(0.4, 0.6, 0))), 0.5, 1e-12);          // edge
  EXPECT_NEAR(shapeDistance(box, kPose, at(box, Vec3(0, 0.15, 0))), -0.05, 1e-12);         // inside

  const ShapeDef cylinder = shape(Geometry::cylinder(0.1, 0.2));
  EXPECT_NEAR(shapeDistance(cylinder, kPose, at(cylinder, Vec3(0, 0.4, 0.1))), 0.3, 1e-12);
  EXPECT_NEAR(shapeDistance(cylinder, kPose, at(cylinder, Vec3(0.05, 0, 0.5))), 0.3, 1e-12);
  EXPECT_NEAR(shapeDistance(cylinder, kPose, at(cylinder, Vec3(0.4, 0, 0.6))), 0.5, 1e-12);  // rim
  EXPECT_NEAR(shapeDistance(cylinder, kPose, at(cylinder, Vec3(0, 0, 0.15))), -0.05, 1e-12);
}

TEST(ShapeDistance, HullFacesAndPlaneNeverPicked) {
  std::vector<Vec3> cube;
  for (int i = 0; i < 8; ++i) cube.emplace_back(i & 1 ? 0.1 : -0.1, i & 2 ? 0.1 : -0.1, i & 4 ? 0.1 : -0.1);
  const ShapeDef hull = shape(Geometry::convexHull(cube));
  ASSERT_TRUE(hull.geometry.hull);
  EXPECT_NEAR(shapeDistance(hull, kPose, at(hull, Vec3(0, 0, 0.35))), 0.25, 1e-9);
  EXPECT_NEAR(shapeDistance(hull, kPose, at(hull, Vec3(0, 0.02, 0))), -0.08, 1e-9);
  const ShapeDef plane = shape(Geometry::plane(Vec3::UnitZ(), 0.0));
  EXPECT_TRUE(std::isinf(shapeDistance(plane, kPose, kPose.p)));
}

TEST(PickNearestLink, NearestLinkOfAnyRagdollWithinTheCap) {
  test::TwoRagdolls scene(1.0);
  const auto views = scene.views();
  // Just outside the second ragdoll's torso capsule (axis at (0, 2), z 1.1 + 0.15 .. 0.45).
  LinkPick p = pickNearestLink(scene.world, views, Vec3(0.15, 2.0, 1.4), 0.3);
  ASSERT_TRUE(p.valid());
  EXPECT_EQ(p.ragdoll, 1);
  EXPECT_EQ(scene.def.links[static_cast<size_t>(p.link)].name, "torso");
  EXPECT_NEAR(p.distance, 0.03, 1e-9);
  // Inside the first ragdoll's pelvis box.
  p = pickNearestLink(scene.world, views, Vec3(0.05, 0.0, 1.0), 0.3);
  ASSERT_TRUE(p.valid());
  EXPECT_EQ(p.ragdoll, 0);
  EXPECT_EQ(scene.def.links[static_cast<size_t>(p.link)].name, "pelvis");
  EXPECT_LT(p.distance, 0.0);
  // Far from both: refused, but the distance is reported; the ground is never picked.
  p = pickNearestLink(scene.world, views, Vec3(0, 1.0, 0.01), 0.3);
  EXPECT_FALSE(p.valid());
  EXPECT_GT(p.distance, 0.3);
  EXPECT_LT(p.distance, 1.5);
  // The picked link follows the body: move ragdoll 0's pelvis, the old point misses it.
  scene.world.setBodyState(scene.a.bodies[0], Transform(Vec3(5, 0, 1), Quat::Identity()),
                           Vec3::Zero(), Vec3::Zero());
  p = pickNearestLink(scene.world, views, Vec3(5.0, 0.0, 0.85), 0.1);
  ASSERT_TRUE(p.valid());
  EXPECT_EQ(p.ragdoll, 0);
  EXPECT_EQ(p.link, 0);
}

TEST(PokeImpulse, TowardsTheCentreOfMassWithTheGivenSize) {
  const Vec3 j = pokeImpulse(Vec3(1, 0, 0), Vec3(1, 0, 2), 7.0);
  EXPECT_NEAR((j - Vec3(0, 0, 7)).norm(), 0.0, 1e-12);
  const Vec3 k = pokeImpulse(Vec3(0, 0, 0), Vec3(3, 4, 0), 10.0);
  EXPECT_NEAR((k - Vec3(6, 8, 0)).norm(), 0.0, 1e-12);
  EXPECT_EQ(pokeImpulse(Vec3(1, 1, 1), Vec3(1, 1, 1), 5.0), Vec3::Zero());
}

TEST(DragForce, SpringDamperCappedByBothLimits) {
  DragSettings s;
  s.stiffness = 100.0;
  s.damping = 10.0;
  s.max_force = 1000.0;
  // Spring only, then with damping against the motion.
  EXPECT_NEAR((dragForce(Vec3(0, 0, 1), Vec3::Zero(), Vec3(0, 0, 1.5), s, 1e5) - Vec3(0, 0, 50)).norm(),
              0.0, 1e-12);
  EXPECT_NEAR((dragForce(Vec3(0, 0, 1), Vec3(1, 0, 0), Vec3(0, 0, 1.5), s, 1e5) - Vec3(-10, 0, 50)).norm(),
              0.0, 1e-12);
  // 100 m away: capped at drag max_force, then at the node's max_force, direction kept.
  Vec3 f = dragForce(Vec3::Zero(), Vec3::Zero(), Vec3(100, 0, 0), s, 1e5);
  EXPECT_NEAR((f - Vec3(1000, 0, 0)).norm(), 0.0, 1e-9);
  f = dragForce(Vec3::Zero(), Vec3::Zero(), Vec3(0, 100, 0), s, 250.0);
  EXPECT_NEAR((f - Vec3(0, 250, 0)).norm(), 0.0, 1e-9);
  // At the target and at rest: nothing.
  EXPECT_EQ(dragForce(Vec3(1, 2, 3), Vec3::Zero(), Vec3(1, 2, 3), s, 1e5), Vec3::Zero());
}

TEST(DragLink, NamedTorsoOrRoot) {
  RagdollDef def = test::stickModel();
  EXPECT_EQ(dragLink(def, ""), 1);        // torso
  EXPECT_EQ(dragLink(def, "pelvis"), 0);
  EXPECT_EQ(dragLink(def, "no_such_link"), -1);
  def.links[1].name = "chest";
  EXPECT_EQ(dragLink(def, ""), def.root);  // no torso: the root link
}

TEST(RvizSettings, RangeChecksNameTheParameter) {
  EXPECT_EQ(validateMarkerSettings(MarkerSettings()), "");
  EXPECT_EQ(validatePokeSettings(PokeSettings()), "");
  EXPECT_EQ(validateDragSettings(DragSettings()), "");
  MarkerSettings m;
  m.arrow_fade = -1.0;
  EXPECT_NE(validateMarkerSettings(m).find("~markers/arrow_fade"), std::string::npos);
  m = MarkerSettings();
  m.max_arrows = 0;
  EXPECT_NE(validateMarkerSettings(m).find("~markers/max_arrows"), std::string::npos);
  m = MarkerSettings();
  m.impact_flash = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(validateMarkerSettings(m).find("~markers/impact_flash"), std::string::npos);
  m.impact_flash = 0.0;  // no flashes
  EXPECT_EQ(validateMarkerSettings(m), "");
  PokeSettings p;
  p.impulse = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(validatePokeSettings(p).find("~poke/impulse"), std::string::npos);
  p = PokeSettings();
  p.max_distance = 0.0;
  EXPECT_NE(validatePokeSettings(p).find("~poke/max_distance"), std::string::npos);
  DragSettings d;
  d.max_force = std::numeric_limits<double>::infinity();
  EXPECT_NE(validateDragSettings(d).find("~drag/max_force"), std::string::npos);
  d = DragSettings();
  d.stiffness = -1.0;
  EXPECT_NE(validateDragSettings(d).find("~drag/stiffness"), std::string::npos);
}
