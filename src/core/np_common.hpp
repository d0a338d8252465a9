// Internal narrowphase vocabulary shared by the pair routines: fixed-capacity candidate and
// clip buffers (no heap in collide()), the 4-point manifold reduction, segment closest points,
// polygon clipping with feature ids, and the pair routines that live in their own files.
#pragma once

#include <cstdint>

#include "narrowphase.hpp"

namespace ragdoll_sim {
namespace np {

struct Candidate {
  Vec3 point;
  double separation;
  uint32_t id;
};

struct Candidates {
  static constexpr int kCap = 64;
  Candidate c[kCap];
  int n = 0;
  // pB lies on the surface of B; the stored point is midway between the two surfaces. When
  // full, the new point replaces the shallowest one if it is deeper.
  void add(const Vec3& pB, const Vec3& normal, double sep, uint32_t id) {
    const Candidate cand{pB - 0.5 * sep * normal, sep, id};
    if (n < kCap) {
      c[n++] = cand;
      return;
    }
    int worst = 0;
    for (int i = 1; i < n; ++i)
      if (c[i].separation > c[worst].separation) worst = i;
    if (sep < c[worst].separation) c[worst] = cand;
  }
};

// Fills `out` (normal given) with the candidates whose separation is below `speculative`:
// all of them when at most 4, else the deepest plus the three that maximise the area.
void reduce(const Vec3& normal, const Candidates& cs, double speculative, Manifold& out);

// Parameters s, t in [0,1] of the closest points of segments p1 + s d1 and p2 + t d2.
void closestSegmentParams(const Vec3& p1, const Vec3& d1, const Vec3& p2, const Vec3& d2,
                          double& s, double& t);

// Two points for near-parallel segment cores pa + s da (radius ra) and pb + t db (radius rb)
// whose projections overlap: B's core clipped to A's slab, each end against its closest point
// on A, separations along n. Adds nothing otherwise.
void parallelSegments(const Vec3& pa, const Vec3& da, double ra, const Vec3& pb, const Vec3& db,
                      double rb, const Vec3& n, Candidates& cs);

// Polygon (or a segment when n == 2) being clipped. Each vertex has a 16-bit id: an original
// vertex keeps its own; a vertex made by plane j cutting the edge labelled L gets
// 0x8000 | L << 7 | j. `label` names the edge leaving the vertex (an original edge index, or
// 0x80 | j for a stretch along plane j).
struct ClipPoly {
  static constexpr int kCap = 64;
  struct Vert {
    Vec3 p;
    uint16_t id;
    uint8_t label;
  };
  Vert v[kCap];
  int n = 0;
  void push(const Vec3& p, uint16_t id, uint8_t label) {
    if (n < kCap) v[n++] = {p, id, label};
  }
};

// Keeps the part of `poly` inside the prism over the convex polygon ref[0..m) (counter-clockwise
// about its normal `n`).
void clipToPrism(ClipPoly& poly, const Vec3* ref, int m, const Vec3& n);

// Manifold id: the reference and incident feature indices, whether the reference is B, and
// the 16-bit point id.
inline uint32_t contactId(int ref_feature, int inc_feature, bool ref_is_b, uint16_t point) {
  return uint32_t(ref_feature & 0xFF) << 24 | uint32_t(inc_feature & 0x7F) << 17 |
         uint32_t(ref_is_b) << 16 | point;
}

// Pair routines (a and b in the order named; normal from a to b).
void collideBoxBox(const Geometry& a, const Transform& xa, const Geometry& b,
                   const Transform& xb, double speculative, Manifold& out);
// Box or hull against box or hull: SAT with Gauss-map pruned edge pairs.
void collidePolytopes(const Geometry& a, const Transform& xa, const Geometry& b,
                      const Transform& xb, double speculative, Manifold& out);
// Any two convex shapes: GJK/EPA on the cores, then clipping of the support features.
void collideConvex(const Geometry& a, const Transform& xa, const Geometry& b,
                   const Transform& xb, double speculative, Manifold& out,
                   const Vec3* guess = nullptr);

}  // namespace np
}  // namespace ragdoll_sim
