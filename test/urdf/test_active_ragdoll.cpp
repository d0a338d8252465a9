// Active ragdoll: joint motors holding the standing pose keep the bundled ragdoll upright
// under gravity, and it recovers from a 20 N s shove to the torso without falling.
#include <gtest/gtest.h>

#include <cmath>

#include "ragdoll_sim/balance.hpp"
#include "ragdoll_sim/urdf_loader.hpp"

using namespace ragdoll_sim;

TEST(ActiveRagdoll, StandsAndRecoversFromShove) {
  const UrdfLoadResult r = loadUrdfFile(std::string(RAGDOLL_SIM_SOURCE_DIR) + "/urdf/ragdoll.urdf");
  ASSERT_TRUE(r.ok) << r.error;
  World w;
  BodyDef g;
  g.type = BodyType::Static;
  w.addShape(w.createBody(g), {Geometry::plane(Vec3::UnitZ(), 0.0), Transform(), Material()});
  const Ragdoll rd = spawnRagdoll(w, r.def, Transform(Vec3(0, 0, 1.0005), Quat::Identity()));
  BalanceController balance(w, rd, r.def);
  ASSERT_TRUE(balance.missing().empty());
  const BodyId pelvis = rd.bodies[r.def.findLink("pelvis")], torso = rd.bodies[r.def.findLink("torso")];
  double min_z = 10.0;
  for (int i = 0; i < 2000; ++i) {
    balance.update(w);
    w.step(1e-3);
    min_z = std::min(min_z, w.bodyPose(pelvis).p.z());
  }
  EXPECT_GT(min_z, 0.95) << "did not stand";
  w.applyLinearImpulse(torso, Vec3(20.0, 0, 0), w.comPosition(torso));
  double min_after = 10.0, max_tilt = 0.0;
  for (int i = 0; i < 4000; ++i) {
    balance.update(w);
    w.step(1e-3);
    const Transform p = w.bodyPose(pelvis);
    min_after = std::min(min_after, p.p.z());
    max_tilt = std::max(max_tilt, std::acos(std::clamp((p.q * Vec3::UnitZ()).z(), -1.0, 1.0)));
  }
  EXPECT_GT(min_after, 0.9) << "fell";
  EXPECT_LT(std::acos(std::clamp((w.bodyPose(pelvis).q * Vec3::UnitZ()).z(), -1.0, 1.0)), 0.05);
  std::printf("[ active   ] standing pelvis min z %.3f; after 20 N s shove: min z %.3f, max tilt %.3f rad\n",
              min_z, min_after, max_tilt);
}
