// Active ragdoll: joint motors holding the standing pose keep the bundled ragdoll upright
// under gravity, and it recovers from a 20 N s shove to the torso without falling.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "ragdoll_sim/balance.hpp"
#include "ragdoll_sim/urdf_loader.hpp"

using namespace ragdoll_sim;

namespace {

struct ShoveResult {
  double min_z, min_after, max_tilt, final_tilt;
};

double tilt(const Transform& p) {
  return std::acos(std::clamp((p.q * Vec3::UnitZ()).z(), -1.0, 1.0));
}

// Stands the bundled ragdoll for 2 s, shoves the torso with 20 N s, runs 4 s more. With
// `ankle_torque` > 0 the ankles get their own motor gains capped at that torque.
UrdfLoadResult bundled() {
  return loadUrdfFile(std::string(RAGDOLL_SIM_SOURCE_DIR) + "/urdf/ragdoll.urdf");
}

// The ragdoll standing with its feet on a ground plane.
Ragdoll standOnGround(World& w, const RagdollDef& def) {
  BodyDef g;
  g.type = BodyType::Static;
  w.addShape(w.createBody(g), {Geometry::plane(Vec3::UnitZ(), 0.0), Transform(), Material()});
  return spawnRagdoll(w, def, Transform(Vec3(0, 0, 1.0005), Quat::Identity()));
}

ShoveResult standAndShove(double ankle_torque) {
  const UrdfLoadResult r = bundled();
  EXPECT_TRUE(r.ok) << r.error;
  World w;
  const Ragdoll rd = standOnGround(w, r.def);
  BalanceController balance(w, rd, r.def);
  EXPECT_TRUE(balance.missing().empty());
  if (ankle_torque > 0.0) {
    JointMotor weak = BalanceDef().hold;
    weak.max_torque = ankle_torque;
    EXPECT_TRUE(balance.setTarget(w, "ankle_l", weak));
    EXPECT_TRUE(balance.setTarget(w, "ankle_r", weak));
    EXPECT_DOUBLE_EQ(balance.ankleMotor(0).max_torque, ankle_torque);
  }
  const BodyId pelvis = rd.bodies[r.def.findLink("pelvis")], torso = rd.bodies[r.def.findLink("torso")];
  ShoveResult out{10.0, 10.0, 0.0, 0.0};
  for (int i = 0; i < 2000; ++i) {
    balance.update(w);
    w.step(1e-3);
    out.min_z = std::min(out.min_z, w.bodyPose(pelvis).p.z());
  }
  w.applyLinearImpulse(torso, Vec3(20.0, 0, 0), w.comPosition(torso));
  for (int i = 0; i < 4000; ++i) {
    balance.update(w);
    w.step(1e-3);
    const Transform p = w.bodyPose(pelvis);
    out.min_after = std::min(out.min_after, p.p.z());
    out.max_tilt = std::max(out.max_tilt, tilt(p));
  }
  out.final_tilt = tilt(w.bodyPose(pelvis));
  return out;
}

}  // namespace

TEST(ActiveRagdoll, StandsAndRecoversFromShove) {
  const ShoveResult s = standAndShove(0.0);
  EXPECT_GT(s.min_z, 0.95) << "did not stand";
  EXPECT_GT(s.min_after, 0.9) << "fell";
  EXPECT_LT(s.final_tilt, 0.05);
  std::printf("[ active   ] standing pelvis min z %.3f; after 20 N s shove: min z %.3f, max tilt %.3f rad\n",
              s.min_z, s.min_after, s.max_tilt);
}

// The balance law drives each ankle with that joint's own gains (config/joints.yaml): ankles
// capped at 3 N m cannot hold the body against the shove, so it falls.
TEST(ActiveRagdoll, AnklesKeepTheirOwnGains) {
  const ShoveResult s = standAndShove(3.0);
  EXPECT_LT(s.min_after, 0.9) << "weak ankles held the shove: their gains were not used";
  std::printf("[ active   ] ankles capped at 3 N m: after the shove min z %.3f, max tilt %.3f rad\n",
              s.min_after, s.max_tilt);
}

// A balance law whose gains overflow (kp = inf) leaves the ankles' last motors in place instead
// of handing a non-finite target to the World (which refuses it): no throw, no body fault.
TEST(ActiveRagdoll, OverflowingBalanceLawKeepsTheLastMotor) {
  const UrdfLoadResult r = bundled();
  ASSERT_TRUE(r.ok) << r.error;
  World w;
  const Ragdoll rd = standOnGround(w, r.def);
  BalanceDef def;
  def.kp = std::numeric_limits<double>::infinity();
  BalanceController balance(w, rd, r.def, def);
  for (int i = 0; i < 200; ++i) {
    ASSERT_NO_THROW(balance.update(w)) << "step " << i;
    w.step(1e-3);
  }
  EXPECT_EQ(w.bodyFaultCount(), 0);
  EXPECT_GT(w.bodyPose(rd.bodies[r.def.findLink("pelvis")]).p.z(), 0.9);
}
