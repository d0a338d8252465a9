// The double geometry of the wide contact blocks (contact_wide.hpp), which the double-lane
// kernels read: the separations (contact_separations.hpp) and the friction rows
// (contact_friction_rows.hpp). A plain record: the AVX2 kernel files include this header too.
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
  double separation[kBlockPoints][kRowBlock];  // as the last update computed them
};

}  // namespace ragdoll_sim
