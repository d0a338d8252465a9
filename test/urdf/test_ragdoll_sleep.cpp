// Sleep that always comes: 64 bundled ragdolls dropped in varied orientations onto the ground
// (the node's surface) all sleep within a bound of sim time, the frictionless turns of heads,
// hands and feet included (SleepDef::island_speed), and then cost next to nothing per step.
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "ragdoll_sim/urdf_loader.hpp"
#include "../test_scale.hpp"

using namespace ragdoll_sim;

namespace {

struct Drop {
  World world;
  std::vector<Ragdoll> ragdolls;

  explicit Drop(const WorldDef& wd, int n) : world(wd) {
    const UrdfLoadResult r =
        loadUrdfFile(std::string(RAGDOLL_SIM_SOURCE_DIR) + "/urdf/ragdoll.urdf");
    EXPECT_TRUE(r.ok) << r.error;
    const Material surface{0.8, 0.6, 0.0, 0.05};  // the node's default (scene.hpp)
    BodyDef ground;
    ground.type = BodyType::Static;
    world.addShape(world.createBody(ground),
                   {Geometry::plane(Vec3::UnitZ(), 0.0), Transform(), surface});
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    const int side = int(std::ceil(std::sqrt(double(n))));
    for (int k = 0; k < n; ++k) {
      const Quat q = Quat(Eigen::AngleAxisd(2 * M_PI * u(rng), Vec3::UnitZ())) *
                     Quat(Eigen::AngleAxisd(M_PI * u(rng), Vec3::UnitX())) *
                     Quat(Eigen::AngleAxisd(2 * M_PI * u(rng), Vec3::UnitZ()));
      const Vec3 p((k % side) * 3.0, (k / side) * 3.0, 1.2 + 0.8 * u(rng));
      ragdolls.push_back(spawnRagdoll(world, r.def, {p, q.normalized()}, &surface));
    }
  }
  int awakeRagdolls() const {
    int awake = 0;
    for (const Ragdoll& r : ragdolls) {
      bool a = false;
      for (BodyId b : r.bodies) a = a || world.isAwake(b);
      awake += a;
    }
    return awake;
  }
};

}  // namespace

// (RAGDOLL_SIM_TEST_SCALE drops fewer ragdolls, 8 at least, under the same bound.)
TEST(RagdollSleep, SixtyFourDroppedRagdollsAllSleep) {
  constexpr double kDt = 1e-3;
  constexpr int kBound = 15000;  // steps: every ragdoll asleep within 15 s of sim time
  const int n = test_scale::count(64, 8);
  Drop d(WorldDef(), n);
  int steps = 0;
  while (d.world.awakeBodyCount() > 0 && steps < kBound) {
    d.world.step(kDt);
    ++steps;
  }
  EXPECT_EQ(d.awakeRagdolls(), 0) << "after " << steps << " steps";
  // Settled: what a step of n sleeping ragdolls costs (at 1 kHz, the share of a core).
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < 1000; ++i) d.world.step(kDt);
  const double us = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() * 1e3;
  std::printf("[ sleep    ] %d ragdolls asleep after %.1f s of sim time; then %.1f us per step "
              "(%.2f %% of a core at 1 kHz)\n", n, steps * kDt, us, us / 10.0);
  EXPECT_EQ(d.world.awakeBodyCount(), 0) << "a settled ragdoll woke";
}
