// The baseline build of the frame kernel (two lanes, SSE2) and the run-time choice of width.
#include "point_frames_kernel.hpp"

#include "lane_width.hpp"

namespace ragdoll_sim {

namespace point_frames_w2 {
void refresh(PointFrameBlock* frames, PointRowBlock* rows, int count, const LaneBodies& bodies,
             bool advance_angles, double h) {
  using Lanes = double_lanes::Double2;
  point_frames::refreshBlocks<Lanes>(frames, rows, count, bodies, advance_angles, h);
}
}  // namespace point_frames_w2

void refreshPointFrames(PointFrameBlock* frames, PointRowBlock* rows, int count,
                        const LaneBodies& bodies, bool advance_angles, double h) {
  if (cpuHasAvx2()) point_frames_w4::refresh(frames, rows, count, bodies, advance_angles, h);
  else point_frames_w2::refresh(frames, rows, count, bodies, advance_angles, h);
}

}  // namespace ragdoll_sim
