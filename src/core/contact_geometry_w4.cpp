// The contact geometry kernels four lanes at a time in AVX registers, compiled with -mavx2
// -mno-fma (CMakeLists.txt) and called only on a CPU with AVX2; see contact_geometry.hpp.
// Without those flags they run two lanes at a time, with the same bits.
#include "contact_row_lanes_kernel.hpp"
#include "contact_separations_kernel.hpp"

namespace ragdoll_sim {
namespace contact_geometry_w4 {

using Lanes = double_lanes::WidestLanes;

#include "contact_geometry.inc"

}  // namespace contact_geometry_w4
}  // namespace ragdoll_sim
