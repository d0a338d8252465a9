// What every joint has whatever its type: the two bodies, the joint frames, the spring and
// break limits, and the results the World reports (force, torque, broken). The type structs
// (joint_ball.hpp, joint_hinge.hpp, joint_fixed.hpp, joint_prismatic.hpp) read and write it.
#pragma once

#include "ragdoll_sim/joint.hpp"

namespace ragdoll_sim {

struct JointBase {
  template <class Def>
  explicit JointBase(const Def& def)
      : a(def.body_a.index), b(def.body_b.index), frame_a(def.frame_a), frame_b(def.frame_b),
        spring(def.spring) {}

  int a = -1, b = -1;          // body / solver-body indices
  Transform frame_a, frame_b;  // joint frames in the link frames
  JointSpring spring;
  bool broken = false;
  bool overloaded = false;  // the anchor reached break_force in this substep
  bool sweeps_in_lanes = false;  // every row the sweeps would solve is in the wide pass this step
  int moved_sweep = 0;  // the last position sweep of the step in which it moved a body
  double force = 0.0;  // N in the anchor during the last substep
  double torque = 0.0;  // N m in a fixed joint's rotation lock during the last substep
  double impulse_h = 0.0;  // s: the substep the parts' impulses were accumulated over

  Quat frameRotationA(const Quat& qa) const { return qa * frame_a.q; }
  Quat frameRotationB(const Quat& qb) const { return qb * frame_b.q; }
};

}  // namespace ragdoll_sim
