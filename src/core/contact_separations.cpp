// The baseline build of the separation kernel (two lanes, SSE2) and the run-time choice of width.
#include "contact_separations_kernel.hpp"

#include "lane_width.hpp"

namespace ragdoll_sim {

namespace contact_separations_w2 {
void update(ContactGeometryBlock* geometry, ContactBlock* blocks, int count,
            const LaneBodies& bodies) {
  contact_separations::updateBlocks<double_lanes::Double2>(geometry, blocks, count, bodies);
}
}  // namespace contact_separations_w2

void updateBlockSeparations(ContactGeometryBlock* geometry, ContactBlock* blocks, int count,
                            const LaneBodies& bodies) {
  if (cpuHasAvx2()) contact_separations_w4::update(geometry, blocks, count, bodies);
  else contact_separations_w2::update(geometry, blocks, count, bodies);
}

}  // namespace ragdoll_sim
