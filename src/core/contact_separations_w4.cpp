// The separations four lanes at a time in AVX registers, compiled with -mavx2 -mno-fma
// (CMakeLists.txt) and called only on a CPU with AVX2; see contact_separations_kernel.hpp.
// Without those flags it runs two lanes at a time, with the same bits.
#include "contact_separations_kernel.hpp"

namespace ragdoll_sim {
namespace contact_separations_w4 {

#if defined(__AVX__)
using Lanes = double_lanes::Double4;
#else
using Lanes = double_lanes::Double2;
#endif

void update(ContactGeometryBlock* geometry, ContactBlock* blocks, int count,
            const LaneBodies& bodies) {
  contact_separations::updateBlocks<Lanes>(geometry, blocks, count, bodies);
}

}  // namespace contact_separations_w4
}  // namespace ragdoll_sim
