// Fixed bases (RagdollDef::fixed_base, SpawnDef::fixed_base): the root link is a static body at
// its spawn pose. A bar hinged to a pinned base swings with the compound pendulum's period, and
// the bundled ragdoll hung by its hands from a pinned bar stays attached and comes to rest under
// it.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "object_models.hpp"
#include "ragdoll_sim/scene.hpp"

using namespace ragdoll_sim;

namespace {

constexpr double kG = 9.81;
// Hanging ragdoll: viscous damping in its joints and in the grips, without which nothing takes
// the energy of the swing away.
constexpr double kJointDamping = 20.0;  // N m s/rad
constexpr double kGripDamping = 200.0;  // N m s/rad

// A 1 m bar (2 kg) hanging from a hinge about y at the origin of a small base link.
RagdollDef pendulum(const Vec3& bar_half, double bar_mass) {
  RagdollDef def;
  def.name = "pendulum";
  def.fixed_base = true;
  LinkDef base;
  base.name = "base";
  base.mass = 1.0;
  base.inertia = test::solidBoxInertia(Vec3(0.05, 0.05, 0.05), 1.0);
  base.shapes.push_back({Geometry::box(Vec3(0.05, 0.05, 0.05)), Transform(), Material()});
  LinkDef bar;
  bar.name = "bar";
  bar.mass = bar_mass;
  bar.inertia = test::solidBoxInertia(bar_half, bar_mass);
  bar.shapes.push_back({Geometry::box(bar_half), Transform(), Material()});
  bar.rest_pose = Transform(Vec3(0, 0, -bar_half.z()), Quat::Identity());
  def.links = {base, bar};
  RagdollJointDef hinge;
  hinge.name = "pivot";
  hinge.kind = RagdollJointKind::Hinge;
  hinge.parent = 0;
  hinge.child = 1;
  hinge.frame_child = Transform(Vec3(0, 0, bar_half.z()), Quat::Identity());
  hinge.axes = {Vec3::UnitY()};
  def.joints = {hinge};
  return def;
}

TEST(FixedBase, CompoundPendulumPeriod) {
  SceneDef sd;
  sd.ground = false;
  sd.world.gravity = Vec3(0, 0, -kG);
  Scene scene(sd);
  const Vec3 half(0.02, 0.02, 0.5);
  const double m = 2.0, d = half.z();
  SpawnDef s;
  s.name = "pendulum";
  s.def = pendulum(half, m);
  const Vec3 pivot(0, 0, 2.0);
  s.pose = Transform(pivot, Quat::Identity());
  std::string e;
  ASSERT_EQ(scene.addRagdoll(s, &e), SpawnResult::Added) << e;
  ASSERT_TRUE(scene.start(&e)) << e;
  World& w = scene.world();
  const BodyId base = scene.bodies(0).bodies[0], bar = scene.bodies(0).bodies[1];
  const JointId j = scene.bodies(0).joints[0];
  // Small amplitude: released at rest 0.05 rad from the vertical.
  const Quat tilt(Eigen::AngleAxisd(0.05, Vec3::UnitY()));
  w.setBodyState(bar, Transform(pivot + tilt * Vec3(0, 0, -d), tilt), Vec3::Zero(), Vec3::Zero());
  std::vector<double> ups;  // upward zero crossings of the hinge angle
  double prev = w.hingeAngle(j);
  for (int i = 0; i < 20000 && ups.size() < 9; ++i) {
    scene.step();
    const double a = w.hingeAngle(j);
    if (prev < 0.0 && a >= 0.0) ups.push_back(scene.time() - scene.dt() * a / (a - prev));
    prev = a;
  }
  ASSERT_GE(ups.size(), 9u) << "the bar does not swing about the pinned base";
  const double T = (ups.back() - ups.front()) / double(ups.size() - 1);
  const double I = m * (4 * half.x() * half.x() + 4 * half.z() * half.z()) / 12.0 + m * d * d;
  const double expected = 2 * M_PI * std::sqrt(I / (m * kG * d));
  RecordProperty("period_measured", std::to_string(T));
  RecordProperty("period_closed_form", std::to_string(expected));
  EXPECT_NEAR(T, expected, 0.01 * expected);
  EXPECT_EQ(w.bodyPose(base).p, pivot) << "the base moved";
  EXPECT_LT(w.jointAnchorError(j).norm(), 1e-3);
}

// The bundled ragdoll with its arms raised, its hands tied to a pinned bar by ball joints (the
// World's API): it swings under the bar, stays attached and comes to rest there, with the joints
// solved alone in double and in lanes (a closed loop of damped joints: the two row orders).
class HungFromBar : public ::testing::TestWithParam<int> {};  // SolverSettings::lanes

TEST_P(HungFromBar, RagdollComesToRest) {
  SceneDef sd;
  sd.ground = false;
  sd.world.solver.lanes = GetParam();
  Scene scene(sd);
  std::string e;
  SpawnDef r;
  r.name = "ragdoll";
  r.def = test::bundledRagdoll();
  // The bundled URDF has no <dynamics>: muscle tone as viscous damping on every axis.
  for (RagdollJointDef& j : r.def.joints) j.damping.assign(size_t(jointAxisCount(j.kind)), kJointDamping);
  r.pose = Transform(Vec3(0, 0, 1.0), Quat::Identity());
  ASSERT_EQ(scene.addRagdoll(r, &e), SpawnResult::Added) << e;
  ASSERT_TRUE(scene.start(&e)) << e;
  World& w = scene.world();
  const int k = scene.find("ragdoll");
  // Arms raised forward about the shoulders' y axes, inside shoulder_*_y's limit (-2.8 rad).
  const Quat raise(Eigen::AngleAxisd(-2.6, Vec3::UnitY()));
  for (const char* side : {"l", "r"}) {
    const std::string s(side);
    const int upper = scene.findLink(k, "upper_arm_" + s);
    ASSERT_GE(upper, 0);
    const Vec3 shoulder = w.bodyPose(scene.bodies(k).bodies[size_t(upper)]).p;
    for (const std::string& link : {"upper_arm_" + s, "lower_arm_" + s, "hand_" + s}) {
      const BodyId b = scene.bodies(k).bodies[size_t(scene.findLink(k, link))];
      const Transform x = w.bodyPose(b);
      w.setBodyState(b, Transform(shoulder + raise * (x.p - shoulder), raise * x.q), Vec3::Zero(),
                     Vec3::Zero());
    }
  }
  const int hl = scene.findLink(k, "hand_l"), hr = scene.findLink(k, "hand_r");
  ASSERT_GE(hl, 0);
  ASSERT_GE(hr, 0);
  const BodyId hand[2] = {scene.bodies(k).bodies[size_t(hl)], scene.bodies(k).bodies[size_t(hr)]};
  Vec3 grip[2];
  for (int i = 0; i < 2; ++i) grip[i] = w.bodyState(hand[i]).com_position;
  const Vec3 mid = 0.5 * (grip[0] + grip[1]);
  // A pinned bar through both grips (a fixed-base object of one link).
  SpawnDef bar = test::boxObject("bar", Vec3(0.02, 0.5, 0.02), 3.0, mid);
  bar.fixed_base = true;
  ASSERT_EQ(scene.addObject(bar, &e), SpawnResult::Added) << e;
  const int kb = scene.find("bar");
  ASSERT_GE(kb, 0);
  const BodyId bar_body = scene.bodies(kb).bodies[0];
  JointId joints[2];
  for (int i = 0; i < 2; ++i) {
    BallJointDef bj;
    bj.body_a = bar_body;
    bj.body_b = hand[i];
    bj.frame_a = Transform(w.bodyPose(bar_body).applyInverse(grip[i]), Quat::Identity());
    bj.frame_b = Transform(w.bodyPose(hand[i]).applyInverse(grip[i]),
                           w.bodyPose(hand[i]).q.conjugate());
    // A grip rubs: viscous damping on each axis.
    for (JointMotor& m : bj.motors) m.damping = kGripDamping;
    joints[i] = w.createBallJoint(bj);
  }
  double worst = 0.0;
  const int steps = int(std::lround(12.0 / scene.dt()));
  for (int i = 0; i < steps; ++i) {
    scene.step();
    for (JointId j : joints) worst = std::max(worst, w.jointAnchorError(j).norm());
  }
  double last = 0.0;
  for (JointId j : joints) last = std::max(last, w.jointAnchorError(j).norm());
  double mass = 0.0;
  Vec3 com = Vec3::Zero();
  for (BodyId b : scene.bodies(k).bodies) {
    mass += w.bodyDef(b).mass;
    com += w.bodyDef(b).mass * w.bodyState(b).com_position;
  }
  com /= mass;
  const double speed = test::maxSpeed(w, scene.bodies(k).bodies);
  RecordProperty("anchor_error_worst_mm", std::to_string(worst * 1e3));
  RecordProperty("anchor_error_end_mm", std::to_string(last * 1e3));
  RecordProperty("max_speed_end", std::to_string(speed));
  EXPECT_LT((w.bodyPose(bar_body).p - mid).norm(), 1e-6) << "the bar moved";
  EXPECT_LT(worst, 0.005) << "the hands came off the bar";
  EXPECT_LT(last, 0.002);
  EXPECT_LT(speed, 0.05) << "not at rest after 12 s";
  EXPECT_LT(com.z(), mid.z() - 0.3) << "the body does not hang under the bar";
  EXPECT_LT(std::hypot(com.x() - mid.x(), com.y() - mid.y()), 0.05);
}

INSTANTIATE_TEST_SUITE_P(FixedBase, HungFromBar, ::testing::Values(1, 8));

}  // namespace
