// The run-time choice between the two builds of the point-row kernel.
#include "point_row_wide.hpp"

#include "lane_width.hpp"

namespace ragdoll_sim {

void solvePointRows(int width, PointRowBlock* blocks, int count, const LaneBodies& bodies,
                    const PointRowParams& params) {
  if (width == 8 && cpuHasAvx2()) kernel_w8::solvePointRows(blocks, count, bodies, params);
  else kernel_w4::solvePointRows(blocks, count, bodies, params);
}

}  // namespace ragdoll_sim
