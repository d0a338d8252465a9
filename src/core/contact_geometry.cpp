// The baseline build of the contact geometry kernels (two lanes, SSE2) and the run-time choice
// of width.
#include "contact_geometry.hpp"

#include "contact_row_lanes_kernel.hpp"
#include "contact_separations_kernel.hpp"
#include "lane_width.hpp"

namespace ragdoll_sim {

namespace contact_geometry_w2 {
using Lanes = double_lanes::Double2;
#include "contact_geometry.inc"
}  // namespace contact_geometry_w2

void prepareBlockRows(ContactGeometryBlock* geometry, ContactBlock* blocks, int count,
                      const LaneBodies& bodies) {
  if (cpuHasAvx2()) contact_geometry_w4::prepareRows(geometry, blocks, count, bodies);
  else contact_geometry_w2::prepareRows(geometry, blocks, count, bodies);
}

void updateBlockSeparations(ContactGeometryBlock* geometry, ContactBlock* blocks, int count,
                            const LaneBodies& bodies) {
  if (cpuHasAvx2()) contact_geometry_w4::updateSeparations(geometry, blocks, count, bodies);
  else contact_geometry_w2::updateSeparations(geometry, blocks, count, bodies);
}

}  // namespace ragdoll_sim
