// The run-time choice between the two builds of the normal-row kernel.
#include "normal_row_wide.hpp"

#include "lane_width.hpp"

namespace ragdoll_sim {

void solveNormalRows(int width, NormalRowBlock* blocks, int count, const BodyVelocitiesF& bodies,
                     const NormalRowParams& params) {
  if (width == 8 && cpuHasAvx2()) kernel_w8::solveNormalRows(blocks, count, bodies, params);
  else kernel_w4::solveNormalRows(blocks, count, bodies, params);
}

void solveNormalRowsAos(int width, NormalRowBlock* blocks, int count, BodyVelocityF* bodies,
                        const NormalRowParams& params) {
  if (width == 8 && cpuHasAvx2()) kernel_w8::solveNormalRowsAos(blocks, count, bodies, params);
  else kernel_w4::solveNormalRowsAos(blocks, count, bodies, params);
}

}  // namespace ragdoll_sim
