// The run-time choice between the builds of the point-row kernels.
#include "point_row_wide.hpp"

#include "lane_width.hpp"

namespace ragdoll_sim {

void warmStartPointRows(int width, PointRowBlock* blocks, int count, const LaneBodies& bodies) {
  if (width == 8 && cpuHasAvx512()) return kernel_w16::warmStartPointRows(blocks, count, bodies);
  if (width == 8 && cpuHasAvx2()) kernel_w8::warmStartPointRows(blocks, count, bodies);
  else kernel_w4::warmStartPointRows(blocks, count, bodies);
}

void solvePointRows(int width, PointRowBlock* blocks, int count, const LaneBodies& bodies,
                    const PointRowParams& params) {
  if (width == 8 && cpuHasAvx512())
    return kernel_w16::solvePointRows(blocks, count, bodies, params);
  if (width == 8 && cpuHasAvx2()) kernel_w8::solvePointRows(blocks, count, bodies, params);
  else kernel_w4::solvePointRows(blocks, count, bodies, params);
}

}  // namespace ragdoll_sim
