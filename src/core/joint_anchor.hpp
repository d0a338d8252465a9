// The anchor of ball, hinge and fixed joints: the rigid point part (part_point.hpp), or, with
// spring.stiffness > 0, a Hooke spring on the same anchors solved once per substep in the
// biased pass. A rigid anchor's impulse is capped at break_force h: past it the joint breaks.
#pragma once

#include "joint_base.hpp"
#include "part_point.hpp"

namespace ragdoll_sim {

struct AnchorPart {
  PointPart point;
  // The sweeps leave the rigid point part, and a hinge's axis part with it, to the wide pass
  // (point_lanes.hpp), set per step.
  bool in_lanes = false;

  void prepare(const JointBase& j, const StepContext& ctx) {
    in_lanes = false;
    const auto& m = *ctx.motions;
    point.prepare(m[j.a], m[j.b], j.frame_a.p, j.frame_b.p);
  }

  // In the lanes, the anchors, K^-1 and the warm start are the wide pass's (PointLanes::load).
  void warmStart(const JointBase& j, SolverBody& A, SolverBody& B, const StepContext& ctx,
                 bool anchors_current) {
    if (in_lanes) return;
    const double k = j.spring.stiffness;
    point.updateMass(A, B, k > 0.0 ? PointPart::springGamma(k, j.spring.damping, ctx.h) : 0.0,
                     anchors_current);
    if (k > 0.0) return;
    point.warmStart(A, B);
  }

  void solve(JointBase& j, SolverBody& A, SolverBody& B, const StepContext& ctx, bool use_bias) {
    if (j.spring.stiffness > 0.0) {
      if (use_bias) j.force = point.solveSpring(A, B, j.spring.stiffness, j.spring.damping, ctx.h);
      return;
    }
    if (in_lanes) return;
    const double max_impulse = j.spring.break_force * ctx.h;
    if (point.solve(A, B, ctx.joint_softness, use_bias, max_impulse)) j.overloaded = true;
  }

  // After a substep's last sweep: a rigid anchor's force is its impulse accumulated over the
  // substep (a spring's is set by its solve).
  void setForce(JointBase& j, const StepContext& ctx) const {
    if (!(j.spring.stiffness > 0.0)) j.force = point.impulse.norm() * ctx.inv_h;
  }

  // After the position update: the relax sweeps see the moved anchors (in the lanes,
  // PointLanes::refreshAnchors moves them).
  void refresh(const SolverBody& A, const SolverBody& B) {
    if (!in_lanes) point.refresh(A, B);
  }

  bool project(const JointBase& j, SolverBody& A, SolverBody& B, const StepContext& ctx) const {
    if (j.spring.stiffness > 0.0) return false;  // a spring anchor is meant to stretch
    return point.project(A, B, ctx.settings->max_position_correction, ctx.settings->joint_slop);
  }

  void scaleImpulses(double s) { point.impulse *= s; }
  void clearWarmStart() { point = PointPart(); }
};

}  // namespace ragdoll_sim
