// Running one PointRowBlock through the wide kernels for the kernel tests (test_joint_lanes.cpp,
// test_limit_lanes.cpp): the warm start, a biased sweep and a relax sweep, and the check that
// 4 and 8 lanes leave the same bits.
#pragma once

#include <gtest/gtest.h>

#include <cstddef>
#include <cstring>
#include <vector>

#include "body.hpp"
#include "lane_bodies.hpp"
#include "point_row_wide.hpp"
#include "softness.hpp"

namespace ragdoll_sim {
namespace test {

inline constexpr double kLaneH = 1.0 / 960.0;
inline const Softness kLaneSoft = Softness::make(60.0, 5.0, kLaneH);

inline PointRowParams laneParams(bool use_bias) {
  const Softness r = kLaneSoft.orRigid(use_bias);
  PointRowParams p;
  p.bias_rate = float(r.bias_rate);
  p.mass_scale = float(r.mass_scale);
  p.impulse_scale = float(r.impulse_scale);
  p.inv_h = float(1.0 / kLaneH);
  p.use_bias = use_bias;
  return p;
}

// The warm start, a biased sweep and a relax sweep at lane width `width`.
inline void runLanes(int width, PointRowBlock& b, std::vector<SolverBody>& bodies) {
  const LaneBodies view = laneBodies(bodies.data());
  warmStartPointRows(width, &b, 1, view);
  for (const bool use_bias : {true, false})
    solvePointRows(width, &b, 1, view, laneParams(use_bias));
}

// b4 / f4: a block and bodies after runLanes(4, ...); the same at 8 lanes from `block` and
// `start` must give the same block fields and velocities bit for bit.
inline void expectEightLanesSameBits(const PointRowBlock& block,
                                     const std::vector<SolverBody>& start, const PointRowBlock& b4,
                                     const std::vector<SolverBody>& f4) {
  PointRowBlock b8 = block;
  std::vector<SolverBody> f8 = start;
  runLanes(8, b8, f8);
  // the fields, not the padding after them
  const size_t fields = offsetof(PointRowBlock, axis_rows) + sizeof b4.axis_rows;
  EXPECT_EQ(std::memcmp(&b4, &b8, fields), 0) << "blocks";
  for (size_t i = 0; i < start.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      EXPECT_EQ(f4[i].v[c], f8[i].v[c]) << "body " << i;
      EXPECT_EQ(f4[i].w[c], f8[i].w[c]) << "body " << i;
    }
}

}  // namespace test
}  // namespace ragdoll_sim
