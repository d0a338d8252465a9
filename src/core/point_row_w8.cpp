// The point-row kernel at 8 lanes, compiled with -mavx2 -mno-fma (CMakeLists.txt); see
// point_row_wide.inc and kernel_w8.hpp.
#include "kernel_w8.hpp"
#include "point_row_wide.inc"
