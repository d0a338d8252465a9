// rostest: launch/stairs.launch drops the ragdoll on the top landing (z = 1.44 m, its edge at
// x = 0.28 m) of worlds/stairs.world with a push towards the stairs; after 6 s of sim time its
// root link is down the stairs (beyond the landing's edge, more than 0.5 m lower), and every
// link's state is finite.
#include <gtest/gtest.h>

#include <cstdio>

#include "node_log.hpp"
#include "sim_client.hpp"

using namespace ragdoll_test;

TEST(Stairs, RagdollTumblesDown) {
  SimClient sim("/ragdoll_sim");
  ASSERT_TRUE(sim.waitUp(60.0)) << "node did not come up";
  std::string root;
  const std::vector<LinkMass> links = urdfLinks(&root);
  ASSERT_FALSE(root.empty());
  const auto start = sim.link("", root);
  ASSERT_TRUE(start.success) << start.message;
  EXPECT_GT(linear(start).x(), 1.0) << "no push at start-up";
  for (int k = 0; k < 12; ++k) ASSERT_TRUE(sim.step(500).success);
  const auto end = sim.link("", root);
  ASSERT_TRUE(end.success) << end.message;
  std::printf("[figure] stairs: root from (%.3f, %.3f) to (%.3f, %.3f) (x, z) in 6 s\n",
              position(start).x(), position(start).z(), position(end).x(), position(end).z());
  EXPECT_GT(position(end).x(), 0.28 + 0.3);
  EXPECT_LT(position(end).z(), position(start).z() - 0.5);
  for (const LinkMass& l : links) {
    const auto s = sim.link("", l.name);
    if (!s.success) continue;  // a ball joint's dummy link
    EXPECT_TRUE(position(s).allFinite() && linear(s).allFinite()) << l.name;
  }
}

int main(int argc, char** argv) {
  return ragdoll_test::runRosTests(argc, argv, "stairs_test", 1, [] {}, [] {});
}
