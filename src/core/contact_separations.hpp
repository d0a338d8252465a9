// The separations of the wide contact blocks' points (contact_wide.hpp) at the bodies' current
// displacement and rotation deltas, in double lanes once per position state: what
// updateSeparations (contact_solver.hpp) computes one manifold at a time, with the same bits
// (contact_separations_kernel.hpp), then rounded into the blocks' float lanes.
// Declarations only: the AVX2 kernel file includes this header too.
#pragma once

#include "contact_geometry.hpp"

namespace ragdoll_sim {

// Blocks [0, count): the separations of each lane's points into `geometry` and, rounded, into
// the points' float lanes of `blocks`. Four lanes at a time where the CPU has AVX2, else two.
void updateBlockSeparations(ContactGeometryBlock* geometry, ContactBlock* blocks, int count,
                            const LaneBodies& bodies);

// The two widths (the AVX one only where cpuHasAvx2()); the tests call them directly.
namespace contact_separations_w2 {
void update(ContactGeometryBlock* geometry, ContactBlock* blocks, int count,
            const LaneBodies& bodies);
}
namespace contact_separations_w4 {
void update(ContactGeometryBlock* geometry, ContactBlock* blocks, int count,
            const LaneBodies& bodies);
}

}  // namespace ragdoll_sim
