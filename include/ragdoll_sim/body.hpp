// Body definitions. A body's frame is its link frame (as in URDF); mass properties are given
// about the centre of mass `com` expressed in that frame. The solver works on the COM.
#pragma once

#include <cstdint>
#include <string>

#include "ragdoll_sim/math.hpp"

namespace ragdoll_sim {

struct BodyId {
  int32_t index = -1;
  bool valid() const { return index >= 0; }
  bool operator==(BodyId o) const { return index == o.index; }
  bool operator!=(BodyId o) const { return index != o.index; }
};

enum class BodyType : uint8_t { Static, Dynamic };

struct BodyDef {
  BodyType type = BodyType::Dynamic;
  std::string name;
  Transform pose;                       // link frame in world
  Vec3 linear_velocity = Vec3::Zero();  // of the centre of mass, world
  Vec3 angular_velocity = Vec3::Zero(); // world
  double mass = 1.0;                    // kg, ignored for static bodies
  Vec3 com = Vec3::Zero();              // centre of mass in the link frame
  Mat3 inertia = Mat3::Identity() * 0.01;  // about the COM, link-frame axes (kg m^2)
  double linear_damping = 0.0;          // 1/s: dv/dt = -c v
  double angular_damping = 0.0;         // 1/s
  double gravity_scale = 1.0;
};

// State of a body as seen from outside.
struct BodyState {
  Transform pose;            // link frame in world
  Vec3 com_position;         // world
  Vec3 linear_velocity;      // of the COM
  Vec3 angular_velocity;
};

}  // namespace ragdoll_sim
