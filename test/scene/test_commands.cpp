// Unit tests of the node's ROS-free command validation and conversion (src/scene/commands.*).
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "commands.hpp"
#include "ragdoll_sim/ragdoll.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::scene;

namespace {

RagdollDef twoLinks() {
  RagdollDef def;
  def.name = "test";
  LinkDef a;
  a.name = "pelvis";
  LinkDef b;
  b.name = "torso";
  def.links = {a, b};
  RagdollJointDef j;
  j.name = "waist_y+waist_x+waist_z";
  j.kind = RagdollJointKind::Ball;
  j.parent = 0;
  j.child = 1;
  j.chain_links = {"waist_link1", "waist_link2"};
  def.joints = {j};
  return def;
}

// Link 1 ("torso") is at (1,2,3), turned 90 deg about z; link 0 at the origin.
Transform posesOf(int link) {
  if (link == 1) return Transform(Vec3(1, 2, 3), Quat(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitZ())));
  return Transform();
}

const LinkPoseFn kPoses = [](int link) { return posesOf(link); };

}  // namespace

TEST(Commands, LinkTable) {
  LinkTable t(twoLinks());
  EXPECT_EQ(t.find("pelvis"), 0);
  EXPECT_EQ(t.find("torso"), 1);
  EXPECT_EQ(t.find("head"), -1);
  ASSERT_NE(t.chainJointOf("waist_link2"), nullptr);
  EXPECT_EQ(*t.chainJointOf("waist_link2"), "waist_y+waist_x+waist_z");
  EXPECT_EQ(t.chainJointOf("torso"), nullptr);
}

TEST(Commands, Frames) {
  CommandFrame f;
  EXPECT_TRUE(parseFrame("", &f));
  EXPECT_EQ(f, CommandFrame::World);
  EXPECT_TRUE(parseFrame("world", &f));
  EXPECT_EQ(f, CommandFrame::World);
  EXPECT_TRUE(parseFrame("link", &f));
  EXPECT_EQ(f, CommandFrame::Link);
  EXPECT_FALSE(parseFrame("base_link", &f));
  EXPECT_FALSE(parseFrame("World", &f));
}

TEST(Commands, ImpulseRejections) {
  LinkTable t(twoLinks());
  CommandLimits lim;
  ImpulseCommand c;
  c.link = "torso";
  c.frame = "link";
  c.impulse = Vec3(0, 10, 0);
  EXPECT_TRUE(checkImpulse(c, t, lim, kPoses).ok);

  ImpulseCommand bad = c;
  bad.link = "nope";
  CommandCheck r = checkImpulse(bad, t, lim, kPoses);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("unknown link 'nope'"), std::string::npos) << r.error;

  bad = c;
  bad.link = "waist_link1";
  r = checkImpulse(bad, t, lim, kPoses);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("dummy"), std::string::npos) << r.error;

  bad = c;
  bad.frame = "base";
  r = checkImpulse(bad, t, lim, kPoses);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("unknown frame 'base'"), std::string::npos) << r.error;

  bad = c;
  bad.impulse.x() = std::numeric_limits<double>::quiet_NaN();
  r = checkImpulse(bad, t, lim, kPoses);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("not finite"), std::string::npos) << r.error;

  bad = c;
  bad.point.z() = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(checkImpulse(bad, t, lim, kPoses).ok);

  bad = c;
  bad.impulse = Vec3(0, 0, 1001);
  r = checkImpulse(bad, t, lim, kPoses);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("max_impulse"), std::string::npos) << r.error;

  // Lever arm: a world point far from the link is rejected, a near one accepted.
  bad = c;
  bad.frame = "world";
  bad.point = Vec3(1, 2, 3) + Vec3(0, 0, 10.5);
  EXPECT_FALSE(checkImpulse(bad, t, lim, kPoses).ok);
  bad.point = Vec3(1, 2, 3) + Vec3(0, 0, 0.5);
  EXPECT_TRUE(checkImpulse(bad, t, lim, kPoses).ok);
}

// Every rule has its own problem key (the node throttles its warnings per key), and the key
// never holds message contents.
TEST(Commands, ProblemKeys) {
  LinkTable t(twoLinks());
  CommandLimits lim;
  ImpulseCommand c;
  c.link = "torso";
  c.frame = "link";
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto problem = [&](auto edit) {
    ImpulseCommand bad = c;
    edit(bad);
    const CommandCheck r = checkImpulse(bad, t, lim, kPoses);
    EXPECT_FALSE(r.ok);
    return r.problem;
  };
  EXPECT_EQ(problem([](ImpulseCommand& b) { b.link = ""; }), "empty link");
  EXPECT_EQ(problem([](ImpulseCommand& b) { b.link = "nope"; }), "unknown link");
  EXPECT_EQ(problem([](ImpulseCommand& b) { b.link = "waist_link1"; }), "dummy link");
  EXPECT_EQ(problem([](ImpulseCommand& b) { b.frame = "base"; }), "unknown frame");
  EXPECT_EQ(problem([&](ImpulseCommand& b) { b.impulse.x() = nan; }), "impulse not finite");
  EXPECT_EQ(problem([&](ImpulseCommand& b) { b.point.y() = nan; }), "point not finite");
  EXPECT_EQ(problem([](ImpulseCommand& b) { b.impulse.z() = 1e4; }), "above max_impulse");
  EXPECT_EQ(problem([](ImpulseCommand& b) { b.point.z() = 11.0; }), "lever arm");
  EXPECT_EQ(checkImpulse(c, t, lim, kPoses).problem, "");

  ForceCommand f;
  f.link = "pelvis";
  f.torque.x() = 2e5;
  EXPECT_EQ(checkForce(f, t, lim, kPoses).problem, "above max_torque");
  f.torque.x() = nan;
  EXPECT_EQ(checkForce(f, t, lim, kPoses).problem, "torque not finite");
  f.torque.x() = 0.0;
  f.duration = nan;
  EXPECT_EQ(checkForce(f, t, lim, kPoses).problem, "duration not finite");
}

