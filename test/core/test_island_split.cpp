// A big island is split in two halves of whole limbs plus the boundary contacts between them
// (island_split.hpp). The splitter's halves and boundary on a small graph; then a world whose
// one island is split: momentum is conserved through the boundary, a bounce across the cut
// reaches both halves, the chains do not sink into each other, and 1 and 2 threads give the
// same poses and contact reports.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>

#include "island_split.hpp"
#include "report_test_util.hpp"
#include "scene_util.hpp"
#include "world_tuning.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {

Contact contactBetween(int a, int b) {
  Contact c;
  c.body_a = a;
  c.body_b = b;
  return c;
}

// Limbs of three bodies {1,2,3} {4,5,6} ...: two joints each, 1-2, 2-3, 4-5, ...
std::vector<Joint> limbJoints(int limbs) {
  std::vector<Joint> joints(2 * limbs);
  for (int limb = 0; limb < limbs; ++limb)
    for (int k = 0; k < 2; ++k) {
      Joint& j = joints[2 * limb + k];
      j.a = 1 + 3 * limb + k;
      j.b = j.a + 1;
    }
  return joints;
}

}  // namespace

// Body 0 is static (outside the island). Limbs of three bodies: {1,2,3} {4,5,6} {7,8,9}
// {10,11,12} {13,14,15}, touching in a row; the first half grows from limb 0 until it holds
// half the bodies (limbs 0..2: 9 of 15), so only the contact between limbs 2 and 3 is cut.
TEST(IslandSplitter, HalvesAreWholeLimbsAndTheBoundaryIsTheCut) {
  std::vector<Joint> joints = limbJoints(5);
  // listed from the far end, so the halves must regroup them
  std::vector<Joint*> js;
  for (int k = int(joints.size()) - 1; k >= 0; --k) js.push_back(&joints[k]);
  const std::vector<Contact> all = {
      contactBetween(13, 12),  // 0: limbs 4-3
      contactBetween(0, 15),   // 1: ground - limb 4
      contactBetween(9, 10),   // 2: limbs 2-3, the cut
      contactBetween(7, 9),    // 3: inside limb 2
      contactBetween(6, 7),    // 4: limbs 1-2
      contactBetween(1, 0),    // 5: limb 0 - ground
      contactBetween(3, 5),    // 6: limbs 0-1
  };
  std::vector<int> contacts = {0, 1, 2, 3, 4, 5, 6};
  std::vector<int> bodies;  // ascending, as World lists an island's bodies
  for (int b = 1; b <= 15; ++b) bodies.push_back(b);

  IslandSplitter splitter;
  IslandHalves h;
  ASSERT_TRUE(splitter.split(bodies.data(), 15, js.data(), int(js.size()), contacts.data(), 7,
                             all, 16, h));
  EXPECT_EQ(h.body_mid, 9);
  EXPECT_EQ(bodies, (std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15}));
  // Stable: each half keeps the given (descending) order.
  EXPECT_EQ(h.joint_mid, 6);
  EXPECT_EQ(js[0]->a, 8);
  EXPECT_EQ(js[6]->a, 14);
  for (int k = 0; k < int(js.size()); ++k)
    EXPECT_EQ(k < h.joint_mid, js[k]->a < 10) << "joint " << js[k]->a << "-" << js[k]->b;
  EXPECT_EQ(h.contact_mid, 4);
  EXPECT_EQ(h.boundary_begin, 6);
  EXPECT_EQ(h.boundary_mid, 7);  // the one boundary contact is group 0
  EXPECT_EQ(contacts, (std::vector<int>{3, 4, 5, 6, 0, 1, 2}));

  // The splitter leaves no state behind: a second island of other bodies splits the same way.
  std::vector<int> again = bodies;
  std::vector<int> contacts2 = contacts;
  ASSERT_TRUE(splitter.split(again.data(), 15, js.data(), int(js.size()), contacts2.data(), 7,
                             all, 16, h));
  EXPECT_EQ(again, bodies);
  EXPECT_EQ(contacts2, contacts);
}

