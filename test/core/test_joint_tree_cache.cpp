// The joint tree keeps a part's forest while its bodies and joints are those of its last build
// (joint_tree.hpp): whatever changed in between (a joint swapped or broken, a body that stops
// moving, another part built over its slots), the velocity solve after a build must give the
// same bits as a fresh tree's.
#include <gtest/gtest.h>

#include <cstring>
#include <deque>
#include <vector>

#include "joint_tree.hpp"

namespace ragdoll_sim {
namespace {

constexpr double kH = 1.0 / 180.0;

// Bodies 0..5 move (1 kg, tumbling), body 6 is static; joints: a chain 0-1-2-3-4-5 and body
// 0 hung from the static one, each anchor with its own levers.
struct Rig {
  std::vector<SolverBody> solver;
  std::vector<int> island;
  std::deque<Joint> joints;
  std::vector<Joint*> js;

  Rig() {
    for (int b = 0; b < 7; ++b) {
      SolverBody s;
      if (b < 6) {
        s.inv_mass = 1.0 / (1.0 + b);
        s.inv_inertia = Mat3::Identity() * (2.0 + 0.3 * b);
        s.inv_inertia(0, 1) = s.inv_inertia(1, 0) = 0.1 * b;
        s.v = Vec3(0.1 * b, -0.2, 0.05 * b * b);
        s.w = Vec3(1.0, 0.5 * b, -0.3);
        island.push_back(b);
      }
      solver.push_back(s);
    }
    add(6, 0);
    for (int b = 0; b < 5; ++b) add(b, b + 1);
  }
  Joint& add(int a, int b) {
    BallJointDef d;
    d.body_a.index = a;
    d.body_b.index = b;
    Joint& j = joints.emplace_back(d);
    PointPart& pt = j.anchor()->point;
    pt.rA = Vec3(0.1, 0.2 + 0.01 * a, -0.05);
    pt.rB = Vec3(-0.1, -0.15, 0.02 * b);
    js.push_back(&j);
    return j;
  }
};

IslandRange part(int b0, int b1, int j0, int j1) {
  IslandRange p;
  p.body_begin = b0, p.body_end = b1, p.joint_begin = j0, p.joint_end = j1;
  return p;
}

// Builds p on tree t and projects the velocities of a copy of the rig's bodies (the joints'
// impulses from zero); returns the bodies.
std::vector<SolverBody> solveOn(JointTree& t, Rig& rig, const IslandRange& p) {
  for (Joint& j : rig.joints) j.anchor()->point.impulse.setZero();
  std::vector<SolverBody> s = rig.solver;
  t.reserve(int(s.size()), int(rig.island.size()), int(rig.js.size()));
  t.build(p, rig.island, rig.js.data(), s);
  t.projectVelocities(p, s, rig.island, kH, 0.0);
  return s;
}

// Bit-for-bit the same velocities as a fresh tree's solve of p.
void expectAsFresh(const std::vector<SolverBody>& got, Rig& rig, const IslandRange& p) {
  JointTree fresh;
  const std::vector<SolverBody> want = solveOn(fresh, rig, p);
  for (size_t b = 0; b < got.size(); ++b) {
    EXPECT_EQ(std::memcmp(got[b].v.data(), want[b].v.data(), sizeof(Vec3)), 0) << "body " << b;
    EXPECT_EQ(std::memcmp(got[b].w.data(), want[b].w.data(), sizeof(Vec3)), 0) << "body " << b;
  }
}

const IslandRange kWhole = part(0, 6, 0, 6);

}  // namespace

TEST(JointTreeCache, SameInputsGiveSameSolve) {
  Rig rig;
  JointTree t;
  solveOn(t, rig, kWhole);
  const std::vector<SolverBody> s = solveOn(t, rig, kWhole);
  EXPECT_NE(s[5].v, rig.solver[5].v);  // the solve did something
  expectAsFresh(s, rig, kWhole);
}

// The slot of joint 3-4 takes a new joint 0-4 (another address, other bodies).
TEST(JointTreeCache, JointSwappedInItsSlot) {
  Rig rig;
  JointTree t;
  solveOn(t, rig, kWhole);
  rig.js[4] = &rig.add(0, 4);
  rig.js.pop_back();
  expectAsFresh(solveOn(t, rig, kWhole), rig, kWhole);
}

// The same joint object now between other bodies (as when a destroyed joint's memory is reused).
TEST(JointTreeCache, JointMovedToOtherBodies) {
  Rig rig;
  JointTree t;
  solveOn(t, rig, kWhole);
  rig.js[4]->a = 0;
  expectAsFresh(solveOn(t, rig, kWhole), rig, kWhole);
}

TEST(JointTreeCache, JointBroken) {
  Rig rig;
  JointTree t;
  solveOn(t, rig, kWhole);
  rig.js[2]->broken = true;
  expectAsFresh(solveOn(t, rig, kWhole), rig, kWhole);
}

TEST(JointTreeCache, AnchorTurnedSpring) {
  Rig rig;
  JointTree t;
  solveOn(t, rig, kWhole);
  rig.js[3]->spring.stiffness = 100.0;
  expectAsFresh(solveOn(t, rig, kWhole), rig, kWhole);
}

// Body 3 stops moving (an identity solver body): the chain falls into two trees.
TEST(JointTreeCache, BodyStopsMoving) {
  Rig rig;
  JointTree t;
  solveOn(t, rig, kWhole);
  rig.solver[3] = SolverBody();
  expectAsFresh(solveOn(t, rig, kWhole), rig, kWhole);
}

// Two bodies trade slots in the island's array.
TEST(JointTreeCache, BodiesReordered) {
  Rig rig;
  JointTree t;
  solveOn(t, rig, kWhole);
  std::swap(rig.island[1], rig.island[4]);
  expectAsFresh(solveOn(t, rig, kWhole), rig, kWhole);
}

// Another part built over some of the whole part's slots in between (a split island's half,
// say), then the whole part again with its old inputs.
TEST(JointTreeCache, OverlappingPartBuiltInBetween) {
  Rig rig;
  JointTree t;
  solveOn(t, rig, kWhole);
  const IslandRange tail = part(2, 6, 2, 6);  // joint 1-2 a leaf on body 2 here
  expectAsFresh(solveOn(t, rig, tail), rig, tail);
  expectAsFresh(solveOn(t, rig, kWhole), rig, kWhole);
}

// The same bodies and joints as another part of the same start, with other bounds.
TEST(JointTreeCache, SameStartOtherBounds) {
  Rig rig;
  JointTree t;
  solveOn(t, rig, kWhole);
  const IslandRange head = part(0, 4, 0, 4);
  expectAsFresh(solveOn(t, rig, head), rig, head);
  expectAsFresh(solveOn(t, rig, kWhole), rig, kWhole);
}

}  // namespace ragdoll_sim
