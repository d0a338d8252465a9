// Exact joint anchors (src/core/joint_tree.hpp): the point rows of each joint tree solved
// directly hold where Gauss-Seidel cannot converge (many links on one body, light links on
// heavy ones), the solve is the same for 1 and 2 threads on a split island, and the impulses
// it adds reach the joint reports.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <memory>
#include <vector>

#include "joint_test_util.hpp"
#include "joint_tree.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {

constexpr double kStep = 1.0 / 60.0;

// A 1 kg hub with n 1 kg children on ball joints, their anchors 0.5 m out in a Fibonacci
// pattern, spinning at 3 rad/s about z at `centre`; hung from a static body above it when
// `hang` (else free).
struct Star {
  BodyId hub;
  std::vector<BodyId> children;
  std::vector<JointId> joints;
};

Star addStar(World& w, int n, const Vec3& centre, bool hang) {
  Star s;
  const Vec3 spin(0, 0, 3);
  s.hub = addDynamic(w, 1.0, Mat3::Identity() * 0.004, Transform(centre, Quat::Identity()),
                     Vec3::Zero(), Vec3::Zero(), spin);
  if (hang) {
    BallJointDef t;
    t.body_a = addStatic(w, Transform(centre + Vec3(0, 0, 0.6), Quat::Identity()));
    t.body_b = s.hub;
    t.frame_b.p = Vec3(0, 0, 0.6);
    s.joints.push_back(w.createBallJoint(t));
  }
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / n, r = std::sqrt(1.0 - z * z), a = golden * i;
    const Vec3 dir(r * std::cos(a), r * std::sin(a), z);
    const BodyId c = addBody(w, Geometry::sphere(0.04), 1.0, Mat3::Identity() * 6.4e-4,
                             Transform(centre + 0.55 * dir, Quat::Identity()), Material(),
                             spin.cross(0.55 * dir));
    BallJointDef j;
    j.body_a = s.hub;
    j.body_b = c;
    j.frame_a.p = 0.5 * dir;
    j.frame_b.p = -0.05 * dir;
    s.joints.push_back(w.createBallJoint(j));
    s.children.push_back(c);
  }
  return s;
}

double maxAnchorError(const World& w, const std::vector<JointId>& joints) {
  double e = 0.0;
  for (const JointId j : joints) e = std::max(e, w.jointAnchorError(j).norm());
  return e;
}

}  // namespace

// 200 children on one hub: Gauss-Seidel alone flings the star apart within the first steps
// (anchors metres apart); the tree solve holds every anchor within the slop.
TEST(JointTree, StarOfTwoHundredChildrenHoldsItsAnchors) {
  WorldDef def = noSleep();
  World w(def);
  const Star s = addStar(w, 200, Vec3(0, 0, 1.4), true);
  double worst = 0.0;
  for (int i = 0; i < 30; ++i) {
    w.step(kStep);
    worst = std::max(worst, maxAnchorError(w, s.joints));
  }
  EXPECT_LT(worst, 1e-3);
  // the spin about the hanging axis is kept (the projection adds no torque about it)
  EXPECT_GT(w.bodyState(s.hub).angular_velocity.z(), 2.0);
}

// A heavy arm (3 x 10 kg) ending in three 10 g finger links, swinging down from horizontal:
// 1000:1 along the chain. The sweeps alone leave millimetres; the tree solve the slop.
TEST(JointTree, HeavyArmWithGramFingersHolds) {
  WorldDef def = noSleep();
  World w(def);
  std::vector<JointId> joints;
  addChain(w, Vec3(0, 0, 2), {10, 10, 10, 0.01, 0.01, 0.01}, Vec3::UnitX(), &joints);
  double worst = 0.0;
  for (int i = 0; i < 60; ++i) {
    w.step(kStep);
    worst = std::max(worst, maxAnchorError(w, joints));
  }
  EXPECT_LT(worst, 1e-3);
}

// The anchor's impulse from the tree solve is the joint's: a 2 kg bob hanging at rest from a
// static body reports its weight (jointForce), and the impulse warm starts the next step.
TEST(JointTree, HangingBobReportsItsWeight) {
  World w(noSleep());
  std::vector<JointId> joints;
  const std::vector<BodyId> bob = addChain(w, Vec3(0, 0, 2), {2.0}, -Vec3::UnitZ(), &joints);
  for (int i = 0; i < 60; ++i) w.step(kStep);
  EXPECT_NEAR(w.jointForce(joints[0]), 2.0 * kG, 1e-6 * 2.0 * kG);
  EXPECT_LT(w.bodyState(bob[0]).linear_velocity.norm(), 1e-9);
}

