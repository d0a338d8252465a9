// With AVX-512F the 8-lane sweeps solve two blocks of a colour at once (FloatPair16): random
// contact and point-row blocks, some that pair and some that do not (another colour, point
// count or rows), give the bits of the 8-lane build block by block. Skipped on a CPU without
// AVX-512F, where the paired kernels are never called.
#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "body.hpp"
#include "contact_rows_wide.hpp"
#include "lane_width.hpp"
#include "point_row_wide.hpp"

using namespace ragdoll_sim;

namespace {

constexpr int kBodies = 200;

std::vector<SolverBody> randomBodies(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0), m(0.2, 3.0);
  std::vector<SolverBody> bodies(kBodies);
  for (SolverBody& b : bodies) {
    b.v = Vec3(u(rng), u(rng), u(rng));
    b.w = Vec3(u(rng), u(rng), u(rng));
    b.inv_mass = m(rng);
  }
  return bodies;
}

bool sameBits(const void* a, const void* b, size_t bytes) { return std::memcmp(a, b, bytes) == 0; }
// The velocities, bit for bit (a SolverBody's padding is not copied by its copy constructor).
bool sameVelocities(const std::vector<SolverBody>& a, const std::vector<SolverBody>& b) {
  for (size_t i = 0; i < a.size(); ++i)
    if (!sameBits(a[i].v.data(), b[i].v.data(), 3 * sizeof(double)) ||
        !sameBits(a[i].w.data(), b[i].w.data(), 3 * sizeof(double)))
      return false;
  return true;
}

// The bodies of block k: 8 distinct ones from a shuffled list (a colour's blocks share none),
// some lanes static (-1) or padding (both -1).
template <class Block>
void pickBodies(Block& b, std::mt19937& rng, std::vector<int>& pool, int lanes) {
  std::uniform_int_distribution<int> coin(0, 3);
  for (int l = 0; l < kRowBlock; ++l) {
    const bool used = l < lanes;
    b.body_b[l] = used ? pool.back() : -1;
    if (used) pool.pop_back();
    b.body_a[l] = used && coin(rng) != 0 ? pool.back() : -1;
    if (used && b.body_a[l] >= 0) pool.pop_back();
  }
}

// Blocks in runs of one colour; lanes 8, or fewer for the last of a run.
template <class Block, class Fill>
std::vector<Block> randomBlocks(std::mt19937& rng, int count, Fill fill) {
  std::vector<Block> blocks(count);
  std::uniform_int_distribution<int> run(1, 4), lanes(1, kRowBlock);
  std::vector<int> pool;
  int colour = 0;
  for (int k = 0; k < count;) {
    pool.resize(kBodies);
    for (int i = 0; i < kBodies; ++i) pool[i] = i;
    std::shuffle(pool.begin(), pool.end(), rng);
    const int n = std::min(run(rng), count - k);
    for (int j = 0; j < n; ++j, ++k) {
      Block& b = blocks[k];
      std::memset(static_cast<void*>(&b), 0, sizeof(Block));
      b.colour = colour;
      pickBodies(b, rng, pool, j == n - 1 ? lanes(rng) : kRowBlock);
      fill(b);
    }
    ++colour;
  }
  return blocks;
}


// A warm start and three sweeps (the first biased) by the 8-lane kernels and by the paired ones:
// the same blocks and velocities, bit for bit, and the sweeps did move the bodies.
// run(paired, blocks, count, bodies, sweep): the warm start for sweep < 0.
template <class Block, class Run>
void expectPairedBits(const std::vector<Block>& blocks, const std::vector<SolverBody>& bodies,
                      Run run, int trial) {
  std::vector<Block> b8 = blocks, b16 = blocks;
  std::vector<SolverBody> s8 = bodies, s16 = bodies;
  for (int sweep = -1; sweep < 3; ++sweep) {
    run(false, b8.data(), int(b8.size()), laneBodies(s8.data()), sweep);
    run(true, b16.data(), int(b16.size()), laneBodies(s16.data()), sweep);
  }
  EXPECT_TRUE(sameBits(b8.data(), b16.data(), b8.size() * sizeof(Block))) << trial;
  EXPECT_TRUE(sameVelocities(s8, s16)) << trial;
  EXPECT_FALSE(sameVelocities(s8, bodies)) << trial;
}

}  // namespace

