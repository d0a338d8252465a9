// FloatW operations at the baseline instruction set (see lane_ops.hpp).
#define RAGDOLL_SIM_LANE_TEST_FN runW4File
#include "lane_ops.inc"
