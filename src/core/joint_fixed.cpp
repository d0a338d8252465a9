// Fixed joint (weld): anchor (rigid point part or spring, joint.cpp) + rotation lock
// (part_angle_lock.hpp, 3 angular rows); this file prepares both.
#include "joint.hpp"

namespace ragdoll_sim {

void prepareFixedJoint(Joint& j, const StepContext& ctx) {
  const auto& m = *ctx.motions;
  j.point.prepare(m[j.a], m[j.b], j.frame_a.p, j.frame_b.p);
  j.angle_lock.prepare(j.frameRotationA(m[j.a].q), j.frameRotationB(m[j.b].q));
}

}  // namespace ragdoll_sim
