// The contact kernels with AVX-512F, two 8-lane blocks at once, compiled with -mavx512f -mno-fma
// (CMakeLists.txt) and called only where cpuHasAvx512(); see contact_rows_wide.inc. A compiler
// without AVX-512F builds the names only, on the 8-lane kernels (the same bits).
#if defined(__AVX512F__)
#define RAGDOLL_SIM_KERNEL_WIDTH 16
#define RAGDOLL_SIM_KERNEL_NS kernel_w16
#include "contact_rows_wide.inc"
#else
#include "contact_rows_wide.hpp"

namespace ragdoll_sim {
namespace kernel_w16 {
void warmStartContactBlocks(ContactBlock* blocks, int count, const LaneBodies& bodies) {
  kernel_w8::warmStartContactBlocks(blocks, count, bodies);
}
void solveContactBlocks(ContactBlock* blocks, int count, const LaneBodies& bodies,
                        const NormalRowParams& params) {
  kernel_w8::solveContactBlocks(blocks, count, bodies, params);
}
}  // namespace kernel_w16
}  // namespace ragdoll_sim
#endif
