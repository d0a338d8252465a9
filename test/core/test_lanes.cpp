// Float lanes (lanes.hpp) against scalar float at both widths, and the run-time width choice
// (lane_width.hpp). The kernels built on them: test_wide_contacts.cpp, test_wide_points.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "lane_ops.hpp"
#include "lane_width.hpp"
#include "ragdoll_sim/state_hash.hpp"
#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"

namespace ragdoll_sim {
namespace {

using namespace lane_test;

uint32_t bitsOf(float x) {
  uint32_t b;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

// a and b for the operation tests: random values, then the cases where rounding, signed zeros,
// NaN and infinities differ between careless implementations.
struct OpInputs {
  static constexpr int kN = 256;
  alignas(32) float a[kN + 8], b[kN + 8];
  alignas(32) int32_t index[kN];
  OpInputs() {
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-4.0f, 4.0f);
    for (int i = 0; i < kN + 8; ++i) a[i] = u(rng), b[i] = u(rng);
    const float inf = std::numeric_limits<float>::infinity();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    const float special[] = {0.0f, -0.0f, 1.0f, -1.0f, inf, -inf, nan, 1e-40f, -3e-39f, 3.4e38f};
    int i = 0;
    for (float x : special)
      for (float y : special) a[i] = x, b[i] = y, i += 1;  // 100 pairs, then equal values
    for (int k = 0; k < 16; ++k, ++i) b[i] = a[i];
    for (int k = 0; k < kN; ++k) index[k] = (k * 37) % 11 == 3 ? -1 : (k * 53) % kN;
  }
};

float expected(LaneOp op, const OpInputs& in, int i, int width) {
  const float x = in.a[i], y = in.b[i];
  const int c = i - i % width;  // first element of the chunk
  switch (op) {
    case kAdd: return x + y;
    case kSub: return x - y;
    case kMul: return x * y;
    case kDiv: return x / y;
    case kMin: return x < y ? x : y;
    case kMax: return x > y ? x : y;
    case kLt: return x < y;
    case kLe: return x <= y;
    case kGt: return x > y;
    case kGe: return x >= y;
    case kEq: return x == y;
    case kSelect: return x < y ? x : y;
    case kAnd: return x < y && x > 0.0f;
    case kOr: return x < y || x > 0.0f;
    case kAndNot: return x < y && !(x > 0.0f);
    case kAny:
    case kAll: {
      bool any = false, all = true;
      for (int l = c; l < c + width; ++l) {
        const bool t = in.a[l] < in.b[l];
        any = any || t;
        all = all && t;
      }
      return op == kAny ? any : all;
    }
    case kSplat: return in.a[c];
    case kZero: return 0.0f;
    case kLoadU: return in.a[i + 1];
    case kLane: return x;
    case kGather: return in.index[i] >= 0 ? in.a[in.index[i]] : 0.0f;
    default: return 0.0f;
  }
}

// Every operation of the lanes `which` (lane_ops.hpp) against scalar float, bit for bit.
void checkOps(bool (*run)(int, LaneOp, const float*, const float*, const int32_t*, float*, int),
              int which, int width) {
  static const OpInputs in;
  for (int op = 0; op < kOpCount; ++op) {
    alignas(32) float out[OpInputs::kN + 8] = {};
    if (op == kScatter) {
      // Elements no index names keep this value (the indices are distinct).
      for (int i = 0; i < OpInputs::kN; ++i) out[i] = -7.0f;
    }
    ASSERT_TRUE(run(which, LaneOp(op), in.a, in.b, in.index, out, OpInputs::kN));
    alignas(32) float want[OpInputs::kN + 8] = {};
    if (op == kScatter) {
      for (int i = 0; i < OpInputs::kN; ++i) want[i] = -7.0f;
      for (int l = 0; l < OpInputs::kN; ++l)
        if (in.index[l] >= 0) want[in.index[l]] = in.a[l];
    } else {
      for (int i = 0; i < OpInputs::kN; ++i) want[op == kLoadU ? i + 1 : i] = expected(LaneOp(op), in, i, width);
    }
    for (int i = 0; i < OpInputs::kN + 1; ++i) {
      if (std::isnan(want[i]) && std::isnan(out[i])) continue;
      ASSERT_EQ(bitsOf(want[i]), bitsOf(out[i]))
          << "op " << op << " element " << i << ": a " << in.a[i] << " b " << in.b[i]
          << " want " << want[i] << " got " << out[i];
    }
  }
}

TEST(Lanes, PortableArraysMatchScalarFloat) {
  checkOps(runW4File, 0, 4);
  checkOps(runW4File, 1, 8);
}

TEST(Lanes, Sse2MatchesScalarFloat) { checkOps(runW4File, 2, 4); }

TEST(Lanes, Avx2MatchesScalarFloat) {
  if (!cpuHasAvx2()) GTEST_SKIP() << "no AVX2 on this CPU or in this build";
  checkOps(runW8File, 3, 8);
  checkOps(runW8File, 2, 4);  // the SSE2 lanes in VEX encoding
  checkOps(runW8File, 1, 8);
}

TEST(Lanes, ChooseLaneWidth) {
  // Automatic: the widest the CPU runs.
  EXPECT_EQ(chooseLaneWidth(0, nullptr, true), 8);
  EXPECT_EQ(chooseLaneWidth(0, nullptr, false), 4);
  EXPECT_EQ(chooseLaneWidth(0, "", true), 8);
  // The variable, and 8 falls back to 4 without AVX2.
  EXPECT_EQ(chooseLaneWidth(0, "4", true), 4);
  EXPECT_EQ(chooseLaneWidth(0, "8", true), 8);
  EXPECT_EQ(chooseLaneWidth(0, "8", false), 4);
  // An explicit request wins over the variable.
  EXPECT_EQ(chooseLaneWidth(4, "8", true), 4);
  EXPECT_EQ(chooseLaneWidth(8, "4", true), 8);
  EXPECT_EQ(chooseLaneWidth(8, nullptr, false), 4);
  // Refusals name the value.
  try {
    chooseLaneWidth(0, "16", true);
    ADD_FAILURE() << "RAGDOLL_SIM_LANES=16 accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("RAGDOLL_SIM_LANES=16"), std::string::npos) << e.what();
  }
  EXPECT_THROW(chooseLaneWidth(0, "8x", true), std::invalid_argument);
  EXPECT_THROW(chooseLaneWidth(2, nullptr, true), std::invalid_argument);
  // Automatic only when nothing forces a width.
  EXPECT_TRUE(laneWidthAutomatic(0, nullptr));
  EXPECT_TRUE(laneWidthAutomatic(0, ""));
  EXPECT_FALSE(laneWidthAutomatic(0, "4"));
  EXPECT_FALSE(laneWidthAutomatic(0, "8"));
  for (const int lanes : {1, 4, 8}) EXPECT_FALSE(laneWidthAutomatic(lanes, nullptr)) << lanes;
}

TEST(Lanes, ChooseLaneWidthReadsTheEnvironment) {
  const char* old = std::getenv("RAGDOLL_SIM_LANES");
  const std::string saved = old ? old : "";
  setenv("RAGDOLL_SIM_LANES", "4", 1);
  EXPECT_EQ(chooseLaneWidth(0), 4);
  setenv("RAGDOLL_SIM_LANES", "8", 1);
  EXPECT_EQ(chooseLaneWidth(0), cpuHasAvx2() ? 8 : 4);
  setenv("RAGDOLL_SIM_LANES", "five", 1);
  EXPECT_THROW(chooseLaneWidth(0), std::invalid_argument);
  unsetenv("RAGDOLL_SIM_LANES");
  EXPECT_EQ(chooseLaneWidth(0), cpuHasAvx2() ? 8 : 4);
  if (old) setenv("RAGDOLL_SIM_LANES", saved.c_str(), 1);
}

// The double-lane kernels' runs: the widest lanes the CPU runs, every item once and in order,
// and the last run's spare lanes holding the last item (a kernel's lanes write what that item
// alone gives, twice).
TEST(Lanes, ByLaneWidthFillsTheLastRunWithTheLastItem) {
  const int width = cpuHasAvx2() ? 4 : 2;
  for (int n = 0; n <= 11; ++n) {
    std::vector<int> items;
    for (int i = 0; i < n; ++i) items.push_back(100 + i);
    std::vector<int> seen;
    int runs = 0;
    byLaneWidth(items.data(), n, [&](int w, const int* run, int count) {
      EXPECT_EQ(w, width) << n;
      EXPECT_GT(count, 0) << n;
      EXPECT_EQ(count % w, 0) << n;
      seen.insert(seen.end(), run, run + count);
      ++runs;
    });
    ASSERT_EQ(int(seen.size()), (n + width - 1) / width * width) << n;
    EXPECT_LE(runs, 2) << n;
    for (int i = 0; i < int(seen.size()); ++i)
      EXPECT_EQ(seen[i], 100 + std::min(i, n - 1)) << "n " << n << ", lane " << i;
  }
}

// The World says which width it runs, from its settings and as they change.
TEST(Lanes, WorldLaneWidthFollowsTheSettings) {
  const int widest = chooseLaneWidth(0);
  WorldDef def;
  def.solver.lanes = 1;
  World w(def);
  EXPECT_EQ(w.laneWidth(), 1);
  SolverSettings s = w.def().solver;
  for (const int lanes : {0, 4, 8, 1}) {
    s.lanes = lanes;
    w.setSolverSettings(s);
    EXPECT_EQ(w.laneWidth(), lanes == 0 ? widest : lanes == 8 && !cpuHasAvx2() ? 4 : lanes)
        << "lanes " << lanes;
    EXPECT_EQ(w.lanesAutomatic(), lanes == 0 && laneWidthAutomatic(0)) << "lanes " << lanes;
  }
  s.lanes = 2;
  EXPECT_THROW(w.setSolverSettings(s), std::invalid_argument);
  EXPECT_EQ(w.laneWidth(), 1);  // unchanged
}

// The state after boxes, each its own island, slide and spin to rest on the ground.
uint64_t boxesHash(int boxes, int lanes) {
  using test::addBox;
  using test::addGround;
  WorldDef def;
  def.solver.lanes = lanes;
  def.sleep.enabled = false;
  World w(def);
  addGround(w);
  const Vec3 half(0.1, 0.15, 0.05);
  for (int k = 0; k < boxes; ++k) {
    const Vec3 x(0.5 * (k % 6), 0.5 * (k / 6), 0.052);
    const BodyId b = addBox(w, half, 1.0 + 0.05 * k, x);
    w.setBodyState(b, Transform(x, Quat::Identity()), Vec3(0.3 + 0.01 * k, -0.2, 0.0),
                   Vec3(0.0, 0.0, 1.0 + 0.1 * k));
  }
  for (int i = 0; i < 300; ++i) w.step(1e-3);
  return hashStates(w);
}

// With the width automatic, a step whose islands hold fewer than World::kLanesMinBodies awake
// bodies solves in double rows (as lanes 1), one with that many in the lanes (as 4 and 8); a forced
// width runs the lanes at any size. The rows differ (the hashes of 1 and 8 are not equal), so
// each comparison tells which ran.
TEST(Lanes, AutomaticWidthSolvesFewBodiesInDoubleRows) {
  const char* old = std::getenv("RAGDOLL_SIM_LANES");
  const std::string saved = old ? old : "";
  unsetenv("RAGDOLL_SIM_LANES");
  for (const int boxes : {World::kLanesMinBodies - 1, World::kLanesMinBodies}) {
    const uint64_t automatic = boxesHash(boxes, 0), wide = boxesHash(boxes, 8),
                   rows = boxesHash(boxes, 1);
    EXPECT_NE(wide, rows) << boxes << " boxes";
    EXPECT_EQ(automatic, boxes < World::kLanesMinBodies ? rows : wide) << boxes << " boxes";
    EXPECT_EQ(boxesHash(boxes, 4), wide) << boxes << " boxes";
  }
  // RAGDOLL_SIM_LANES forces the lanes too.
  setenv("RAGDOLL_SIM_LANES", "4", 1);
  EXPECT_EQ(boxesHash(World::kLanesMinBodies - 1, 0), boxesHash(World::kLanesMinBodies - 1, 8));
  unsetenv("RAGDOLL_SIM_LANES");
  if (old) setenv("RAGDOLL_SIM_LANES", saved.c_str(), 1);
}

}  // namespace
}  // namespace ragdoll_sim
