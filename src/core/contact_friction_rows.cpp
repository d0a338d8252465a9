// The baseline build of the friction-row kernel (two lanes, SSE2) and the run-time choice of
// width.
#include "contact_friction_rows_kernel.hpp"

#include "lane_width.hpp"

namespace ragdoll_sim {

namespace contact_friction_rows_w2 {
void prepare(const ContactGeometryBlock* geometry, ContactBlock* blocks, int count,
             const LaneBodies& bodies) {
  contact_friction_rows::prepareBlocks<double_lanes::Double2>(geometry, blocks, count, bodies);
}
}  // namespace contact_friction_rows_w2

void prepareBlockFrictionRows(const ContactGeometryBlock* geometry, ContactBlock* blocks,
                              int count, const LaneBodies& bodies) {
  if (cpuHasAvx2()) contact_friction_rows_w4::prepare(geometry, blocks, count, bodies);
  else contact_friction_rows_w2::prepare(geometry, blocks, count, bodies);
}

}  // namespace ragdoll_sim
