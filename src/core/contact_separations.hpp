// The separations of the wide contact blocks' points (contact_wide.hpp) at the bodies' current
// displacement and rotation deltas, in double lanes once per position state: what
// updateSeparations (contact_solver.hpp) computes one manifold at a time, with the same bits
// (contact_separations_kernel.hpp), then rounded into the blocks' float lanes.
// Plain records and declarations only: the AVX2 kernel file includes this header too.
#pragma once

#include <cstdint>

#include "contact_rows_wide.hpp"

namespace ragdoll_sim {

// The double geometry of a ContactBlock's manifolds, lane i of each field lane i's; whole
// cache lines. A padding lane has count 0 and body 0: it is computed but nothing is stored.
struct alignas(64) ContactSeparationBlock {
  int32_t body_a[kRowBlock], body_b[kRowBlock];  // any body, static ones too
  int32_t count[kRowBlock];                      // the lane's points
  double n[3][kRowBlock];                        // the normal, A to B
  // Of each point, from the step's prepare: the lever arms rA, rB and base_separation.
  double r_a[kBlockPoints][3][kRowBlock], r_b[kBlockPoints][3][kRowBlock];
  double base[kBlockPoints][kRowBlock];
  double separation[kBlockPoints][kRowBlock];  // as the last update computed them
};

// Blocks [0, count): the separations of each lane's points into `geometry` and, rounded, into
// the points' float lanes of `blocks`. Four lanes at a time where the CPU has AVX2, else two.
void updateBlockSeparations(ContactSeparationBlock* geometry, ContactBlock* blocks, int count,
                            const LaneBodies& bodies);

// The two widths (the AVX one only where cpuHasAvx2()); the tests call them directly.
namespace contact_separations_w2 {
void update(ContactSeparationBlock* geometry, ContactBlock* blocks, int count,
            const LaneBodies& bodies);
}
namespace contact_separations_w4 {
void update(ContactSeparationBlock* geometry, ContactBlock* blocks, int count,
            const LaneBodies& bodies);
}

}  // namespace ragdoll_sim
