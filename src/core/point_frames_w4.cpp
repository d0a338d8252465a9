// The frames four lanes at a time in AVX registers, compiled with -mavx2 -mno-fma
// (CMakeLists.txt) and called only on a CPU with AVX2; see point_frames_kernel.hpp. Without
// those flags (a compiler or target without AVX2) it runs two lanes at a time, with the same bits.
#include "point_frames_kernel.hpp"

namespace ragdoll_sim {
namespace point_frames_w4 {

using Lanes = double_lanes::WidestLanes;

void refresh(PointFrameBlock* frames, PointRowBlock* rows, int count, const LaneBodies& bodies,
             bool advance_angles, double h) {
  point_frames::refreshBlocks<Lanes>(frames, rows, count, bodies, advance_angles, h);
}

}  // namespace point_frames_w4
}  // namespace ragdoll_sim
