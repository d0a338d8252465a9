// Joint definitions. Every joint is placed by a joint frame fixed in body A (frame_a, in A's
// link frame) and one fixed in body B (frame_b); at zero angles the two frames coincide.
#pragma once

#include <array>
#include <cstdint>
#include <limits>

#include "ragdoll_sim/body.hpp"

namespace ragdoll_sim {

struct JointId {
  int32_t index = -1;
  bool valid() const { return index >= 0; }
  bool operator==(JointId o) const { return index == o.index; }
};

enum class JointType : uint8_t { Ball, Hinge };

// Ball joint: anchors coincide. Optional limits on the Euler angles of B's joint frame relative
// to A's, decomposed about three orthonormal joint-frame axes in the order given (the meaning
// of a chain of three revolute joints with coincident origins: R = R(a0,t0) R(a1,t1) R(a2,t2)).
struct BallJointDef {
  BodyId body_a, body_b;
  Transform frame_a, frame_b;
  std::array<Vec3, 3> axes = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
  bool enable_limits = false;
  std::array<double, 3> lower = {0, 0, 0};
  std::array<double, 3> upper = {0, 0, 0};
  bool collide_connected = false;
};

// Hinge: anchors coincide and B rotates relative to A about `axis` (joint frame, unit).
// The angle is positive by the right-hand rule about the axis, 0 when the frames coincide.
struct HingeJointDef {
  BodyId body_a, body_b;
  Transform frame_a, frame_b;
  Vec3 axis = Vec3::UnitZ();
  bool enable_limit = false;
  double lower = 0.0, upper = 0.0;
  bool collide_connected = false;
};

}  // namespace ragdoll_sim
