// Removal without rebuild: World::destroyBody, destroyJoint and removeShape change only what
// they remove. The other islands keep their warm starts and their sleep, and an awake island
// steps bit for bit as in a world where the removed bodies stay (islands are independent); a
// rebuilt world would restart every body awake with cold warm starts and fail these.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <stdexcept>
#include <vector>

#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {
constexpr double kDt = 1.0 / 240.0;
const Vec3 kHalf(0.1, 0.05, 0.05);

struct Group {
  std::vector<BodyId> bodies;
  std::vector<JointId> joints;
};

// Four boxes joined into a chain along x by ball joints, dropped onto the ground at (x, y).
Group addGroup(World& w, double x, double y) {
  Group g;
  for (int i = 0; i < 4; ++i)
    g.bodies.push_back(addBox(w, kHalf, 1.0, Vec3(x + 0.2 * i, y, 0.08 + 0.01 * i)));
  for (int i = 0; i + 1 < 4; ++i) g.joints.push_back(chainLink(w, g.bodies[i], g.bodies[i + 1], 0.1));
  return g;
}

void destroyGroup(World& w, const Group& g) {
  for (const BodyId b : g.bodies) w.destroyBody(b);
}

bool sameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool sameBits(const Vec3& a, const Vec3& b) {
  return sameBits(a.x(), b.x()) && sameBits(a.y(), b.y()) && sameBits(a.z(), b.z());
}
bool sameState(const BodyState& a, const BodyState& b) {
  return sameBits(a.com_position, b.com_position) && sameBits(a.pose.q.coeffs().head<3>(), b.pose.q.coeffs().head<3>()) &&
         sameBits(a.pose.q.w(), b.pose.q.w()) && sameBits(a.linear_velocity, b.linear_velocity) &&
         sameBits(a.angular_velocity, b.angular_velocity);
}

std::vector<ContactInfo> contactsOf(const World& w, const Group& g) {
  std::vector<ContactInfo> out;
  for (const ContactInfo& c : w.contacts())
    for (const BodyId b : g.bodies)
      if (c.body_a == b || c.body_b == b) {
        out.push_back(c);
        break;
      }
  return out;
}

int stepUntil(World& w, int max_steps, const std::function<bool()>& done) {
  for (int i = 0; i < max_steps; ++i) {
    if (done()) return i;
    w.step(kDt);
  }
  return max_steps;
}
}  // namespace

// The anchors by the sweeps alone (SolverSettings::exact_joints off): with exact anchors a box
// of the chain may come to rest on two of its four corners (the load is statically
// indeterminate), and a box whose contacts carry nothing cannot show that its impulses were
// kept.
TEST(Removal, SleepingIslandKeepsSleepAndWarmStarts) {
  WorldDef def;
  def.solver.exact_joints = false;
  World w(def);
  addGround(w);
  const Group a = addGroup(w, 0, 0), b = addGroup(w, 5, 0);
  const auto asleep = [&](const Group& g) {
    for (const BodyId id : g.bodies)
      if (w.isAwake(id)) return false;
    return true;
  };
  ASSERT_LT(stepUntil(w, 5000, [&] { return asleep(a) && asleep(b); }), 5000);
  w.applyLinearImpulseToCenter(b.bodies[0], Vec3(0, 0, 0.5));
  for (int i = 0; i < 5; ++i) w.step(kDt);
  ASSERT_FALSE(asleep(b));
  ASSERT_TRUE(asleep(a));
  const std::vector<ContactInfo> before = contactsOf(w, a);
  ASSERT_FALSE(before.empty());
  std::vector<BodyState> states;
  for (const BodyId id : a.bodies) states.push_back(w.bodyState(id));
  std::vector<double> forces;
  for (const JointId j : a.joints) forces.push_back(w.jointForce(j));

  destroyGroup(w, b);
  for (int i = 0; i < 100; ++i) w.step(kDt);

  EXPECT_TRUE(asleep(a));
  EXPECT_EQ(w.awakeBodyCount(), 0);
  for (size_t k = 0; k < a.bodies.size(); ++k)
    EXPECT_TRUE(sameState(w.bodyState(a.bodies[k]), states[k])) << "body " << k;
  for (size_t k = 0; k < a.joints.size(); ++k)
    EXPECT_TRUE(sameBits(w.jointForce(a.joints[k]), forces[k])) << "joint " << k;
  const std::vector<ContactInfo> after = contactsOf(w, a);
  ASSERT_EQ(after.size(), before.size());
  for (size_t k = 0; k < after.size(); ++k) {
    EXPECT_TRUE(sameBits(after[k].normal_impulse, before[k].normal_impulse)) << "contact " << k;
    EXPECT_TRUE(sameBits(after[k].point, before[k].point));
  }
  // The impulses kept are the ones that hold the chain up: each box's contacts carry about
  // its weight over a step (how a box shares it between its corners is indeterminate).
  for (const BodyId b : a.bodies) {
    double carried = 0.0;
    for (const ContactInfo& c : after)
      if (c.body_a == b || c.body_b == b) carried += c.normal_impulse;
    EXPECT_GT(carried, 0.5 * 9.81 * kDt / SolverSettings().substeps) << "body " << b.index;
  }
}

