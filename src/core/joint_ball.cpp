// Ball joint: anchor + one motor / limit per Euler angle (joint.cpp), or swing-twist limits
// (part_swing_twist.hpp); this file gives the angles and their Jacobian rows (derivations in
// joint_angles.hpp).
#include "joint.hpp"

namespace ragdoll_sim {

void prepareBallJoint(Joint& j, const StepContext& ctx) {
  const auto& m = *ctx.motions;
  j.point.prepare(m[j.a], m[j.b], j.frame_a.p, j.frame_b.p);
}

void updateBallAngles(Joint& j, const StepContext& ctx) {
  const bool euler = j.angleRowsNeeded();
  if (!euler && !j.swing_twist_limits) {
    j.angle_count = 0;
    return;
  }
  const auto& m = *ctx.motions;
  const auto& s = *ctx.bodies;
  const Quat fa = j.frameRotationA(s[j.a].dq * m[j.a].q);
  const Quat fb = j.frameRotationB(s[j.b].dq * m[j.b].q);
  if (j.swing_twist_limits) j.swing_twist.update(fa, fb, j.twist_axis);
  if (!euler) {
    j.angle_count = 0;
    return;
  }
  Vec3 t;
  j.angle_count = j.euler.angles(fa, fb, t, &j.angle_rows) ? 3 : 0;
  j.angles = {t[0], t[1], t[2]};
}

}  // namespace ragdoll_sim
