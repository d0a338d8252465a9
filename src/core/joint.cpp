// The joint step functions: a switch on the type (Joint::visit) that ends in a call to the
// type's own step function (joint_<type>.cpp).
#include "joint.hpp"

namespace ragdoll_sim {

void prepareJoint(Joint& j, const StepContext& ctx) {
  j.moved_sweep = 0;
  j.sweeps_in_lanes = false;
  if (j.impulse_h != ctx.h) {
    j.scaleImpulses(warmStartScale(j.impulse_h, ctx.h));
    j.impulse_h = ctx.h;
  }
  j.visit([&](auto& t) { t.prepare(j, ctx); });
}

void warmStartJoint(Joint& j, const StepContext& ctx, bool first_substep) {
  auto& s = *ctx.bodies;
  SolverBody &A = s[j.a], &B = s[j.b];
  j.visit([&](auto& t) { t.warmStart(j, A, B, ctx, first_substep); });
}

void solveJoint(Joint& j, const StepContext& ctx, bool use_bias) {
  auto& s = *ctx.bodies;
  SolverBody &A = s[j.a], &B = s[j.b];
  j.visit([&](auto& t) { t.solve(j, A, B, ctx, use_bias); });
}

bool breaksAfterSubstep(Joint& j, const StepContext& ctx) {
  if (j.broken) return false;
  j.visit([&](auto& t) { t.finishSubstep(j, ctx); });
  return j.overloaded || j.force > j.spring.break_force ||
         j.torque >= (1.0 - 1e-9) * j.spring.break_torque;
}

void advanceJoint(Joint& j, const StepContext& ctx) {
  auto& s = *ctx.bodies;
  const SolverBody &A = s[j.a], &B = s[j.b];
  j.visit([&](auto& t) { t.advance(j, A, B, ctx); });
}

bool projectJointLimits(Joint& j, const StepContext& ctx) {
  if (j.broken) return false;
  auto& s = *ctx.bodies;
  SolverBody &A = s[j.a], &B = s[j.b];
  return j.visit([&](auto& t) { return t.projectLimits(j, A, B, ctx); });
}

bool projectJointAnchor(Joint& j, const StepContext& ctx) {
  if (j.broken) return false;
  auto& s = *ctx.bodies;
  SolverBody &A = s[j.a], &B = s[j.b];
  return j.visit([&](auto& t) { return t.projectAnchor(j, A, B, ctx); });
}

}  // namespace ragdoll_sim
