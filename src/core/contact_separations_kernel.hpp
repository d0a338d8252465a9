// updateBlockSeparations (contact_geometry.hpp) written once for a lane type D, Double2 or
// Double4 (double_lanes.hpp). Each lane does exactly the IEEE operations, in the order, of the
// Eigen expressions of updateSeparations (contact_solver.cpp; EIGEN_DONT_VECTORIZE, no fused
// multiply-add), so its bits are those of
//   dpn = (dpB - dpA) . n,  nA = dqA^* n,  nB = dqB^* n,
//   s = ((dpn + rB . nB) - rA . nA) + base_separation       for each point of the manifold
// with q^* = (-x, -y, -z, w) and q v and a . b as in point_frames_kernel.hpp.
// As double_lanes.hpp: no std headers or Eigen, and an inline namespace per instruction set.
#pragma once

#include "contact_geometry.hpp"
#include "point_frames_kernel.hpp"

#if defined(__AVX2__)
#define RAGDOLL_SIM_SEPARATIONS_ISA contact_separations_avx2
#else
#define RAGDOLL_SIM_SEPARATIONS_ISA contact_separations_sse2
#endif

namespace ragdoll_sim {
namespace contact_separations {
inline namespace RAGDOLL_SIM_SEPARATIONS_ISA {

using double_lanes::gather;
using double_lanes::lane;
using point_frames::dot;
using point_frames::laneFields;
using point_frames::loadLanes;
using point_frames::loadVector;
using point_frames::rotate;
using point_frames::storeLanes;

// Lanes [o, o + W) of one block.
template <class D>
inline void separationLanes(ContactGeometryBlock& g, ContactBlock& b, int o,
                            const LaneBodies& bodies) {
  constexpr int W = sizeof(D) / sizeof(double);
  const double *qa[W], *qb[W], *pa[W], *pb[W];
  laneFields<W>(bodies, g.body_a + o, kLaneDq, qa);
  laneFields<W>(bodies, g.body_b + o, kLaneDq, qb);
  laneFields<W>(bodies, g.body_a + o, kLaneDp, pa);
  laneFields<W>(bodies, g.body_b + o, kLaneDp, pb);
  D dqa[4], dqb[4], dpa[3], dpb[3], n[3];
  gather<4>(qa, dqa);
  gather<4>(qb, dqb);
  gather<3>(pa, dpa);
  gather<3>(pb, dpb);
  loadVector(g.n, o, n);
  for (int j = 0; j < 3; ++j) {
    dqa[j] = -dqa[j];  // the conjugates
    dqb[j] = -dqb[j];
  }
  D d[3], na[3], nb[3];
  for (int j = 0; j < 3; ++j) d[j] = dpb[j] - dpa[j];
  const D dpn = dot(d, n);
  rotate(dqa, n, na);
  rotate(dqb, n, nb);
  for (int p = 0; p < b.points; ++p) {
    D ra[3], rb[3];
    loadVector(g.r_a[p], o, ra);
    loadVector(g.r_b[p], o, rb);
    const D s = ((dpn + dot(rb, nb)) - dot(ra, na)) + loadLanes<D>(g.base[p] + o);
    storeLanes(s, g.separation[p] + o);
    for (int l = 0; l < W; ++l)
      if (p < g.count[o + l]) b.point[p].separation[o + l] = float(lane(s, l));
  }
}

// Blocks [0, count), W lanes at a time up to the first padding lane's group.
template <class D>
inline void updateBlocks(ContactGeometryBlock* geometry, ContactBlock* blocks, int count,
                         const LaneBodies& bodies) {
  constexpr int W = sizeof(D) / sizeof(double);
  for (int k = 0; k < count; ++k)
    for (int o = 0; o < kRowBlock && geometry[k].count[o] > 0; o += W)
      separationLanes<D>(geometry[k], blocks[k], o, bodies);
}

}  // namespace RAGDOLL_SIM_SEPARATIONS_ISA
}  // namespace contact_separations
}  // namespace ragdoll_sim
