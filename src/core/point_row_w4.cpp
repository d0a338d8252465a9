// The point-row kernel at 4 lanes (SSE2, the x86-64 baseline); see point_row_wide.inc.
#define RAGDOLL_SIM_KERNEL_WIDTH 4
#define RAGDOLL_SIM_KERNEL_NS kernel_w4
#include "point_row_wide.inc"