// Limbs {1,2,3} {4,5,6} {7,8,9} {10,11,12}: the first half is limbs 0 and 1. Three contacts
// cross the cut; two share body 5, so they form one boundary component and stay together, in
// their order, in group 0; the third goes to group 1 (fewer contacts). The groups share no
// body, which is what lets two threads solve them at once.
TEST(IslandSplitter, BoundaryGroupsAreWholeComponentsSharingNoBody) {
  std::vector<Joint> joints = limbJoints(4);
  std::vector<Joint*> js;
  for (Joint& j : joints) js.push_back(&j);
  const std::vector<Contact> all = {
      contactBetween(2, 4),    // 0: limbs 0-1
      contactBetween(5, 7),    // 1: limbs 1-2, boundary, shares body 5 with 3
      contactBetween(1, 10),   // 2: limbs 0-3, boundary
      contactBetween(8, 5),    // 3: limbs 2-1, boundary
      contactBetween(11, 12),  // 4: inside limb 3
  };
  std::vector<int> contacts = {0, 1, 2, 3, 4};
  std::vector<int> bodies;
  for (int b = 1; b <= 12; ++b) bodies.push_back(b);
  IslandSplitter splitter;
  IslandHalves h;
  ASSERT_TRUE(splitter.split(bodies.data(), 12, js.data(), int(js.size()), contacts.data(), 5,
                             all, 13, h));
  EXPECT_EQ(h.body_mid, 6);
  EXPECT_EQ(h.boundary_begin, 2);
  EXPECT_EQ(h.boundary_mid, 4);
  EXPECT_EQ(contacts, (std::vector<int>{0, 4, 1, 3, 2}));
  const auto touches = [&](int begin, int end, int body) {
    for (int k = begin; k < end; ++k)
      if (all[contacts[k]].body_a == body || all[contacts[k]].body_b == body) return true;
    return false;
  };
  for (int body = 1; body <= 12; ++body)
    EXPECT_FALSE(touches(h.boundary_begin, h.boundary_mid, body) && touches(h.boundary_mid, 5, body))
        << "body " << body << " in both groups";
}

TEST(IslandSplitter, OneLimbIsNotSplit) {
  std::vector<Joint> joints(3);
  std::vector<Joint*> js;
  for (int k = 0; k < 3; ++k) joints[k].a = k, joints[k].b = k + 1, js.push_back(&joints[k]);
  std::vector<int> bodies = {3, 1, 2, 0};
  const std::vector<Contact> all = {contactBetween(0, 2)};
  std::vector<int> contacts = {0};
  IslandSplitter splitter;
  IslandHalves h;
  EXPECT_FALSE(splitter.split(bodies.data(), 4, js.data(), 3, contacts.data(), 1, all, 4, h));
  EXPECT_EQ(bodies, (std::vector<int>{3, 1, 2, 0}));
  EXPECT_EQ(js[0], &joints[0]);
}

namespace {

// 8 chains of 8 boxes (ball joints between the faces) side by side, touching, in zero
// gravity: one island of 64 bodies, which World splits. Alternate chains move against each
// other and spin, so the boundary contacts carry load.
struct Raft {
  static constexpr int kChains = 8, kLinks = 8;
  static constexpr double kHalf = 0.1;
  std::unique_ptr<World> world;
  std::vector<BodyId> boxes;

  explicit Raft(int threads, int relax = SolverSettings().contact_relax_iterations) {
    WorldDef def;
    def.gravity.setZero();
    def.sleep.enabled = false;
    def.threads = threads;
    def.solver.contact_relax_iterations = relax;
    world = std::make_unique<World>(def);
    add(Vec3::Zero());
  }

