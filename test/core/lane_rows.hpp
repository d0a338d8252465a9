// Random contact normal rows in both layouts (float blocks for the lane kernels, double rows
// for normal_row_double.hpp), for test_lanes.cpp and bench/bench_lanes.cpp.
#pragma once

#include <algorithm>
#include <random>
#include <vector>

#include "normal_row_double.hpp"
#include "normal_row_wide.hpp"
#include "softness.hpp"

namespace ragdoll_sim {
namespace lane_test {

// Body velocities in float SoA with their storage.
struct BodyArraysF {
  std::vector<float> v[3], w[3];
  explicit BodyArraysF(const std::vector<SolverBody>& bodies) {
    for (int k = 0; k < 3; ++k) {
      v[k].resize(bodies.size());
      w[k].resize(bodies.size());
      for (size_t i = 0; i < bodies.size(); ++i) {
        v[k][i] = float(bodies[i].v[k]);
        w[k][i] = float(bodies[i].w[k]);
      }
    }
  }
  BodyVelocitiesF view() {
    return {{v[0].data(), v[1].data(), v[2].data()}, {w[0].data(), w[1].data(), w[2].data()}};
  }
};

// The same as 8-float records.
inline std::vector<BodyVelocityF> bodyRecordsF(const std::vector<SolverBody>& bodies) {
  std::vector<BodyVelocityF> r(bodies.size());
  for (size_t i = 0; i < bodies.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      r[i].v[k] = float(bodies[i].v[k]);
      r[i].w[k] = float(bodies[i].w[k]);
    }
    r[i].pad[0] = r[i].pad[1] = 0.0f;
  }
  return r;
}

struct RowSet {
  std::vector<SolverBody> bodies;
  std::vector<NormalRowD> rows;          // row order: block by block, lane by lane
  std::vector<NormalRowBlock> blocks;    // the same rows, padding lanes after the last
  NormalRowParamsD params_d;
  NormalRowParams params;
};

// `count` rows over `body_count` bodies (>= 2 kRowBlock); the rows of one block share no body,
// and with `reuse` false no body is in two rows (body_count >= 2 count). A quarter of the rows
// have a static side A.
inline RowSet makeRows(int count, int body_count, bool reuse, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0), pos(0.0, 1.0);
  RowSet set;
  set.bodies.resize(body_count);
  for (SolverBody& b : set.bodies) {
    b.v = 2.0 * Vec3(u(rng), u(rng), u(rng));
    b.w = 5.0 * Vec3(u(rng), u(rng), u(rng));
    b.inv_mass = 0.2 + 2.0 * pos(rng);
    Mat3 S;
    S << u(rng), u(rng), u(rng), u(rng), u(rng), u(rng), u(rng), u(rng), u(rng);
    b.inv_inertia = 2.0 * S * S.transpose() + (5.0 + 45.0 * pos(rng)) * Mat3::Identity();
  }
  const double h = 1.0 / 240.0;
  const Softness soft = Softness::make(std::min(360.0, 0.25 / h), 10.0, h);
  set.params_d = {1.0 / h, soft.bias_rate, soft.mass_scale, soft.impulse_scale, 0.0005, 3.0, true};
  set.params = {float(1.0 / h), float(soft.bias_rate), float(soft.mass_scale),
                float(soft.impulse_scale), 0.0005f, 3.0f, true};

  std::vector<int> order(body_count);
  for (int i = 0; i < body_count; ++i) order[i] = i;
  int next_body = body_count;  // without reuse: bodies handed out in a shuffled order
  const SolverBody ground;
  const int block_count = (count + kRowBlock - 1) / kRowBlock;
  set.blocks.resize(block_count);
  for (int k = 0; k < block_count; ++k) {
    NormalRowBlock& blk = set.blocks[k];
    blk = NormalRowBlock{};
    if (reuse || next_body + 2 * kRowBlock > body_count) {
      std::shuffle(order.begin(), order.end(), rng);
      next_body = 0;
    }
    for (int l = 0; l < kRowBlock; ++l) {
      blk.body_a[l] = blk.body_b[l] = -1;
      if (k * kRowBlock + l >= count) continue;  // padding: mass 0, static sides
      NormalRowD r;
      r.a = pos(rng) < 0.25 ? -1 : order[next_body];
      r.b = order[next_body + 1];
      next_body += 2;
      const SolverBody& A = r.a >= 0 ? set.bodies[r.a] : ground;
      const SolverBody& B = set.bodies[r.b];
      r.normal = Vec3(u(rng), u(rng), u(rng)).normalized();
      const Vec3 rA = 0.3 * Vec3(u(rng), u(rng), u(rng)), rB = 0.3 * Vec3(u(rng), u(rng), u(rng));
      r.row.angA = rA.cross(r.normal);
      r.row.angB = rB.cross(r.normal);
      r.row.iangA = A.inv_inertia * r.row.angA;
      r.row.iangB = B.inv_inertia * r.row.angB;
      r.row.mass = 1.0 / (A.inv_mass + B.inv_mass + r.row.angA.dot(r.row.iangA) +
                          r.row.angB.dot(r.row.iangB));
      r.separation = 0.01 * u(rng);
      r.impulse = pos(rng) < 0.5 ? 0.0 : 2.0 * pos(rng);
      r.max_impulse = 0.0;
      set.rows.push_back(r);
      blk.body_a[l] = r.a;
      blk.body_b[l] = r.b;
      for (int c = 0; c < 3; ++c) {
        blk.n[c][l] = float(r.normal[c]);
        blk.ang_a[c][l] = float(r.row.angA[c]);
        blk.ang_b[c][l] = float(r.row.angB[c]);
        blk.iang_a[c][l] = float(r.row.iangA[c]);
        blk.iang_b[c][l] = float(r.row.iangB[c]);
      }
      blk.inv_mass_a[l] = float(A.inv_mass);
      blk.inv_mass_b[l] = float(B.inv_mass);
      blk.mass[l] = float(r.row.mass);
      blk.separation[l] = float(r.separation);
      blk.impulse[l] = float(r.impulse);
      blk.max_impulse[l] = 0.0f;
    }
  }
  return set;
}

}  // namespace lane_test
}  // namespace ragdoll_sim
