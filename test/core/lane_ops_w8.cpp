// FloatW operations with AVX2 (CMakeLists.txt builds this file with -mavx2; see lane_ops.hpp).
#if defined(__AVX2__)
#define RAGDOLL_SIM_LANE_TEST_FN runW8File
#include "lane_ops.inc"
#else
#include "lane_ops.hpp"
bool ragdoll_sim::lane_test::runW8File(int, LaneOp, const float*, const float*, const int32_t*,
                                       float*, int) {
  return false;
}
#endif