  // Another raft like it, moved by offset (its own island when far enough).
  void add(const Vec3& offset) {
    const Vec3 half(kHalf, kHalf, kHalf);
    // Chains 1-2, 3-4 and 5-6 meet at 1.6 m/s, above the restitution threshold; 3-4 is the
    // cut (the first half grows from chain 0 to 32 bodies), whose bounce must reach both
    // halves' bodies before they take their velocities.
    Material bouncy;
    bouncy.restitution = 0.5;
    for (int c = 0; c < kChains; ++c)
      for (int k = 0; k < kLinks; ++k) {
        const Vec3 pos = offset + Vec3(2 * kHalf * k, 2 * kHalf * c, 0);
        const Vec3 v(0, c % 2 ? 0.8 : -0.8, 0.05 * c);
        const BodyId b = addBody(*world, Geometry::box(half), 1.0 + 0.1 * k, boxInertia(half, 1.0 + 0.1 * k),
                                 Transform(pos, Quat::Identity()), bouncy, v);
        if (k > 0) chainLink(*world, boxes.back(), b, kHalf);
        boxes.push_back(b);
      }
  }

  // Steps both rafts' worlds once (1 ms); returns the deepest overlap in one's after it.
  static double stepBoth(Raft& one, Raft& two) {
    one.world->step(1e-3);
    two.world->step(1e-3);
    return one.deepest();
  }

  // Deepest overlap between boxes of different chains, from the contacts.
  double deepest() const {
    double d = 0;
    for (const ContactInfo& c : world->contacts()) d = std::max(d, -c.separation);
    return d;
  }
};

}  // namespace

TEST(SplitIsland, MomentumConservedChainsStayApartSameForOneAndTwoThreads) {
  Raft one(1), two(2);
  const Vec3 p0 = one.world->linearMomentum();
  double deepest = 0;
  for (int i = 0; i < 400; ++i) {
    deepest = std::max(deepest, Raft::stepBoth(one, two));
    if (i > 0) continue;
    const IslandCounters n = one.world->islandCounters();
    EXPECT_EQ(n.islands, 1);
    EXPECT_EQ(n.split_islands, 1);
    EXPECT_EQ(n.largest_island, 64);
    // The halves and the boundary's groups are batches of their own, the same on two threads;
    // the 56 ball joints are all in the lanes.
    const IslandCounters m = two.world->islandCounters();
    EXPECT_GE(n.lane_batches, 3);
    EXPECT_EQ(n.joint_lane_rows, Raft::kChains * (Raft::kLinks - 1));
    EXPECT_EQ(m.lane_batches, n.lane_batches);
    EXPECT_EQ(m.joint_lanes, n.joint_lanes);
    EXPECT_EQ(m.contact_lane_rows, n.contact_lane_rows);
    EXPECT_EQ(m.contact_lanes, n.contact_lanes);
    EXPECT_GT(n.contact_lane_rows, 0);
    // After the first step chains 3 and 4 (across the cut) bounce apart at 0.5 x 1.6 m/s.
    const auto chainVy = [&](int c) {
      double vy = 0;
      for (int k = 0; k < Raft::kLinks; ++k)
        vy += one.world->bodyState(one.boxes[c * Raft::kLinks + k]).linear_velocity.y();
      return vy / Raft::kLinks;
    };
    EXPECT_NEAR(chainVy(4) - chainVy(3), 0.8, 0.1);
  }
  int across = 0;  // contacts between different chains: the island is one
  for (const ContactInfo& c : one.world->contacts())
    across += c.body_a.index / Raft::kLinks != c.body_b.index / Raft::kLinks;
  EXPECT_GT(across, Raft::kChains);
  const Vec3 p1 = one.world->linearMomentum();
  EXPECT_LT((p1 - p0).norm(), 1e-9 * p0.norm()) << p0.transpose() << " -> " << p1.transpose();
  EXPECT_LT(deepest, 0.005);
  for (const BodyId& b : one.boxes) {
    const Transform x1 = one.world->bodyPose(b), x2 = two.world->bodyPose(b);
    ASSERT_EQ(std::memcmp(x1.p.data(), x2.p.data(), sizeof(double) * 3), 0) << "body " << b.index;
    ASSERT_EQ(std::memcmp(x1.q.coeffs().data(), x2.q.coeffs().data(), sizeof(double) * 4), 0);
  }
  std::printf("[ split    ] 64 boxes, one island: %d contacts across chains, |dp|/|p| = %.1e, "
              "deepest overlap %.2e m\n",
              across, (p1 - p0).norm() / p0.norm(), deepest);
}

