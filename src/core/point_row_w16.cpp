// The point-row kernel with AVX-512F, two 8-lane blocks at once, compiled with -mavx512f
// -mno-fma (CMakeLists.txt) and called only where cpuHasAvx512(); see point_row_wide.inc. A
// compiler without AVX-512F builds the names only, on the 8-lane kernel (the same bits).
#if defined(__AVX512F__)
#define RAGDOLL_SIM_KERNEL_WIDTH 16
#define RAGDOLL_SIM_KERNEL_NS kernel_w16
#include "point_row_wide.inc"
#else
#include "point_row_wide.hpp"

namespace ragdoll_sim {
namespace kernel_w16 {
void warmStartPointRows(PointRowBlock* blocks, int count, const LaneBodies& bodies) {
  kernel_w8::warmStartPointRows(blocks, count, bodies);
}
void solvePointRows(PointRowBlock* blocks, int count, const LaneBodies& bodies,
                    const PointRowParams& params) {
  kernel_w8::solvePointRows(blocks, count, bodies, params);
}
}  // namespace kernel_w16
}  // namespace ragdoll_sim
#endif
