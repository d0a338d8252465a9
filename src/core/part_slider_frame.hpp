// Prismatic joint geometry: anchor pA (fixed in A), anchor pB (fixed in B), d = pB - pA, and
// the slide axis a with two perpendiculars n1, n2, all fixed in A.
// A row on C = u . d for a unit u fixed in A (u = a: slide position; u = n1, n2: off-axis):
//   Cdot = u . (vB + wB x rB - vA - wA x rA) + d . (wA x u)
//        = u . (vB - vA) + (rB x u) . wB - ((rA + d) x u) . wA
//   J    = [ -u  -(rA + d) x u  u  rB x u ]
// i.e. a LinearRow (part_rows.hpp) with lever arm rA + d for A and rB for B: the impulse acts
// at pB on both bodies, so it keeps angular momentum as well as momentum.
// Tracked through the substeps like PointPart: anchors rotated by the bodies' delta rotations,
// centres moved by their delta positions.
#pragma once

#include "body.hpp"
#include "solver_context.hpp"

namespace ragdoll_sim {

struct SliderPose {
  Vec3 rA, rB;  // anchors from the COMs (world)
  Vec3 d;       // pB - pA
  Vec3 axis, n1, n2;
  double position() const { return axis.dot(d); }
  Vec3 leverA() const { return rA + d; }
};

struct SliderFrame {
  Vec3 rA0 = Vec3::Zero(), rB0 = Vec3::Zero(), delta_center = Vec3::Zero();
  Vec3 axis0 = Vec3::UnitX(), n1_0 = Vec3::UnitY(), n2_0 = Vec3::UnitZ();

  // Anchors in each body's link frame; axis and n1 in A's link frame (unit, perpendicular).
  // n1 is fixed in A so that the line part's impulse keeps its meaning while A turns (and
  // World::jointWrench reads it back at A's current pose).
  void prepare(const BodyMotion& A, const BodyMotion& B, const Vec3& anchor_a,
               const Vec3& anchor_b, const Vec3& axis_in_a, const Vec3& n1_in_a) {
    rA0 = A.q * (anchor_a - A.local_com);
    rB0 = B.q * (anchor_b - B.local_com);
    delta_center = centerOffset(A, B);
    axis0 = A.q * axis_in_a;
    n1_0 = A.q * n1_in_a;
    n2_0 = axis0.cross(n1_0);
  }

  SliderPose at(const SolverBody& A, const SolverBody& B) const {
    SliderPose p;
    p.rA = A.dq * rA0;
    p.rB = B.dq * rB0;
    p.d = (B.dp - A.dp) + (p.rB - p.rA) + delta_center;
    p.axis = A.dq * axis0;
    p.n1 = A.dq * n1_0;
    p.n2 = A.dq * n2_0;
    return p;
  }
};

}  // namespace ragdoll_sim