// Every sweep of a split island solves every contact once, the boundary's too, whatever the
// number of relax sweeps, and 1 and 2 threads agree bit for bit.
TEST(SplitIsland, EverySweepSolvesEveryContactOnceSameForOneAndTwoThreads) {
  for (const int relax : {0, 1, 2, 3, 5}) {
    Raft one(1, relax), two(2, relax);
    const int substeps = one.world->def().solver.substeps;
    int split_steps = 0;
    for (int i = 0; i < 100; ++i) {
      const int64_t before = WorldInternals::contactSweeps(*one.world);
      Raft::stepBoth(one, two);
      const IslandCounters n = one.world->islandCounters();
      split_steps += n.split_islands;
      EXPECT_EQ(WorldInternals::contactSweeps(*one.world) - before,
                int64_t(substeps) * (1 + relax) * n.contacts)
          << "relax " << relax << ", step " << i;
      EXPECT_EQ(WorldInternals::contactSweeps(*two.world), WorldInternals::contactSweeps(*one.world));
    }
    EXPECT_GT(split_steps, 10) << "relax " << relax;
    for (const BodyId& b : one.boxes) {
      const Transform x1 = one.world->bodyPose(b), x2 = two.world->bodyPose(b);
      ASSERT_EQ(std::memcmp(x1.p.data(), x2.p.data(), sizeof(double) * 3), 0)
          << "relax " << relax << ", body " << b.index;
      ASSERT_EQ(std::memcmp(x1.q.coeffs().data(), x2.q.coeffs().data(), sizeof(double) * 4), 0);
    }
  }
}