TEST(Removal, AwakeIslandStepsAsIfTheRemovedOnesStayed) {
  struct Scene {
    World w;
    Group a, b, c;
    Scene() {
      addGround(w);
      a = addGroup(w, 0, 0);
      b = addGroup(w, 5, 0);
      c = addGroup(w, 10, 0);
    }
  };
  Scene kept, removed;
  // Every 100 steps (0.42 s), within the sleep time (0.5 s): group c never sleeps.
  const auto kick = [](Scene& s, int i) {
    if (i % 100 == 0) s.w.applyLinearImpulse(s.c.bodies[1], Vec3(0.2, 0.1, 0.6), s.w.comPosition(s.c.bodies[0]));
  };
  for (int i = 0; i < 60; ++i) {
    kick(kept, i), kick(removed, i);
    kept.w.step(kDt), removed.w.step(kDt);
  }
  destroyGroup(removed.w, removed.b);
  removed.w.destroyJoint(removed.a.joints[2]);
  kept.w.destroyJoint(kept.a.joints[2]);  // the same change to group a in both worlds
  int differing = 0;
  for (int i = 60; i < 900; ++i) {
    kick(kept, i), kick(removed, i);
    kept.w.step(kDt), removed.w.step(kDt);
    for (int k = 0; k < 4; ++k) {
      differing += !sameState(kept.w.bodyState(kept.a.bodies[k]), removed.w.bodyState(removed.a.bodies[k]));
      differing += !sameState(kept.w.bodyState(kept.c.bodies[k]), removed.w.bodyState(removed.c.bodies[k]));
      differing += kept.w.isAwake(kept.c.bodies[k]) != removed.w.isAwake(removed.c.bodies[k]);
    }
  }
  EXPECT_EQ(differing, 0);
  EXPECT_TRUE(removed.w.isAwake(removed.c.bodies[0]));  // kicked all along
}

