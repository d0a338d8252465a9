// Dispatch on joint type.
#include "joint.hpp"

namespace ragdoll_sim {

void prepareJoint(Joint& j, const StepContext& ctx) {
  if (j.type == JointType::Ball) prepareBallJoint(j, ctx);
  else prepareHingeJoint(j, ctx);
}

void warmStartJoint(Joint& j, const StepContext& ctx) {
  if (j.type == JointType::Ball) warmStartBallJoint(j, ctx);
  else warmStartHingeJoint(j, ctx);
}

void solveJoint(Joint& j, const StepContext& ctx, bool use_bias) {
  if (j.type == JointType::Ball) solveBallJoint(j, ctx, use_bias);
  else solveHingeJoint(j, ctx, use_bias);
}

}  // namespace ragdoll_sim
