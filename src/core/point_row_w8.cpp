// The point-row kernel at 8 lanes, compiled with -mavx2 -mno-fma (CMakeLists.txt) and called
// only on a CPU with AVX2 (lane_width.hpp); see point_row_wide.inc. Without those flags (a
// compiler or target without AVX2) it hands over to the 4-lane kernel, which gives the same bits.
#if defined(__AVX2__)
#define RAGDOLL_SIM_KERNEL_WIDTH 8
#define RAGDOLL_SIM_KERNEL_NS kernel_w8
#include "point_row_wide.inc"
#else
#include "point_row_wide.hpp"

namespace ragdoll_sim {
void kernel_w8::warmStartPointRows(PointRowBlock* blocks, int count, const LaneBodies& bodies) {
  kernel_w4::warmStartPointRows(blocks, count, bodies);
}
void kernel_w8::solvePointRows(PointRowBlock* blocks, int count, const LaneBodies& bodies,
                               const PointRowParams& params) {
  kernel_w4::solvePointRows(blocks, count, bodies, params);
}
}  // namespace ragdoll_sim
#endif
