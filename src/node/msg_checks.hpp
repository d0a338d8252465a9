// Checks of the geometry messages that services take (poses, twists): a value or an error that
// names the problem and the rule, with a short throttle key for the WARN.
#pragma once

#include <string>

#include <geometry_msgs/Pose.h>
#include <geometry_msgs/Twist.h>

#include "ragdoll_sim/math.hpp"

namespace ragdoll_sim {
namespace node {

// A pose from a message, or "" and the error naming the problem (*problem: its throttle key):
// position finite and within max_position of the origin; orientation finite and a unit
// quaternion within a tolerance (normalized then), or all zeros, which means identity (an unset
// Pose, e.g. rosservice call without an orientation).
std::string poseFromMsg(const geometry_msgs::Pose& m, double max_position, Transform* t,
                        std::string* problem);

// A twist from a message, or the error (*problem: its throttle key): finite, |linear| at most
// max_linear (m/s) and |angular| at most max_angular (rad/s).
std::string twistFromMsg(const geometry_msgs::Twist& m, double max_linear, double max_angular,
                         Vec3* v, Vec3* w, std::string* problem);

}  // namespace node
}  // namespace ragdoll_sim
