// The joint step functions: a switch on the type (Joint::visit) that ends in a call to the
// type's own step function (joint_<type>.cpp); and firstSubstepAngles, the angles of several
// joints at once.
#include "joint.hpp"

#include <vector>

#include "joint_angles.hpp"
#include "joint_angles_lanes.hpp"

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

void firstSubstepAngles(Joint* const* joints, int count, const StepContext& ctx) {
  thread_local std::vector<HingeAngleJob> hinge_jobs;
  thread_local std::vector<EulerAngleJob> ball_jobs;
  thread_local std::vector<Joint*> hinges, balls;  // job k's joint
  thread_local std::vector<double> ok;  // a ball job's: 0 near gimbal lock (no rows)
  hinge_jobs.clear();
  ball_jobs.clear();
  hinges.clear();
  balls.clear();
  ok.resize(size_t(count));
  const auto& s = *ctx.bodies;
  const auto& m = *ctx.motions;
  for (int k = 0; k < count; ++k) {
    Joint& j = *joints[k];
    if (j.broken) continue;
    const SolverBody &A = s[j.a], &B = s[j.b];
    if (HingeJoint* h = std::get_if<HingeJoint>(&j.kind)) {
      if (!h->axes.rowsNeeded()) continue;
      hinges.push_back(&j);
      hinge_jobs.push_back(h->angleJob(currentFrames(j, A, B, m)));
    } else if (BallJoint* b = std::get_if<BallJoint>(&j.kind)) {
      if (b->swing_twist_limits || !b->axes.rowsNeeded()) continue;
      balls.push_back(&j);
      ball_jobs.push_back(b->angleJob(currentFrames(j, A, B, m), &ok[ball_jobs.size()]));
    }
  }
  hingeAngles(hinge_jobs.data(), int(hinge_jobs.size()));
  eulerAngles(ball_jobs.data(), int(ball_jobs.size()));
  const auto take = [&](Joint& j, auto& axes, int rows) {
    axes.count = rows;
    axes.fresh = true;
    axes.batched = true;
    axes.updateMass(s[j.a], s[j.b]);
  };
  for (Joint* j : hinges) take(*j, std::get<HingeJoint>(j->kind).axes, 1);
  for (size_t k = 0; k < balls.size(); ++k)
    take(*balls[k], std::get<BallJoint>(balls[k]->kind).axes, ok[k] != 0.0 ? 3 : 0);
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
