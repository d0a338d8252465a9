// Float lanes (lanes.hpp), the normal-row kernel at both widths (normal_row_wide.inc) and the
// run-time width choice (lane_width.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <vector>

#include "lane_ops.hpp"
#include "lane_rows.hpp"
#include "lane_width.hpp"

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

// The kernel's formula in plain scalar float, operation by operation as normal_row_wide.inc
// orders them, one row after the other.
void solveRowsScalarFloat(std::vector<NormalRowBlock>& blocks, BodyVelocitiesF b,
                          const NormalRowParams& p) {
  auto fmax = [](float x, float y) { return x > y ? x : y; };
  auto fmin = [](float x, float y) { return x < y ? x : y; };
  for (NormalRowBlock& k : blocks) {
    for (int l = 0; l < kRowBlock; ++l) {
      const int ia = k.body_a[l], ib = k.body_b[l];
      float vA[3], wA[3], vB[3], wB[3];
      for (int c = 0; c < 3; ++c) {
        vA[c] = ia >= 0 ? b.v[c][ia] : 0.0f;
        wA[c] = ia >= 0 ? b.w[c][ia] : 0.0f;
        vB[c] = ib >= 0 ? b.v[c][ib] : 0.0f;
        wB[c] = ib >= 0 ? b.w[c][ib] : 0.0f;
      }
      const float s = k.separation[l];
      float soft_bias = 0.0f, ms = 1.0f, is = 0.0f;
      if (p.use_bias) {
        soft_bias = fmax(p.bias_rate * fmin(s + p.linear_slop, 0.0f), -p.max_push_velocity);
        ms = p.mass_scale;
        is = p.impulse_scale;
      }
      const float bias = s > 0.0f ? s * p.inv_h : soft_bias;
      const float dn = k.n[0][l] * (vB[0] - vA[0]) + k.n[1][l] * (vB[1] - vA[1]) +
                       k.n[2][l] * (vB[2] - vA[2]);
      const float db = wB[0] * k.ang_b[0][l] + wB[1] * k.ang_b[1][l] + wB[2] * k.ang_b[2][l];
      const float da = wA[0] * k.ang_a[0][l] + wA[1] * k.ang_a[1][l] + wA[2] * k.ang_a[2][l];
      const float vn = dn + db - da;
      if (s > 0.0f || vn < 0.0f) ms = 1.0f, is = 0.0f;
      const float old = k.impulse[l];
      const float neg = k.mass[l] * ms * (vn + bias) + is * old;
      const float next = fmax(old - neg, 0.0f);
      const float lambda = next - old;
      k.impulse[l] = next;
      k.max_impulse[l] = fmax(k.max_impulse[l], lambda);
      const float la = k.inv_mass_a[l] * lambda, lb = k.inv_mass_b[l] * lambda;
      for (int c = 0; c < 3; ++c) {
        if (ia >= 0) {
          b.v[c][ia] = vA[c] - la * k.n[c][l];
          b.w[c][ia] = wA[c] - lambda * k.iang_a[c][l];
        }
        if (ib >= 0) {
          b.v[c][ib] = vB[c] + lb * k.n[c][l];
          b.w[c][ib] = wB[c] + lambda * k.iang_b[c][l];
        }
      }
    }
  }
}

struct Solved {
  std::vector<NormalRowBlock> blocks;
  BodyArraysF bodies;
};

// Two sweeps (biased, then relaxed) with `solve`, from the same inputs.
template <class Solve>
Solved sweepTwice(const RowSet& set, Solve solve) {
  Solved r{set.blocks, BodyArraysF(set.bodies)};
  NormalRowParams p = set.params;
  solve(r.blocks, r.bodies.view(), p);
  p.use_bias = false;
  solve(r.blocks, r.bodies.view(), p);
  return r;
}

// sweepTwice with the bodies as 8-float records, converted back to fields for comparing.
Solved aosSweepTwice(const RowSet& set,
                     void (*solve)(NormalRowBlock*, int, BodyVelocityF*, const NormalRowParams&)) {
  Solved r{set.blocks, BodyArraysF(set.bodies)};
  std::vector<BodyVelocityF> records = bodyRecordsF(set.bodies);
  NormalRowParams p = set.params;
  solve(r.blocks.data(), int(r.blocks.size()), records.data(), p);
  p.use_bias = false;
  solve(r.blocks.data(), int(r.blocks.size()), records.data(), p);
  for (size_t i = 0; i < records.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      r.bodies.v[k][i] = records[i].v[k];
      r.bodies.w[k][i] = records[i].w[k];
    }
    EXPECT_EQ(records[i].pad[0], 0.0f);
  }
  return r;
}

void expectSameBits(const Solved& x, const Solved& y, const char* what) {
  for (int k = 0; k < 3; ++k) {
    for (size_t i = 0; i < x.bodies.v[k].size(); ++i) {
      ASSERT_EQ(bitsOf(x.bodies.v[k][i]), bitsOf(y.bodies.v[k][i])) << what << ": v body " << i;
      ASSERT_EQ(bitsOf(x.bodies.w[k][i]), bitsOf(y.bodies.w[k][i])) << what << ": w body " << i;
    }
  }
  for (size_t k = 0; k < x.blocks.size(); ++k) {
    for (int l = 0; l < kRowBlock; ++l) {
      ASSERT_EQ(bitsOf(x.blocks[k].impulse[l]), bitsOf(y.blocks[k].impulse[l])) << what;
      ASSERT_EQ(bitsOf(x.blocks[k].max_impulse[l]), bitsOf(y.blocks[k].max_impulse[l])) << what;
    }
  }
}

