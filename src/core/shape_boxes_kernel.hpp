// The collide phase's shape boxes on plain arrays, written once for a lane type D: double (one
// shape), Double2 (two in an SSE2 register, the x86-64 baseline) or Double4 (four in an AVX
// register, shape_boxes_w4.cpp, compiled with -mavx2 -mno-fma), the lanes of double_lanes.hpp.
// Each lane does the IEEE operations, in the order, of the Eigen code it replaces
// (World::Impl::computeBox, shape_boxes.cpp), so every type gives its bits:
//   f = (q (p_local - com), q q_local);  R = f.q.toRotationMatrix();  c = x + f.p;
//   box {c - e, c + e} grown by spec + |v dt| on each axis,
// where e is the shape's half extent along the world axes: a sphere's radius; a capsule's
// h |R_z| + r; a box's |R| half (Eigen's row sums a0 + (a1 + a2)); a cylinder's
// h |R_z,i| + r sqrt(max(0, 1 - R_z,i^2)).
// As lanes.hpp: no std headers or Eigen (the AVX file includes this), and an inline namespace
// per instruction set, so that no AVX copy of an inline function replaces a baseline one.
#pragma once

#include "double_lanes.hpp"

#if defined(__AVX2__)
#define RAGDOLL_SIM_SHAPE_BOXES_ISA shape_boxes_avx2
#else
#define RAGDOLL_SIM_SHAPE_BOXES_ISA shape_boxes_sse2
#endif

namespace ragdoll_sim {
namespace shape_boxes {

// The kinds of shape the lanes bound (a hull's box is a loop over its vertices: scalar).
enum BoxKind { kSphereBox, kCapsuleBox, kBoxBox, kCylinderBox, kBoxKinds };

// One shape's inputs and outputs. size: the sphere's, capsule's or cylinder's radius followed by
// its half height (Geometry::radius, half_height), or the box's half extents.
struct ShapeBoxJob {
  const double *x, *q, *v, *com;  // the body's centre, rotation (x, y, z, w), velocity, local COM
  const double *local_p, *local_q, *size;
  double *frame_p, *frame_q, *lo, *hi;
};

inline namespace RAGDOLL_SIM_SHAPE_BOXES_ISA {

using namespace double_lanes;

// std::max(0.0, x) (a NaN gives 0), for a lane type or a double.
template <class D>
inline D atLeastZero(D x) {
  return D() + 0.0 < x ? x : D() + 0.0;
}

// jobs[0, count) of one kind, W = sizeof(D) / 8 at a time; count a multiple of W.
template <int kKind, class D>
inline void shapeBoxes(const ShapeBoxJob* jobs, int count, double spec, double dt) {
  constexpr int W = sizeof(D) / sizeof(double);
  constexpr int kSize = kKind == kBoxBox ? 3 : 2;
  const D specl = D() + spec, dtl = D() + dt;
  for (int k = 0; k < count; k += W) {
    const double *x[W], *q[W], *v[W], *com[W], *lp[W], *lq[W], *size[W];
    double *fp[W], *fq[W], *lo[W], *hi[W];
    for (int l = 0; l < W; ++l) {
      const ShapeBoxJob& j = jobs[k + l];
      x[l] = j.x, q[l] = j.q, v[l] = j.v, com[l] = j.com;
      lp[l] = j.local_p, lq[l] = j.local_q, size[l] = j.size;
      fp[l] = j.frame_p, fq[l] = j.frame_q, lo[l] = j.lo, hi[l] = j.hi;
    }
    D xl[3], ql[4], vl[3], coml[3], lpl[3], lql[4], sizel[kSize];
    gather<3>(x, xl);
    gather<4>(q, ql);
    gather<3>(v, vl);
    gather<3>(com, coml);
    gather<3>(lp, lpl);
    gather<4>(lq, lql);
    gather<kSize>(size, sizel);
    D offset[3], fpl[3], fql[4], R[9], e[3], lol[3], hil[3];
    for (int i = 0; i < 3; ++i) offset[i] = lpl[i] - coml[i];
    rotate(ql, offset, fpl);
    quatProduct(ql, lql, fql);
    rotationMatrix(fql, R);
    for (int i = 0; i < 3; ++i) {
      if (kKind == kSphereBox) {
        e[i] = sizel[0];
      } else if (kKind == kCapsuleBox) {
        e[i] = sizel[1] * magnitude(R[6 + i]) + sizel[0];
      } else if (kKind == kBoxBox) {
        e[i] = magnitude(R[i]) * sizel[0] +
               (magnitude(R[3 + i]) * sizel[1] + magnitude(R[6 + i]) * sizel[2]);
      } else {
        const D w = R[6 + i];
        e[i] = sizel[1] * magnitude(w) + sizel[0] * squareRoot(atLeastZero((D() + 1.0) - w * w));
      }
      const D c = xl[i] + fpl[i];
      const D grow = specl + magnitude(vl[i] * dtl);
      lol[i] = (c - e[i]) - grow;
      hil[i] = (c + e[i]) + grow;
    }
    scatter<3>(fpl, fp);
    scatter<4>(fql, fq);
    scatter<3>(lol, lo);
    scatter<3>(hil, hi);
  }
}

// The same for jobs of `kind` (the callers' one switch over the kinds).
template <class D>
inline void shapeBoxesOf(int kind, const ShapeBoxJob* jobs, int count, double spec, double dt) {
  switch (kind) {
    case kSphereBox: return shapeBoxes<kSphereBox, D>(jobs, count, spec, dt);
    case kCapsuleBox: return shapeBoxes<kCapsuleBox, D>(jobs, count, spec, dt);
    case kBoxBox: return shapeBoxes<kBoxBox, D>(jobs, count, spec, dt);
    default: return shapeBoxes<kCylinderBox, D>(jobs, count, spec, dt);
  }
}

}  // namespace RAGDOLL_SIM_SHAPE_BOXES_ISA
}  // namespace shape_boxes

// The four-shape kernel (shape_boxes_w4.cpp), for a CPU with AVX2 (cpuHasAvx2); count a multiple
// of 4.
namespace shape_boxes_w4 {
void shapeBoxes(int kind, const shape_boxes::ShapeBoxJob* jobs, int count, double spec, double dt);
}  // namespace shape_boxes_w4
}  // namespace ragdoll_sim
