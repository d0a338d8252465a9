// The anatomy parameters of config/joints.yaml: a ball joint's `cone` / `twist` in a ~joints
// entry and ~link_damping (per-link velocity damping), read into the SceneDef.
#pragma once

#include <xmlrpcpp/XmlRpcValue.h>

#include <string>

#include "ragdoll_sim/scene.hpp"

namespace ros {
class NodeHandle;
}

namespace ragdoll_sim {
namespace node {

// A ~joints entry's `cone` (a number: circular, or [about axes[1], about axes[2]]) or `twist`
// ([lower, upper]) into *s; false with *error naming `where`/key when it is not that shape.
bool readSwingTwistKey(const std::string& key, XmlRpc::XmlRpcValue& value,
                       const std::string& where, JointSettings* s, std::string* error);

// ~link_damping: {link name or "*": {linear, angular}} (1/s); false with *error naming the
// parameter and the field.
bool loadLinkDamping(const ros::NodeHandle& pnh, SceneDef* scene, std::string* error);

}  // namespace node
}  // namespace ragdoll_sim
