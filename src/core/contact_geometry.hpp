// The double geometry of the wide contact blocks (contact_wide.hpp) and the double-lane kernels
// over it: the points' rows, prepared once per step, and their separations at each position
// state, each with the bits of the scalar code it replaces (contactRow and updateSeparations,
// contact_solver.hpp; contact_row_lanes_kernel.hpp, contact_separations_kernel.hpp), rounded
// into the blocks' float lanes.
// Plain records and declarations only: the AVX2 kernel file includes this header too.
#pragma once

#include <cstdint>

#include "contact_rows_wide.hpp"

namespace ragdoll_sim {

// The double geometry of a ContactBlock's manifolds, lane i of each field lane i's; whole
// cache lines. A padding lane has count 0 and body 0: it is computed but nothing is stored.
struct alignas(64) ContactGeometryBlock {
  int32_t body_a[kRowBlock], body_b[kRowBlock];  // any body, static ones too
  int32_t count[kRowBlock];                      // the lane's points
  double n[3][kRowBlock];                        // the normal, A to B
  double t[2][3][kRowBlock];                     // the tangents
  // Of each point, from the step's prepare: the lever arms rA, rB and base_separation.
  double r_a[kBlockPoints][3][kRowBlock], r_b[kBlockPoints][3][kRowBlock];
  double base[kBlockPoints][kRowBlock];
  double normal_mass[kBlockPoints][kRowBlock];  // the normal rows' 1 / (J M^-1 J^T)
  double separation[kBlockPoints][kRowBlock];  // as the last update computed them
};

// Blocks [0, count): the three rows (normal, tangent 0, tangent 1) of points [0, points) of
// every lane into the blocks, zero past a lane's count and in padding lanes, and the normal
// rows' masses into the geometry (the position projection reads them).
void prepareBlockRows(ContactGeometryBlock* geometry, ContactBlock* blocks, int count,
                      const LaneBodies& bodies);
// Blocks [0, count): the separations of each lane's points at the bodies' current deltas into
// the geometry and, rounded, into the points' float lanes.
void updateBlockSeparations(ContactGeometryBlock* geometry, ContactBlock* blocks, int count,
                            const LaneBodies& bodies);

// The two widths, four lanes where the CPU has AVX2 (called only where cpuHasAvx2()), else
// two; the tests call them directly.
namespace contact_geometry_w2 {
void prepareRows(ContactGeometryBlock* geometry, ContactBlock* blocks, int count,
                 const LaneBodies& bodies);
void updateSeparations(ContactGeometryBlock* geometry, ContactBlock* blocks, int count,
                       const LaneBodies& bodies);
}  // namespace contact_geometry_w2
namespace contact_geometry_w4 {
void prepareRows(ContactGeometryBlock* geometry, ContactBlock* blocks, int count,
                 const LaneBodies& bodies);
void updateSeparations(ContactGeometryBlock* geometry, ContactBlock* blocks, int count,
                       const LaneBodies& bodies);
}  // namespace contact_geometry_w4

}  // namespace ragdoll_sim
