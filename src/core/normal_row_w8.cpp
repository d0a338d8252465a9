// The normal-row kernel at 8 lanes, compiled with -mavx2 -mno-fma (CMakeLists.txt) and called
// only on a CPU with AVX2 (lane_width.hpp); see normal_row_wide.inc. Without those flags (a
// compiler or target without AVX2) it hands over to the 4-lane kernel, which gives the same bits.
#if defined(__AVX2__)
#define RAGDOLL_SIM_KERNEL_WIDTH 8
#define RAGDOLL_SIM_KERNEL_NS kernel_w8
#include "normal_row_wide.inc"
#else
#include "contact_rows_wide.hpp"
#include "normal_row_wide.hpp"

namespace ragdoll_sim {
void kernel_w8::solveNormalRows(NormalRowBlock* blocks, int count, const BodyVelocitiesF& bodies,
                                const NormalRowParams& params) {
  kernel_w4::solveNormalRows(blocks, count, bodies, params);
}
void kernel_w8::solveNormalRowsAos(NormalRowBlock* blocks, int count, BodyVelocityF* bodies,
                                   const NormalRowParams& params) {
  kernel_w4::solveNormalRowsAos(blocks, count, bodies, params);
}
void kernel_w8::warmStartContactBlocks(ContactBlock* blocks, int count, const LaneBodies& bodies) {
  kernel_w4::warmStartContactBlocks(blocks, count, bodies);
}
void kernel_w8::solveContactBlocks(ContactBlock* blocks, int count, const LaneBodies& bodies,
                                   const NormalRowParams& params) {
  kernel_w4::solveContactBlocks(blocks, count, bodies, params);
}
}  // namespace ragdoll_sim
#endif
