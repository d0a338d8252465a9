#include "lane_bodies.hpp"

#include <cstddef>

#include "body.hpp"

namespace ragdoll_sim {

LaneBodies laneBodies(SolverBody* first) {
  static_assert(offsetof(SolverBody, w) == offsetof(SolverBody, v) + 3 * sizeof(double) &&
                    offsetof(SolverBody, inv_mass) ==
                        offsetof(SolverBody, v) + kLaneInvMass * sizeof(double),
                "the kernels read w and the inverse mass right after v");
  static_assert(offsetof(SolverBody, dq) == offsetof(SolverBody, v) + kLaneDq * sizeof(double) &&
                    offsetof(SolverBody, dp) == offsetof(SolverBody, v) + kLaneDp * sizeof(double),
                "the anchor kernels find dq and dp at kLaneDq and kLaneDp");
  static_assert(offsetof(SolverBody, inv_inertia) ==
                        offsetof(SolverBody, v) + kLaneInvInertia * sizeof(double) &&
                    sizeof(Mat3) == 9 * sizeof(double) && !Mat3::IsRowMajor,
                "the row kernel reads the inverse inertia at kLaneInvInertia");
  static_assert(sizeof(SolverBody) % (4 * sizeof(double)) == 0 && alignof(SolverBody) >= 32,
                "the kernels load v with aligned 32-byte loads");
  return {first ? first->v.data() : nullptr, int(sizeof(SolverBody) / sizeof(double))};
}

}  // namespace ragdoll_sim
