// The contact kernels at 8 lanes, compiled with -mavx2 -mno-fma (CMakeLists.txt); see
// contact_rows_wide.inc and kernel_w8.hpp.
#include "kernel_w8.hpp"
#include "contact_rows_wide.inc"
