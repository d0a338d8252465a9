// The public structs' layout as a package sees it that includes the core headers with Eigen's
// default settings (vectorized, 16-byte alignment on x86-64): the core's own defines from
// CMakeLists.txt are taken back before Eigen is included. Only sizeof / alignof are taken here,
// so nothing of Eigen is instantiated twice with different code.
#undef EIGEN_DONT_VECTORIZE
#undef EIGEN_MAX_STATIC_ALIGN_BYTES
#undef EIGEN_MAX_ALIGN_BYTES
#include "layout_probe.hpp"

namespace ragdoll_sim::test {
std::vector<LayoutEntry> layoutWithDefaultEigen() { return RAGDOLL_SIM_LAYOUT_ENTRIES; }
}  // namespace ragdoll_sim::test