TEST(PairedBlocks, ContactsGiveTheEightLaneBits) {
  if (!cpuHasAvx512()) GTEST_SKIP() << "no AVX-512F: the paired kernels are not used here";
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), pos(0.05f, 1.0f);
  std::uniform_int_distribution<int> points(1, 2);
  const auto fill = [&](ContactBlock& b) {
    b.points = points(rng);  // pairs need equal counts: about half of them do
    for (int l = 0; l < kRowBlock; ++l) {
      if (b.body_b[l] < 0) continue;
      b.friction[l] = 0.6f;
      b.inv_mass_a[l] = b.body_a[l] >= 0 ? pos(rng) : 0.0f;
      b.inv_mass_b[l] = pos(rng);
      for (int c = 0; c < 3; ++c) b.n[c][l] = u(rng), b.t0[c][l] = u(rng), b.t1[c][l] = u(rng);
      for (int i = 0; i < b.points; ++i) {
        ContactPointLanes& q = b.point[i];
        q.separation[l] = 0.01f * u(rng);  // some apart (speculative), some touching
        for (int r = 0; r < 3; ++r) {
          q.impulse[r][l] = r == 0 ? 0.1f * pos(rng) : 0.02f * u(rng);
          q.row[r].mass[l] = pos(rng);
          for (int c = 0; c < 3; ++c) {
            q.row[r].ang_a[c][l] = u(rng), q.row[r].ang_b[c][l] = u(rng);
            q.row[r].iang_a[c][l] = 0.3f * u(rng), q.row[r].iang_b[c][l] = 0.3f * u(rng);
          }
        }
      }
    }
  };
  NormalRowParams p;
  p.inv_h = 3000.0f, p.bias_rate = 200.0f, p.mass_scale = 0.8f, p.impulse_scale = 0.2f;
  p.linear_slop = 0.0005f, p.max_push_velocity = 3.0f;
  const auto run = [&](bool paired, ContactBlock* b, int n, const LaneBodies& v, int sweep) {
    p.use_bias = sweep == 0;
    if (sweep < 0 && paired) kernel_w16::warmStartContactBlocks(b, n, v);
    else if (sweep < 0) kernel_w8::warmStartContactBlocks(b, n, v);
    else if (paired) kernel_w16::solveContactBlocks(b, n, v, p);
    else kernel_w8::solveContactBlocks(b, n, v, p);
  };
  for (int trial = 0; trial < 20; ++trial) {
    const std::vector<ContactBlock> blocks = randomBlocks<ContactBlock>(rng, 24, fill);
    expectPairedBits(blocks, randomBodies(rng), run, trial);
  }
}

TEST(PairedBlocks, PointRowsGiveTheEightLaneBits) {
  if (!cpuHasAvx512()) GTEST_SKIP() << "no AVX-512F: the paired kernels are not used here";
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), pos(0.05f, 1.0f);
  std::uniform_int_distribution<int> rows(0, kAngleRows), coin(0, 1);
  const auto fill = [&](PointRowBlock& b) {
    b.angle_rows = rows(rng);  // pairs need the same rows: some do
    b.motor_rows = b.angle_rows > 0 ? coin(rng) : 0;
    b.axis_rows = coin(rng);
    for (int l = 0; l < kRowBlock; ++l) {
      if (b.body_b[l] < 0) continue;
      b.inv_mass[l] = pos(rng);
      for (int c = 0; c < 3; ++c) {
        b.r_a[c][l] = 0.2f * u(rng), b.r_b[c][l] = 0.2f * u(rng);
        b.error[c][l] = 0.001f * u(rng), b.impulse[c][l] = 0.05f * u(rng);
        b.axis_u1[c][l] = b.axis_rows ? u(rng) : 0.0f;
        b.axis_u2[c][l] = b.axis_rows ? u(rng) : 0.0f;
      }
      for (int e = 0; e < 6; ++e) {  // symmetric positive: diagonal dominant
        b.ii_a[e][l] = b.body_a[l] < 0 ? 0.0f : e < 3 ? 2.0f + pos(rng) : 0.3f * u(rng);
        b.ii_b[e][l] = e < 3 ? 2.0f + pos(rng) : 0.3f * u(rng);
      }
      for (int k = 0; k < 2; ++k) {
        b.axis_error[k][l] = 0.001f * u(rng), b.axis_impulse[k][l] = 0.01f * u(rng);
      }
      for (int r = 0; r < b.angle_rows; ++r) {
        for (int c = 0; c < 3; ++c) b.angle_j[r][c][l] = u(rng);
        b.limit_c[r][0][l] = 0.05f * u(rng), b.limit_c[r][1][l] = 0.05f * u(rng);
        b.limit_impulse[r][0][l] = 0.01f * pos(rng), b.limit_impulse[r][1][l] = 0.0f;
        if (!b.motor_rows) continue;
        b.motor_bias[r][l] = u(rng), b.motor_mass_scale[r][l] = 0.9f;
        b.motor_impulse_scale[r][l] = 0.1f, b.motor_max[r][l] = 0.05f;
        b.motor_hc[r][l] = 0.01f * pos(rng), b.motor_impulse[r][l] = 0.01f * u(rng);
      }
    }
  };
  PointRowParams p;
  p.bias_rate = 300.0f, p.mass_scale = 0.7f, p.impulse_scale = 0.3f, p.inv_h = 3000.0f;
  const auto run = [&](bool paired, PointRowBlock* b, int n, const LaneBodies& v, int sweep) {
    p.use_bias = sweep == 0;
    if (sweep < 0 && paired) kernel_w16::warmStartPointRows(b, n, v);
    else if (sweep < 0) kernel_w8::warmStartPointRows(b, n, v);
    else if (paired) kernel_w16::solvePointRows(b, n, v, p);
    else kernel_w8::solvePointRows(b, n, v, p);
  };
  for (int trial = 0; trial < 20; ++trial) {
    const std::vector<PointRowBlock> blocks = randomBlocks<PointRowBlock>(rng, 24, fill);
    expectPairedBits(blocks, randomBodies(rng), run, trial);
  }
}
