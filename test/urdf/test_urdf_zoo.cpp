// Every robot of ../shared/urdf_zoo loads, spawns and falls plausibly: dropped 5 cm above the
// ground for 5 s of sim time it stays finite, comes to rest and no shape sinks 5 cm below the
// ground. Skipped where ../shared is absent.
#include <gtest/gtest.h>

#include <filesystem>
#include <iostream>

#include "ragdoll_sim/drop_check.hpp"
#include "ragdoll_sim/urdf_loader.hpp"

using namespace ragdoll_sim;

TEST(UrdfZoo, EveryRobotFallsAndComesToRest) {
  const std::string dir = std::string(RAGDOLL_SIM_SOURCE_DIR) + "/../shared/urdf_zoo";
  if (!std::filesystem::is_directory(dir))
    GTEST_SKIP() << "no URDF zoo at " << dir << " (the shared test material is not checked out)";
  int robots = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".urdf") continue;
    const std::string file = entry.path().filename().string();
    SCOPED_TRACE(file);
    ++robots;
    const UrdfLoadResult r = loadUrdfFile(entry.path().string());
    ASSERT_TRUE(r.ok) << r.error;
    DropSettings s;
    s.seconds = 5.0;
    const DropReport d = dropTest(r.def, s);
    std::cout << "[ zoo ] " << file << ": " << r.def.links.size() << " bodies, "
              << r.def.warnings.size() << " warnings; penetration " << 1e3 * d.max_penetration
              << " mm, anchor error " << 1e3 * d.max_anchor_error << " mm, lowest "
              << 1e3 * d.min_lowest_point << " mm, final speed " << d.final_speed << " m/s\n";
    EXPECT_TRUE(d.finite);
    EXPECT_NEAR(d.seconds, 5.0, 1e-6);
    EXPECT_LT(d.final_speed, 0.1);           // at rest
    EXPECT_GT(d.min_lowest_point, -0.05);    // nothing through the ground
    EXPECT_LT(d.lowest_point, 0.05);         // on it, not hovering
    EXPECT_LT(d.max_anchor_error, 0.02);     // joints held
  }
  EXPECT_GT(robots, 0);
}