// On two threads each half is solved in solver bodies of its thread's own and the boundary in a
// third array (SolveData::split_shared); the contact reports read the step's motion from the
// World's, and a boundary body's velocity and pose go back and forth between the arrays around
// every boundary phase: the reports are those of one thread, bit for bit.
TEST(SplitIsland, ContactReportsAsOnOneThread) {
  Raft one(1), two(2);
  int reported = 0, moving = 0;  // reports of split steps, and their points that move
  int split_steps = 0;
  for (int i = 1; i <= 100; ++i) {
    Raft::stepBoth(one, two);
    if (two.world->islandCounters().split_islands != 1) continue;
    ++split_steps;
    expectSameContactReports(*one.world, *two.world, "step " + std::to_string(i), reported,
                             moving);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(split_steps, 10);
  EXPECT_GT(reported, 500);
  EXPECT_GT(moving, 500);
  std::printf("[ split    ] %d split steps, %d reports, %d moving points\n", split_steps, reported,
              moving);
}

namespace {

// Three spinning jointed chains of 3, 4 and 5 boxes far from anything: islands of their own.
std::vector<BodyId> addChains(World& world) {
  std::vector<BodyId> boxes;
  const Vec3 half(0.1, 0.05, 0.05);
  for (int c = 0; c < 3; ++c)
    for (int k = 0; k < 3 + c; ++k) {
      const Vec3 pos(0.2 * k, 10.0 + 2.0 * c, 0);
      const Transform pose(pos, Quat::Identity());
      const Vec3 v(0.1 * c, k % 2 ? 0.5 : -0.5, 0.3);
      const BodyId b = addBody(world, Geometry::box(half), 1.0 + 0.2 * k,
                               boxInertia(half, 1.0 + 0.2 * k), pose, Material(), v);
      world.setBodyState(b, pose, v, Vec3(0, 0, 2.0 + c));
      if (k > 0) chainLink(world, boxes.back(), b, 0.1);
      boxes.push_back(b);
    }
  return boxes;
}

bool samePose(const World& a, BodyId ia, const World& b, BodyId ib) {
  const Transform x = a.bodyPose(ia), y = b.bodyPose(ib);
  return std::memcmp(x.p.data(), y.p.data(), sizeof(double) * 3) == 0 &&
         std::memcmp(x.q.coeffs().data(), y.q.coeffs().data(), sizeof(double) * 4) == 0;
}

}  // namespace

// With a split island in the world, the other islands are solved along with its halves
// (World::Impl::attachToSplitHalves), in lockstep with the halves' sweeps. Each island must
// still be solved exactly once and exactly as alone: the chains next to the raft end bitwise
// where they end in a world without it, and the raft where it ends without them, on 1 and 2
// threads (an island solved twice, or not at all, or a step of it skipped, moves it), and on 3
// (the chains then only fill the lighter half, the rest go to the runs).
TEST(SplitIsland, OtherIslandsGoAlongWithTheHalvesUnchanged) {
  for (const int threads : {1, 2, 3}) {
    Raft with(threads), raft_alone(threads);
    const std::vector<BodyId> chains = addChains(*with.world);
    WorldDef def;
    def.gravity.setZero();
    def.sleep.enabled = false;
    def.threads = threads;
    // alone the chains are too few bodies for the automatic width's lanes (World::kLanesMinBodies)
    def.solver.lanes = 8;
    World chains_world(def);
    const std::vector<BodyId> chains_alone = addChains(chains_world);
    for (int i = 0; i < 300; ++i) {
      with.world->step(1e-3);
      raft_alone.world->step(1e-3);
      chains_world.step(1e-3);
    }
    for (size_t k = 0; k < chains.size(); ++k) {
      EXPECT_TRUE(samePose(*with.world, chains[k], chains_world, chains_alone[k]))
          << "chain box " << k << ", threads " << threads;
      EXPECT_GT(with.world->bodyPose(chains[k]).p.z(), 0.05) << "chain box " << k << " moved";
    }
    for (size_t k = 0; k < with.boxes.size(); ++k)
      ASSERT_TRUE(samePose(*with.world, with.boxes[k], *raft_alone.world, raft_alone.boxes[k]))
          << "raft box " << k << ", threads " << threads;
  }
}

// An island is split only when it holds more than half the awake work: otherwise the threads
// balance on whole islands, and a split island would take all the others through its sweeps in
// lockstep. Three or four rafts far apart hold about a third or a quarter each: none is split,
// and the result is the same for 1 and 2 threads. Alone, a raft is split (the test above).
// (Two equal rafts are the edge: as their contact counts drift apart, one holds more.)
TEST(SplitIsland, OnlyAnIslandWithMostOfTheWorkIsSplit) {
  for (const int rafts : {3, 4}) {
    Raft one(1), two(2);
    for (int k = 1; k < rafts; ++k) {
      one.add(Vec3(0, 0, 10.0 * k));
      two.add(Vec3(0, 0, 10.0 * k));
    }
    const Vec3 p0 = one.world->linearMomentum();
    double deepest = 0;
    for (int i = 0; i < 300; ++i) {
      deepest = std::max(deepest, Raft::stepBoth(one, two));
      const IslandCounters n = two.world->islandCounters();
      ASSERT_GE(n.islands, rafts) << "step " << i;  // a raft may come apart in two
      ASSERT_EQ(n.split_islands, 0) << "step " << i;
      if (i == 0) {
        ASSERT_EQ(n.largest_island, 64);
      }
    }
    EXPECT_LT((one.world->linearMomentum() - p0).norm(), 1e-9 * p0.norm());
    EXPECT_LT(deepest, 0.005);
    for (const BodyId& b : one.boxes)
      ASSERT_TRUE(samePose(*one.world, b, *two.world, b)) << "body " << b.index;
  }
}
