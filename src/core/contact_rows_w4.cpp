// The contact kernels at 4 lanes (SSE2, the x86-64 baseline); see contact_rows_wide.inc.
#define RAGDOLL_SIM_KERNEL_WIDTH 4
#define RAGDOLL_SIM_KERNEL_NS kernel_w4
#include "contact_rows_wide.inc"
