// Contact points (Drake's convention): a URDF collision sphere of radius 0 (or below 1 mm) is a
// point on its link that touches the ground, not dropped; a model left without any collision
// geometry gets one warning that it will fall through the ground. ragdoll_check lists the points
// and gives its verdict on both.
#include <gtest/gtest.h>

#include <string>

#include "malformed_cases.hpp"
#include "ragdoll_sim/urdf_loader.hpp"

using namespace ragdoll_sim;

namespace {
const std::string kFixtures = std::string(RAGDOLL_SIM_SOURCE_DIR) + "/test/urdf/fixtures/";

int count(const std::string& text, const std::string& word) {
  int n = 0;
  for (size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) ++n;
  return n;
}

int fallWarnings(const RagdollDef& d) {
  int n = 0;
  for (const std::string& w : d.warnings) n += w.find("fall through the ground") != std::string::npos;
  return n;
}
}  // namespace

TEST(PointContacts, RadiusZeroSpheresAreShapes) {
  const UrdfLoadResult r = loadUrdfFile(kFixtures + "point_contact_box.urdf");
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.def.links.size(), 1u);
  const LinkDef& box = r.def.links[0];
  ASSERT_EQ(box.shapes.size(), 4u);  // radius 0 three times, 0.4 mm once
  for (size_t k = 0; k < box.shapes.size(); ++k) {
    EXPECT_EQ(box.shapes[k].geometry.type, ShapeType::Sphere);
    EXPECT_EQ(box.shapes[k].geometry.radius, 0.0);
    EXPECT_EQ(box.shape_sources[k].rfind("point", 0), 0u) << box.shape_sources[k];
  }
  EXPECT_NEAR(box.mass, 6.0, 1e-12);  // the points add no mass
  EXPECT_TRUE(r.def.warnings.empty()) << r.def.warnings[0];
}

TEST(PointContacts, BoxRestsOnItsCornerPoints) {
  const UrdfLoadResult r = loadUrdfFile(kFixtures + "point_contact_box.urdf");
  ASSERT_TRUE(r.ok) << r.error;
  World world{WorldDef()};
  BodyDef gd;
  gd.type = BodyType::Static;
  world.addShape(world.createBody(gd), {Geometry::plane(Vec3::UnitZ(), 0.0), Transform(), Material()});
  // Corners 5 cm up, tilted a little so that one corner lands first.
  const Quat tilt(Eigen::AngleAxisd(0.05, Vec3(1, 2, 0).normalized()));
  const Ragdoll rd = spawnRagdoll(world, r.def, Transform(Vec3(0, 0, 0.17), tilt));
  for (int s = 0; s < 1000; ++s) world.step(1e-3);
  const Transform pose = world.bodyPose(rd.bodies[0]);
  for (const ShapeDef& s : r.def.links[0].shapes)
    EXPECT_NEAR((pose * s.local).p.z(), 0.0, 1e-3) << s.local.p.transpose();
  EXPECT_LT(world.bodyState(rd.bodies[0]).linear_velocity.norm(), 1e-2);
}

TEST(PointContacts, NoCollisionGeometryWarnsOnce) {
  const UrdfLoadResult none = loadUrdfFile(kFixtures + "no_collision.urdf");
  ASSERT_TRUE(none.ok) << none.error;
  EXPECT_EQ(fallWarnings(none.def), 1);
  EXPECT_EQ(none.def.warnings.size(), 1u);
  const UrdfLoadResult points = loadUrdfFile(kFixtures + "point_contact_box.urdf");
  ASSERT_TRUE(points.ok) << points.error;
  EXPECT_EQ(fallWarnings(points.def), 0);
  // A zero-size box is still ignored (with its own warning), and then nothing is left.
  const UrdfLoadResult flat = loadUrdfString(
      "<robot name='r'><link name='a'><inertial><mass value='1'/><inertia ixx='0.01' ixy='0' ixz='0' "
      "iyy='0.01' iyz='0' izz='0.01'/></inertial><collision><geometry><box size='0 0.1 0.1'/></geometry>"
      "</collision></link></robot>");
  ASSERT_TRUE(flat.ok) << flat.error;
  EXPECT_EQ(fallWarnings(flat.def), 1);
  EXPECT_EQ(flat.def.warnings.size(), 2u);
}

TEST(PointContacts, RagdollCheckListsPointsAndJudgesTheDrop) {
  std::string out;
  int rc = malformed::run(std::string(RAGDOLL_CHECK_BIN) + " " + kFixtures + "point_contact_box.urdf", &out);
  EXPECT_EQ(rc, 0) << out;
  EXPECT_EQ(count(out, "\n      point "), 4) << out;  // one shape line each
  EXPECT_NE(out.find("shapes=4 points=4"), std::string::npos) << out;
  EXPECT_NE(out.find("verdict=pass"), std::string::npos) << out;
  EXPECT_EQ(out.find("reason:"), std::string::npos) << out;

  rc = malformed::run(std::string(RAGDOLL_CHECK_BIN) + " " + kFixtures + "no_collision.urdf --seconds 0.5", &out);
  EXPECT_EQ(rc, 3) << out;
  EXPECT_NE(out.find("will fall through the ground"), std::string::npos) << out;
  EXPECT_NE(out.find("reason: fell through the ground"), std::string::npos) << out;
  EXPECT_NE(out.find("verdict=fail"), std::string::npos) << out;
  EXPECT_NE(out.find("status=ok"), std::string::npos) << out;  // loaded: the drop failed
}
