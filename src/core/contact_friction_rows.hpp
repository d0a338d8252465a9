// The two friction rows of each point of the wide contact blocks (contact_wide.hpp), prepared
// once per step in double lanes straight from the blocks' geometry (contact_geometry.hpp) and
// rounded into the blocks' float rows: what contactRow (contact_solver.hpp) gives one row at
// a time, with the same bits (contact_friction_rows_kernel.hpp).
// Declarations only: the AVX2 kernel file includes this header too.
#pragma once

#include "contact_geometry.hpp"

namespace ragdoll_sim {

// Blocks [0, count): rows 1 and 2 (tangents 0 and 1) of every point below each lane's count.
// Four lanes at a time where the CPU has AVX2, else two.
void prepareBlockFrictionRows(const ContactGeometryBlock* geometry, ContactBlock* blocks,
                              int count, const LaneBodies& bodies);

// The two widths (the AVX one only where cpuHasAvx2()); the tests call them directly.
namespace contact_friction_rows_w2 {
void prepare(const ContactGeometryBlock* geometry, ContactBlock* blocks, int count,
             const LaneBodies& bodies);
}
namespace contact_friction_rows_w4 {
void prepare(const ContactGeometryBlock* geometry, ContactBlock* blocks, int count,
             const LaneBodies& bodies);
}

}  // namespace ragdoll_sim
