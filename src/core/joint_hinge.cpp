// Hinge joint: anchor + hinge-axis part (2 angular rows) + motor / limit on the hinge angle
// (joint.cpp); this file prepares the axis part and gives the angle and its row.
#include "joint.hpp"

namespace ragdoll_sim {

void prepareHingeJoint(Joint& j, const StepContext& ctx) {
  const auto& m = *ctx.motions;
  j.point.prepare(m[j.a], m[j.b], j.frame_a.p, j.frame_b.p);
  j.hinge_axis.prepare(m[j.a], m[j.b], j.frame_a.q * j.axis, j.frame_b.q * j.axis);
}

void updateHingeAngles(Joint& j, const StepContext& ctx) {
  const auto& m = *ctx.motions;
  const auto& s = *ctx.bodies;
  const Quat fa = j.frameRotationA(s[j.a].dq * m[j.a].q);
  const Quat fb = j.frameRotationB(s[j.b].dq * m[j.b].q);
  j.angle_rows[0] = fa * j.axis;
  j.angles[0] = hingeAngle(fa, fb, j.axis);
  j.angle_count = 1;
}

}  // namespace ragdoll_sim
