// prepareBlockRows (contact_geometry.hpp) written once for a lane type D, Double2 or Double4
// (double_lanes.hpp). Each lane does exactly the IEEE operations, in the order, of contactRow's
// Eigen expressions (contact_solver.hpp; EIGEN_DONT_VECTORIZE, no fused multiply-add), so its
// bits are those of, for the normal and each tangent d of the manifold:
//   angA = rA x d,  angB = rB x d,  iangA = IA^-1 angA,  iangB = IB^-1 angB,
//   k = ((1/mA + 1/mB) + angA . iangA) + angB . iangB,  mass = k > 0 ? 1 / k : 0
// with a x b and a . b as in point_frames_kernel.hpp, and M v row by row as a . b (Eigen's
// lazy product: the same halved reduction). A static body's inverse mass and inertia are 0.
// As double_lanes.hpp: no std headers or Eigen, and an inline namespace per instruction set.
#pragma once

#include "contact_geometry.hpp"
#include "point_frames_kernel.hpp"

#if defined(__AVX2__)
#define RAGDOLL_SIM_ROW_LANES_ISA contact_row_lanes_avx2
#else
#define RAGDOLL_SIM_ROW_LANES_ISA contact_row_lanes_sse2
#endif

namespace ragdoll_sim {
namespace contact_row_lanes {
inline namespace RAGDOLL_SIM_ROW_LANES_ISA {

using double_lanes::gather;
using double_lanes::storeFloats;
using point_frames::cross;
using point_frames::dot;
using point_frames::laneFields;
using point_frames::loadVector;
using point_frames::storeLanes;

// out = M x, M column by column (Eigen's storage).
template <class D>
inline void multiply(const D m[9], const D x[3], D out[3]) {
  for (int i = 0; i < 3; ++i) out[i] = m[i] * x[0] + (m[i + 3] * x[1] + m[i + 6] * x[2]);
}

// The row along d (the double lanes of contactRow): its lever-arm terms and its mass.
// masses: 1/mA + 1/mB; ia, ib: the inverse inertias, column by column.
template <class D>
inline D row(const D ra[3], const D rb[3], const D d[3], const D ia[9], const D ib[9], D masses,
             D ang_a[3], D ang_b[3], D iang_a[3], D iang_b[3]) {
  cross(ra, d, ang_a);
  cross(rb, d, ang_b);
  multiply(ia, ang_a, iang_a);
  multiply(ib, ang_b, iang_b);
  const D k = (masses + dot(ang_a, iang_a)) + dot(ang_b, iang_b);
  return k > 0.0 ? 1.0 / k : D{};
}

// A vector rounded into lanes [o, o + W) of a field; lanes without the point get 0 (a zero row
// with mass 0 takes no impulse).
template <class D, class M>
inline void storeVector(const D x[3], M has_point, int o, float (&field)[3][kRowBlock]) {
  for (int j = 0; j < 3; ++j) storeFloats(has_point ? x[j] : D{}, field[j] + o);
}

// Lanes [o, o + W) of one block.
template <class D>
inline void rowLanes(ContactGeometryBlock& g, ContactBlock& b, int o, const LaneBodies& bodies) {
  constexpr int W = sizeof(D) / sizeof(double);
  const double *ma[W], *mb[W], *ia[W], *ib[W];
  laneFields<W>(bodies, g.body_a + o, kLaneInvMass, ma);
  laneFields<W>(bodies, g.body_b + o, kLaneInvMass, mb);
  laneFields<W>(bodies, g.body_a + o, kLaneInvInertia, ia);
  laneFields<W>(bodies, g.body_b + o, kLaneInvInertia, ib);
  D inv_mass_a[1], inv_mass_b[1], inertia_a[9], inertia_b[9];
  gather<1>(ma, inv_mass_a);
  gather<1>(mb, inv_mass_b);
  gather<9>(ia, inertia_a);
  gather<9>(ib, inertia_b);
  const D masses = inv_mass_a[0] + inv_mass_b[0];
  D d[3][3];  // the normal and the tangents
  loadVector(g.n, o, d[0]);
  loadVector(g.t[0], o, d[1]);
  loadVector(g.t[1], o, d[2]);
  D count;
  for (int l = 0; l < W; ++l) count[l] = double(g.count[o + l]);
  for (int p = 0; p < b.points; ++p) {
    const auto has_point = double(p) < count;
    D ra[3], rb[3];
    loadVector(g.r_a[p], o, ra);
    loadVector(g.r_b[p], o, rb);
    for (int k = 0; k < 3; ++k) {
      D ang_a[3], ang_b[3], iang_a[3], iang_b[3];
      const D mass = row(ra, rb, d[k], inertia_a, inertia_b, masses, ang_a, ang_b, iang_a, iang_b);
      ContactRowLanes& out = b.point[p].row[k];
      storeVector(ang_a, has_point, o, out.ang_a);
      storeVector(ang_b, has_point, o, out.ang_b);
      storeVector(iang_a, has_point, o, out.iang_a);
      storeVector(iang_b, has_point, o, out.iang_b);
      storeFloats(has_point ? mass : D{}, out.mass + o);
      if (k == 0) storeLanes(mass, g.normal_mass[p] + o);
    }
  }
}

// Blocks [0, count), W lanes at a time, padding lanes too: the block is not zeroed there.
template <class D>
inline void prepareBlocks(ContactGeometryBlock* geometry, ContactBlock* blocks, int count,
                          const LaneBodies& bodies) {
  constexpr int W = sizeof(D) / sizeof(double);
  for (int k = 0; k < count; ++k)
    for (int o = 0; o < kRowBlock; o += W) rowLanes<D>(geometry[k], blocks[k], o, bodies);
}

}  // namespace RAGDOLL_SIM_ROW_LANES_ISA
}  // namespace contact_row_lanes
}  // namespace ragdoll_sim