TEST(Removal, DestroyedIdsAreRefused) {
  World w;
  const BodyId ground = addGround(w);
  const Group g = addGroup(w, 0, 0);
  const BodyId other = addBox(w, kHalf, 1.0, Vec3(3, 0, 0.05));
  HingeJointDef hd;
  hd.body_a = ground;
  hd.body_b = other;
  const JointId hinge = w.createHingeJoint(hd);
  const BodyId b = g.bodies[1];
  w.destroyBody(b);
  w.destroyJoint(hinge);
  EXPECT_FALSE(w.isValid(b));
  EXPECT_FALSE(w.isValid(hinge));
  EXPECT_FALSE(w.isValid(g.joints[0]));  // the joints on the destroyed body went with it
  EXPECT_FALSE(w.isValid(g.joints[1]));
  EXPECT_TRUE(w.isValid(g.joints[2]));
  EXPECT_TRUE(w.isValid(g.bodies[0]));
  EXPECT_TRUE(w.isValid(other));
  EXPECT_EQ(w.bodyCount(), 6);  // slots: ids keep their index
  EXPECT_EQ(w.jointCount(), 4);
  const Transform pose;
  BallJointDef bd;
  bd.body_a = g.bodies[0];
  bd.body_b = b;
  using E = std::out_of_range;
  EXPECT_THROW(w.bodyState(b), E);
  EXPECT_THROW(w.bodyPose(b), E);
  EXPECT_THROW(w.bodyDef(b), E);
  EXPECT_THROW(w.bodyShapes(b), E);
  EXPECT_THROW(w.comPosition(b), E);
  EXPECT_THROW(w.pointVelocity(b, Vec3::Zero()), E);
  EXPECT_THROW(w.isAwake(b), E);
  EXPECT_THROW(w.wake(b), E);
  EXPECT_THROW(w.applyLinearImpulse(b, Vec3::UnitZ(), Vec3::Zero()), E);
  EXPECT_THROW(w.applyLinearImpulseToCenter(b, Vec3::UnitZ()), E);
  EXPECT_THROW(w.applyAngularImpulse(b, Vec3::UnitZ()), E);
  EXPECT_THROW(w.applyForce(b, Vec3::UnitZ(), Vec3::Zero()), E);
  EXPECT_THROW(w.applyTorque(b, Vec3::UnitZ()), E);
  EXPECT_THROW(w.setBodyState(b, pose, Vec3::Zero(), Vec3::Zero()), E);
  EXPECT_THROW(w.addShape(b, {Geometry::sphere(0.1), Transform(), Material()}), E);
  EXPECT_THROW(w.removeShape(b, 0), E);
  EXPECT_THROW(w.createBallJoint(bd), E);
  EXPECT_THROW(w.disableCollision(b, other), E);
  EXPECT_THROW(w.destroyBody(b), E);
  for (const JointId j : {hinge, g.joints[0]}) {
    EXPECT_THROW(w.jointType(j), E);
    EXPECT_THROW(w.hingeAngle(j), E);
    EXPECT_THROW(w.ballAngles(j), E);
    EXPECT_THROW(w.ballSwingTwist(j), E);
    EXPECT_THROW(w.prismaticPosition(j), E);
    EXPECT_THROW(w.jointAnchorError(j), E);
    EXPECT_THROW(w.jointForce(j), E);
    EXPECT_THROW(w.jointTorque(j), E);
    EXPECT_THROW(w.isJointBroken(j), E);
    EXPECT_THROW(w.breakJoint(j), E);
    EXPECT_THROW(w.setJointMotor(j, 0, JointMotor()), E);
    EXPECT_THROW(w.destroyJoint(j), E);
  }
  EXPECT_THROW(w.removeShape(other, 1), E);
  EXPECT_THROW(w.removeShape(other, -1), E);
  for (int i = 0; i < 10; ++i) w.step(kDt);
  for (const ContactInfo& c : w.contacts()) EXPECT_TRUE(c.body_a != b && c.body_b != b);
}

TEST(Removal, CreateAfterDestroyAppends) {
  World w;
  addGround(w);
  const Group g = addGroup(w, 0, 0);
  const Vec3 kept_pos = w.comPosition(g.bodies[3]);
  destroyGroup(w, Group{{g.bodies[0], g.bodies[1], g.bodies[2]}, {}});
  const int slots = w.bodyCount();
  const BodyId fresh = addBox(w, kHalf, 1.0, Vec3(0.2, 0, 0.3));
  EXPECT_EQ(fresh.index, slots);
  EXPECT_TRUE(w.isValid(fresh));
  EXPECT_FALSE(w.isValid(g.bodies[0]));
  EXPECT_TRUE(sameBits(w.comPosition(g.bodies[3]), kept_pos));
  const JointId j = chainLink(w, fresh, g.bodies[3], 0.1);
  EXPECT_TRUE(w.isValid(j));
  for (int i = 0; i < 1000; ++i) w.step(kDt);
  EXPECT_NEAR(w.comPosition(fresh).z(), kHalf.z(), 0.01);  // fell and rests on the ground
  EXPECT_LT(w.jointAnchorError(j).norm(), 0.005);
}

