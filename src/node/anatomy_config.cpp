#include "anatomy_config.hpp"

#include <ros/node_handle.h>
#include <xmlrpcpp/XmlRpcException.h>

#include <cmath>
#include <limits>

#include "link_damping.hpp"

namespace ragdoll_sim {
namespace node {

namespace {

// NaN for anything but a number.
double numberOf(XmlRpc::XmlRpcValue& v) {
  if (v.getType() == XmlRpc::XmlRpcValue::TypeInt) return double(int(v));
  if (v.getType() == XmlRpc::XmlRpcValue::TypeDouble) return double(v);
  return std::numeric_limits<double>::quiet_NaN();
}

}  // namespace

bool readSwingTwistKey(const std::string& key, XmlRpc::XmlRpcValue& value,
                       const std::string& where, JointSettings* s, std::string* error) {
  std::array<double, 2> pair;
  const bool cone = key == "cone";
  if (cone && (value.getType() == XmlRpc::XmlRpcValue::TypeInt ||
               value.getType() == XmlRpc::XmlRpcValue::TypeDouble)) {
    pair[0] = pair[1] = numberOf(value);
  } else if (value.getType() == XmlRpc::XmlRpcValue::TypeArray && value.size() == 2) {
    for (int k = 0; k < 2; ++k) pair[static_cast<size_t>(k)] = numberOf(value[k]);
  } else {
    *error = where + "/" + key +
             (cone ? " must be a number or a list of 2 numbers (rad, cone half-angles about the "
                     "ball's second and third axes)"
                   : " must be a list of 2 numbers (rad, [lower, upper] about the ball's first axis)");
    return false;
  }
  for (int k = 0; k < 2; ++k)
    if (std::isnan(pair[static_cast<size_t>(k)])) {
      *error = where + "/" + key + "[" + std::to_string(k) + "] must be a number (rad)";
      return false;
    }
  (cone ? s->cone : s->twist) = pair;
  return true;
}

bool loadLinkDamping(const ros::NodeHandle& pnh, SceneDef* scene, std::string* error) {
  const std::string where = "parameter " + pnh.resolveName("link_damping");
  try {
    XmlRpc::XmlRpcValue links;
    if (!pnh.getParam("link_damping", links)) return true;
    if (links.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
      *error = where + " must be a dictionary: link name (or \"*\") -> {linear, angular} (1/s)";
      return false;
    }
    for (auto& [name, value] : links) {
      const std::string at = where + "/" + name;
      if (value.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
        *error = at + " must be a dictionary {linear, angular} (1/s)";
        return false;
      }
      LinkDamping d;
      for (auto& [key, v] : value) {
        if (key != "linear" && key != "angular") {
          *error = at + " has an unknown key '" + key + "' (known: linear, angular)";
          return false;
        }
        const double x = numberOf(v);
        if (std::isnan(x)) {
          *error = at + "/" + key + " must be a number (1/s)";
          return false;
        }
        (key == "linear" ? d.linear : d.angular) = x;
      }
      *error = scene::validateLinkDamping(d, at);
      if (!error->empty()) return false;
      scene->link_damping.emplace_back(name, d);
    }
  } catch (const XmlRpc::XmlRpcException& e) {
    *error = where + ": " + e.getMessage();
    return false;
  }
  return true;
}

}  // namespace node
}  // namespace ragdoll_sim
