// Ball joint = anchor (point part or spring) + optional angle-motor and angle-limit parts per
// Euler axis
// (joint_angles.hpp has the angle decomposition and its Jacobian).
#include "joint.hpp"

namespace ragdoll_sim {

namespace {
// Current joint-frame rotations and Euler angles with their Jacobian rows.
bool ballLimitRows(const Joint& j, const StepContext& ctx, Vec3& t, std::array<Vec3, 3>& rows) {
  const auto& m = *ctx.motions;
  const auto& s = *ctx.bodies;
  const Quat fa = j.frameRotationA(s[j.a].dq * m[j.a].q);
  const Quat fb = j.frameRotationB(s[j.b].dq * m[j.b].q);
  t = j.euler.angles(fa, fb);
  return j.euler.rates(fa, t, rows);
}
}  // namespace

void prepareBallJoint(Joint& j, const StepContext& ctx) {
  const auto& m = *ctx.motions;
  j.point.prepare(m[j.a], m[j.b], j.frame_a.p, j.frame_b.p);
}

void warmStartBallJoint(Joint& j, const StepContext& ctx) {
  auto& s = *ctx.bodies;
  SolverBody &A = s[j.a], &B = s[j.b];
  if (j.angleRowsNeeded()) {
    Vec3 t;
    std::array<Vec3, 3> rows;
    if (ballLimitRows(j, ctx, t, rows))
      for (int i = 0; i < 3; ++i) {
        j.motor_parts[i].warmStart(A, B, rows[i]);
        if (j.limits_enabled) j.limits3[i].warmStart(A, B, rows[i]);
      }
  }
  warmStartAnchor(j, A, B);
}

void solveBallJoint(Joint& j, const StepContext& ctx, bool use_bias) {
  auto& s = *ctx.bodies;
  SolverBody &A = s[j.a], &B = s[j.b];
  if (j.angleRowsNeeded()) {
    Vec3 t;
    std::array<Vec3, 3> rows;
    if (ballLimitRows(j, ctx, t, rows))
      for (int i = 0; i < 3; ++i) {
        j.motor_parts[i].solve(A, B, rows[i], t[i], j.motors[i], ctx, use_bias);
        if (j.limits_enabled)
          j.limits3[i].solve(A, B, rows[i], t[i], j.lower3[i], j.upper3[i], ctx, use_bias);
      }
  }
  solveAnchor(j, A, B, ctx, use_bias);
}

}  // namespace ragdoll_sim