// Four stars of 20 children touching on the ground: one island of 84 bodies, split in two
// halves of whole stars. Each half's trees are solved on its own thread: the poses are the
// same bit for bit on 1 and 2 threads, and the anchors hold.
TEST(JointTree, SplitIslandSameOnOneAndTwoThreads) {
  std::vector<std::unique_ptr<World>> worlds;
  std::vector<std::vector<JointId>> joints(2);
  for (const int threads : {1, 2}) {
    WorldDef def = noSleep();
    def.threads = threads;
    worlds.push_back(std::make_unique<World>(def));
    World& w = *worlds.back();
    addGround(w);
    for (int k = 0; k < 4; ++k) {
      const Star s = addStar(w, 20, Vec3(1.1 * k, 0, 0.7), false);
      joints[threads - 1].insert(joints[threads - 1].end(), s.joints.begin(), s.joints.end());
    }
  }
  bool split = false;
  double worst = 0.0;
  for (int i = 0; i < 60; ++i) {
    for (auto& w : worlds) w->step(kStep);
    split = split || worlds[0]->islandCounters().split_islands > 0;
    worst = std::max(worst, maxAnchorError(*worlds[1], joints[1]));
  }
  EXPECT_TRUE(split);
  EXPECT_LT(worst, 1e-3);
  for (int b = 0; b < worlds[0]->bodyCount(); ++b) {
    const Transform x1 = worlds[0]->bodyPose(BodyId{b}), x2 = worlds[1]->bodyPose(BodyId{b});
    ASSERT_EQ(std::memcmp(x1.p.data(), x2.p.data(), sizeof(double) * 3), 0) << "body " << b;
    ASSERT_EQ(std::memcmp(x1.q.coeffs().data(), x2.q.coeffs().data(), sizeof(double) * 4), 0);
  }
}

namespace {

// Two chains of three 1 kg bodies on ball joints, as one part of an island (no contact or
// joint between them): chain 0 bodies 0..2, joints 0, 1; chain 1 bodies 3..5, joints 2, 3.
// Each joint's anchors are 0.25 m out along x from its bodies' centres.
struct TwoChains {
  std::vector<SolverBody> bodies = std::vector<SolverBody>(6);
  std::vector<Joint> joints;
  TwoChains(double error0, double error1) {
    for (SolverBody& b : bodies) {
      b.inv_mass = 1.0;
      b.inv_inertia = Mat3::Identity() * 100.0;
    }
    for (int c = 0; c < 2; ++c)
      for (int k = 0; k < 2; ++k) {
        BallJointDef d;
        d.body_a = BodyId{3 * c + k};
        d.body_b = BodyId{3 * c + k + 1};
        Joint j(d);
        j.anchor()->point.rA = Vec3(0.25, 0, 0);
        j.anchor()->point.rB = Vec3(-0.25, 0, 0);
        joints.push_back(j);
      }
    // anchor velocity errors of about error0 (chain 0) and error1 (chain 1), m/s
    for (int b = 0; b < 6; ++b) {
      const double e = b < 3 ? error0 : error1;
      bodies[b].v = e * Vec3(0.3 * b, -0.7 * (b % 2), 0.2);
      bodies[b].w = e * Vec3(0.1, 0.4 * (b % 3), -0.5);
    }
  }
  // Projects the velocities of the chains in `chains` (0, 1 or both) as one part.
  void project(const std::vector<int>& chains, double tolerance) {
    std::vector<int> island_bodies;
    std::vector<Joint*> js;
    for (const int c : chains) {
      for (int k = 0; k < 3; ++k) island_bodies.push_back(3 * c + k);
      for (int k = 0; k < 2; ++k) js.push_back(&joints[2 * c + k]);
    }
    IslandRange p;
    p.body_end = int(island_bodies.size());
    p.joint_end = int(js.size());
    JointTree tree;
    tree.reserve(int(bodies.size()), p.body_end, p.joint_end);
    tree.build(p, island_bodies, js.data(), bodies);
    tree.projectVelocities(p, bodies, island_bodies, 1e-3, tolerance);
  }
};

bool sameBits(const SolverBody& x, const SolverBody& y) {
  return std::memcmp(x.v.data(), y.v.data(), sizeof(double) * 3) == 0 &&
         std::memcmp(x.w.data(), y.w.data(), sizeof(double) * 3) == 0;
}

}  // namespace

// Each tree stops on its own error: a chain whose anchors are within the tolerance is left as
// it is, whatever the other trees of its part, so its bodies have the bits they have alone
// (an island's arithmetic does not depend on the islands that share its range), and a chain
// far off is solved as it is alone.
TEST(JointTree, EachTreeStopsOnItsOwnError) {
  const double tolerance = 1e-3;
  TwoChains both(1.0, 1e-5), alone0(1.0, 1e-5), alone1(1.0, 1e-5);
  both.project({0, 1}, tolerance);
  alone0.project({0}, tolerance);
  alone1.project({1}, tolerance);
  for (int b = 0; b < 3; ++b) EXPECT_TRUE(sameBits(both.bodies[b], alone0.bodies[b])) << b;
  for (int b = 3; b < 6; ++b) {
    EXPECT_TRUE(sameBits(both.bodies[b], alone1.bodies[b])) << b;
    EXPECT_TRUE(sameBits(both.bodies[b], TwoChains(1.0, 1e-5).bodies[b])) << b;  // untouched
  }
  // chain 0 was solved: its anchors' relative velocities are gone
  for (int k = 0; k < 2; ++k) {
    const Joint& j = both.joints[k];
    const SolverBody &A = both.bodies[j.a], &B = both.bodies[j.b];
    const Vec3 rA(0.25, 0, 0), rB(-0.25, 0, 0);
    EXPECT_LT((B.v + B.w.cross(rB) - A.v - A.w.cross(rA)).norm(), 1e-9) << k;
  }
}