TEST(Removal, SteppingSkipsFreedSlots) {
  World w;
  addGround(w);
  const Group g = addGroup(w, 0, 0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // A bad input the fault guard would reset (and report) if it still looked at the slot.
  w.setBodyState(g.bodies[2], Transform(), Vec3(nan, 0, 0), Vec3::Zero());
  w.applyForce(g.bodies[3], Vec3(0, 0, nan), Vec3::Zero());
  w.destroyBody(g.bodies[2]);
  w.destroyBody(g.bodies[3]);
  for (int i = 0; i < 200; ++i) w.step(kDt);
  EXPECT_EQ(w.bodyFaultCount(), 0);
  EXPECT_TRUE(w.takeBodyFaults().empty());
  EXPECT_TRUE(std::isfinite(w.kineticEnergy()));
  EXPECT_TRUE(w.linearMomentum().allFinite());
  EXPECT_LE(w.awakeBodyCount(), 2);
}

TEST(Removal, BodiesTouchingTheDestroyedOneWake) {
  World w;
  addGround(w);
  const Vec3 half(0.2, 0.2, 0.2);
  const BodyId bottom = addBox(w, half, 1.0, Vec3(0, 0, 0.2));
  const BodyId top = addBox(w, half, 1.0, Vec3(0, 0, 0.6));
  const BodyId far = addBox(w, half, 1.0, Vec3(5, 0, 0.2));
  ASSERT_LT(stepUntil(w, 5000, [&] { return w.awakeBodyCount() == 0; }), 5000);
  w.destroyBody(bottom);
  EXPECT_TRUE(w.isAwake(top));
  EXPECT_FALSE(w.isAwake(far));
  for (int i = 0; i < 480; ++i) w.step(kDt);
  EXPECT_NEAR(w.comPosition(top).z(), 0.2, 0.01);  // fell onto the ground
  EXPECT_FALSE(w.isAwake(far));
}

TEST(Removal, DestroyedJointFreesItsBodies) {
  World w;
  std::vector<JointId> joints;
  const std::vector<BodyId> chain = addChain(w, Vec3(0, 0, 2), {1.0, 1.0}, -Vec3::UnitZ(), &joints);
  for (int i = 0; i < 10; ++i) w.step(kDt);
  const double z = w.comPosition(chain[0]).z();
  w.destroyJoint(joints[0]);
  EXPECT_EQ(w.jointCount(), 2);
  EXPECT_TRUE(w.isValid(joints[1]));
  for (int i = 0; i < 120; ++i) w.step(kDt);
  EXPECT_LT(w.comPosition(chain[0]).z(), z - 1.0);  // ~0.5 s of free fall: 1.2 m
  EXPECT_LT(w.jointAnchorError(joints[1]).norm(), 1e-3);  // the other joint still holds
}

TEST(Removal, RemoveShapeKeepsTheOthers) {
  World w;
  addGround(w);
  const BodyId b = addBox(w, kHalf, 1.0, Vec3(0, 0, 0.5));
  w.addShape(b, {Geometry::sphere(0.05), Transform(Vec3(0, 0, -0.3), Quat::Identity()), Material()});
  for (int i = 0; i < 480; ++i) w.step(kDt);
  EXPECT_NEAR(w.comPosition(b).z(), 0.35, 0.01);  // on the sphere
  w.removeShape(b, 1);
  ASSERT_EQ(w.bodyShapes(b).size(), 1u);
  EXPECT_EQ(w.bodyShapes(b)[0].geometry.type, ShapeType::Box);
  EXPECT_TRUE(w.isAwake(b));
  for (int i = 0; i < 480; ++i) w.step(kDt);
  EXPECT_NEAR(w.comPosition(b).z(), kHalf.z(), 0.01);  // fell onto its box
  w.removeShape(b, 0);
  EXPECT_TRUE(w.bodyShapes(b).empty());
  for (int i = 0; i < 10; ++i) w.step(kDt);
  EXPECT_TRUE(w.contacts().empty());
}
