// Each FloatW operation applied over arrays, from files built for each instruction set
// (lane_ops_w4.cpp at the baseline, lane_ops_w8.cpp with AVX2); test_lanes.cpp compares the
// results with scalar float. Plain declarations only (see src/core/lanes.hpp).
#pragma once

#include <cstdint>

namespace ragdoll_sim {
namespace lane_test {

enum LaneOp {
  kAdd, kSub, kMul, kDiv, kMin, kMax,                 // out = a op b
  kLt, kLe, kGt, kGe, kEq,                            // out = mask lane as 1 or 0
  kSelect,                                            // out = a < b ? a : b via select
  kAnd, kOr, kAndNot,                                 // (a < b) op (a > 0)
  kAny, kAll,                                         // every lane: any/all of (a < b) in its chunk
  kSplat,                                             // every lane: the chunk's first a
  kZero,                                              // 0
  kLoadU,                                             // a[i + 1], unaligned load and store
  kLane,                                              // a through lane(i)
  kGather,                                            // a[index[i]] or 0 for index < 0
  kScatter,                                           // out[index[i]] = a[i] for index >= 0
  kOpCount
};

// n a multiple of 8; a, b, out 32-byte aligned, a holds n + 1 floats (kLoadU). `which` picks
// the lanes: 0 the arrays of width 4, 1 of width 8, 2 the SSE2 Float4 (W4 file), 3 the AVX
// Float8 (W8 file). Returns false when that width is not in the file.
bool runW4File(int which, LaneOp op, const float* a, const float* b, const int32_t* index,
               float* out, int n);
bool runW8File(int which, LaneOp op, const float* a, const float* b, const int32_t* index,
               float* out, int n);

}  // namespace lane_test
}  // namespace ragdoll_sim