TEST(Commands, ForceRejections) {
  LinkTable t(twoLinks());
  CommandLimits lim;
  ForceCommand c;
  c.link = "pelvis";
  c.force = Vec3(10, 0, 0);
  c.duration = 0.5;
  EXPECT_TRUE(checkForce(c, t, lim, kPoses).ok);

  ForceCommand bad = c;
  bad.force = Vec3(2e5, 0, 0);
  CommandCheck r = checkForce(bad, t, lim, kPoses);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("max_force"), std::string::npos) << r.error;

  bad = c;
  bad.torque = Vec3(0, 0, 2e5);
  r = checkForce(bad, t, lim, kPoses);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("max_torque"), std::string::npos) << r.error;

  bad = c;
  bad.duration = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(checkForce(bad, t, lim, kPoses).ok);
  bad.duration = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(checkForce(bad, t, lim, kPoses).ok);

  bad = c;
  bad.duration = -1.0;  // until cleared
  EXPECT_TRUE(checkForce(bad, t, lim, kPoses).ok);
}

TEST(Commands, ImpulseToWorld) {
  LinkTable t(twoLinks());
  CommandLimits lim;
  ImpulseCommand c;
  c.link = "torso";
  c.frame = "link";
  c.point = Vec3(1, 0, 0);
  c.impulse = Vec3(1, 0, 0);
  CommandCheck k = checkImpulse(c, t, lim, kPoses);
  ASSERT_TRUE(k.ok);
  WorldImpulse w = toWorldImpulse(c, k, posesOf(k.link));
  EXPECT_EQ(w.link, 1);
  EXPECT_TRUE(w.point.isApprox(Vec3(1, 3, 3), 1e-12)) << w.point.transpose();
  EXPECT_TRUE(w.impulse.isApprox(Vec3(0, 1, 0), 1e-12)) << w.impulse.transpose();

  c.frame = "";
  c.point = Vec3(1, 2, 4);
  k = checkImpulse(c, t, lim, kPoses);
  ASSERT_TRUE(k.ok);
  w = toWorldImpulse(c, k, posesOf(k.link));
  EXPECT_TRUE(w.point.isApprox(Vec3(1, 2, 4)));
  EXPECT_TRUE(w.impulse.isApprox(Vec3(1, 0, 0)));
}

TEST(Commands, ForceToActive) {
  LinkTable t(twoLinks());
  CommandLimits lim;
  ForceCommand c;
  c.link = "torso";
  c.frame = "world";
  c.point = Vec3(1, 2, 4);  // 1 m above the torso origin
  c.force = Vec3(10, 0, 0);
  c.torque = Vec3(0, 0, 1);
  c.duration = 0.5;
  CommandCheck k = checkForce(c, t, lim, kPoses);
  ASSERT_TRUE(k.ok);
  ActiveForce f = toActiveForce(c, k, posesOf(k.link), 1e-3);
  EXPECT_EQ(f.link, 1);
  EXPECT_TRUE(f.local_point.isApprox(Vec3(0, 0, 1), 1e-12)) << f.local_point.transpose();
  EXPECT_TRUE(f.force.isApprox(Vec3(10, 0, 0)));
  EXPECT_TRUE(f.torque.isApprox(Vec3(0, 0, 1)));
  EXPECT_EQ(f.steps_left, 500);

  c.frame = "link";
  c.point = Vec3(0.5, 0, 0);
  c.force = Vec3(10, 0, 0);  // link x = world y
  k = checkForce(c, t, lim, kPoses);
  ASSERT_TRUE(k.ok);
  f = toActiveForce(c, k, posesOf(k.link), 1e-3);
  EXPECT_TRUE(f.local_point.isApprox(Vec3(0.5, 0, 0)));
  EXPECT_TRUE(f.force.isApprox(Vec3(0, 10, 0), 1e-12)) << f.force.transpose();
}

TEST(Commands, ForceStepCount) {
  EXPECT_EQ(forceStepCount(-1.0, 1e-3), -1);
  EXPECT_EQ(forceStepCount(0.0, 1e-3), 1);
  EXPECT_EQ(forceStepCount(0.0001, 1e-3), 1);
  EXPECT_EQ(forceStepCount(0.5, 1e-3), 500);
  EXPECT_EQ(forceStepCount(0.0016, 1e-3), 2);
  EXPECT_EQ(forceStepCount(1e300, 1e-3), -1);
}
