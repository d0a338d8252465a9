// Each thread solves a run of consecutive islands of about equal work (World::Impl::
// partitionIslands). Islands of unequal size, solved by 1 thread and by 2, 3, 5 and 16: an
// island left out of the runs would not move, one solved twice would move twice, and either
// changes the poses against one thread. The threads after the first solve in solver bodies of
// their own (SolveData::team_bodies); the contact reports, which read the step's motion from the
// World's, are the same as on one thread.
#include <gtest/gtest.h>

#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "constants.hpp"
#include "report_test_util.hpp"
#include "scene_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {

// 9 jointed chains of 2..10 boxes, 1.5 m apart (9 islands, 54 bodies: enough to be solved in
// parallel, kParallelMin), dropped on the ground, their boxes moving sideways against each other;
// every other chain bounces (restitution, applied per island after its substeps).
struct Chains {
  static constexpr int kChains = 9;
  static_assert(kChains * (kChains + 3) / 2 >= kParallelMin, "the runs must go to threads");
  std::unique_ptr<World> world;
  std::vector<BodyId> boxes;

  explicit Chains(int threads) {
    WorldDef def;
    def.sleep.enabled = false;
    def.threads = threads;
    world = std::make_unique<World>(def);
    addGround(*world);
    const Vec3 half(0.1, 0.05, 0.05);
    Material bouncy;
    bouncy.restitution = 0.5;
    for (int c = 0; c < kChains; ++c)
      for (int k = 0; k < 2 + c; ++k) {
        const Vec3 pos(0.2 * k, 1.5 * c, 0.4 + 0.02 * k);
        const BodyId b = addBody(*world, Geometry::box(half), 1.0, boxInertia(half, 1.0),
                                 Transform(pos, Quat::Identity()), c % 2 ? bouncy : Material(),
                                 Vec3(0.3 * c, k % 2 ? 0.2 : -0.2, 0));
        if (k > 0) chainLink(*world, boxes.back(), b, 0.1);
        boxes.push_back(b);
      }
  }
};

}  // namespace

TEST(IslandRuns, EveryIslandSolvedOnceForAnyThreadCount) {
  Chains one(1);
  for (int i = 0; i < 700; ++i) one.world->step(1e-3);
  // each chain fell and landed (its boxes rest 5 cm above the ground; they started >= 40 cm)
  for (size_t k = 0; k < one.boxes.size(); ++k)
    EXPECT_LT(one.world->bodyPose(one.boxes[k]).p.z(), 0.1) << "box " << k;
  for (const int threads : {2, 3, 5, 16}) {
    Chains many(threads);
    for (int i = 0; i < 700; ++i) many.world->step(1e-3);
    for (const BodyId& b : one.boxes) {
      const Transform x1 = one.world->bodyPose(b), xn = many.world->bodyPose(b);
      ASSERT_EQ(std::memcmp(x1.p.data(), xn.p.data(), sizeof(double) * 3), 0)
          << threads << " threads, body " << b.index;
      ASSERT_EQ(std::memcmp(x1.q.coeffs().data(), xn.q.coeffs().data(), sizeof(double) * 4), 0)
          << threads << " threads, body " << b.index;
    }
  }
}

TEST(IslandRuns, ContactReportsOfTheTeamThreadsIslandsAsOnOneThread) {
  Chains one(1), two(2);
  int reported = 0, moving = 0;  // reports, and points separating or approaching
  for (int i = 1; i <= 400; ++i) {
    one.world->step(1e-3);
    two.world->step(1e-3);
    if (i % 50 != 0) continue;
    expectSameContactReports(*one.world, *two.world, "step " + std::to_string(i), reported,
                             moving);
    if (HasFatalFailure()) return;
  }
  EXPECT_GT(reported, 40);
  EXPECT_GT(moving, 40);
}