// 1001 rows (a partial last block) over 300 bodies: bodies are shared between blocks, so the
// sweep's order matters and is checked along with the lanes.
TEST(Lanes, NormalRowKernelWidthsGiveTheSameBits) {
  const RowSet set = makeRows(1001, 300, true, 11);
  const Solved scalar = sweepTwice(set, [](auto& b, BodyVelocitiesF v, const NormalRowParams& p) {
    solveRowsScalarFloat(b, v, p);
  });
  const Solved w4 = sweepTwice(set, [](auto& b, BodyVelocitiesF v, const NormalRowParams& p) {
    kernel_w4::solveNormalRows(b.data(), int(b.size()), v, p);
  });
  expectSameBits(scalar, w4, "4 lanes against scalar float");
  // Something happened: impulses were applied and some clamped at zero.
  int applied = 0, clamped = 0;
  for (const NormalRowBlock& k : w4.blocks)
    for (int l = 0; l < kRowBlock; ++l) applied += k.impulse[l] > 0.0f, clamped += k.impulse[l] == 0.0f;
  EXPECT_GT(applied, 200);
  EXPECT_GT(clamped, 200);
  expectSameBits(w4, aosSweepTwice(set, kernel_w4::solveNormalRowsAos), "4 lanes, records");
  if (!cpuHasAvx2()) GTEST_SKIP() << "no AVX2 on this CPU or in this build";
  expectSameBits(w4, aosSweepTwice(set, kernel_w8::solveNormalRowsAos), "8 lanes, records");
  const Solved w8 = sweepTwice(set, [](auto& b, BodyVelocitiesF v, const NormalRowParams& p) {
    kernel_w8::solveNormalRows(b.data(), int(b.size()), v, p);
  });
  expectSameBits(w4, w8, "8 lanes against 4 lanes");
  const Solved chosen = sweepTwice(set, [](auto& b, BodyVelocitiesF v, const NormalRowParams& p) {
    solveNormalRows(8, b.data(), int(b.size()), v, p);
  });
  expectSameBits(w4, chosen, "the dispatcher at 8");
  expectSameBits(w4, aosSweepTwice(set, [](NormalRowBlock* b, int n, BodyVelocityF* v,
                                            const NormalRowParams& p) {
                   solveNormalRowsAos(8, b, n, v, p);
                 }),
                 "the dispatcher at 8, records");
}

// Each body in one row: the float kernel against the double row of contact_solver.cpp, within
// 1e-6 of the scale of each result (float inputs rounded once, then float arithmetic).
TEST(Lanes, NormalRowKernelMatchesDoubleRow) {
  RowSet set = makeRows(2000, 4000, false, 12);
  for (bool use_bias : {true, false}) {
    RowSet s = set;
    s.params.use_bias = s.params_d.use_bias = use_bias;
    BodyArraysF f(s.bodies);
    std::vector<NormalRowBlock> blocks = s.blocks;
    solveNormalRows(chooseLaneWidth(0), blocks.data(), int(blocks.size()), f.view(), s.params);
    const std::vector<SolverBody> before = s.bodies;
    std::vector<NormalRowD> rows = s.rows;
    solveNormalRowsD(rows, s.bodies, s.params_d);
    double worst = 0.0;
    int applied = 0;
    for (size_t i = 0; i < rows.size(); ++i) {
      const NormalRowD& r = rows[i];
      const NormalRowBlock& k = blocks[i / kRowBlock];
      const int l = int(i % kRowBlock);
      const double dl = std::abs(r.impulse - s.rows[i].impulse);
      // The impulse's scale: the old impulse and the row's largest velocity term times m.
      const SolverBody& B = before[r.b];
      const double vterm = B.v.norm() + B.w.norm() * r.row.angB.norm() +
                           (r.a >= 0 ? before[r.a].v.norm() + before[r.a].w.norm() * r.row.angA.norm() : 0.0) +
                           std::abs(r.separation) * s.params_d.inv_h + s.params_d.max_push_velocity;
      const double iscale = s.rows[i].impulse + r.row.mass * vterm;
      worst = std::max(worst, std::abs(k.impulse[l] - r.impulse) / iscale);
      applied += r.impulse > 0.0;
      for (int c = 0; c < 3; ++c) {
        const double vs = B.v.norm() + B.inv_mass * (iscale + dl);
        const double ws = B.w.norm() + r.row.iangB.norm() * (iscale + dl);
        worst = std::max(worst, std::abs(f.v[c][r.b] - s.bodies[r.b].v[c]) / vs);
        worst = std::max(worst, std::abs(f.w[c][r.b] - s.bodies[r.b].w[c]) / ws);
      }
    }
    EXPECT_LT(worst, 1e-6) << "use_bias " << use_bias;
    EXPECT_GT(applied, 400);
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", worst);
    RecordProperty(use_bias ? "worst_relative_biased" : "worst_relative_relax", text);
  }
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

}  // namespace
}  // namespace ragdoll_sim
