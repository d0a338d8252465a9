// The 8-lane build of a kernel file (included before its .inc): kernel_w8 at 8 lanes where the
// file is compiled with AVX2 (CMakeLists.txt), else the 4-lane build under the same name, which
// gives the same bits, so kernel_w8 exists on every target. It is called only on a CPU with
// AVX2 (lane_width.hpp).
#pragma once

#define RAGDOLL_SIM_KERNEL_NS kernel_w8
#if defined(__AVX2__)
#define RAGDOLL_SIM_KERNEL_WIDTH 8
#else
#define RAGDOLL_SIM_KERNEL_WIDTH 4
#endif
