// Helpers shared by the rostests that drive the node through its services: step, link states,
// dynamic_reconfigure, and the total linear momentum of a ragdoll from ~get_link_state and the
// URDF masses.
#pragma once

#include <cmath>
#include <map>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <dynamic_reconfigure/Reconfigure.h>
#include <ragdoll_sim/GetLinkState.h>
#include <ragdoll_sim/Step.h>
#include <ros/ros.h>
#include <std_srvs/Empty.h>

#include "tf_snapshots.hpp"

namespace ragdoll_test {

class SimClient {
 public:
  explicit SimClient(const std::string& node) : node_(node) {}

  bool waitUp(double timeout = 30.0) const {
    return ros::service::waitForService(node_ + "/step", ros::Duration(timeout));
  }
  bool call(const std::string& service) const {
    std_srvs::Empty e;
    return ros::service::call(node_ + "/" + service, e);
  }
  // Steps n physics steps (node paused); the response, or success = false on a failed call.
  ragdoll_sim::Step::Response step(uint32_t n) const {
    ragdoll_sim::Step s;
    s.request.steps = n;
    if (!ros::service::call(node_ + "/step", s)) s.response.success = false;
    return s.response;
  }
  ragdoll_sim::GetLinkState::Response link(const std::string& ragdoll, const std::string& link) const {
    ragdoll_sim::GetLinkState s;
    s.request.ragdoll = ragdoll;
    s.request.link = link;
    if (!ros::service::call(node_ + "/get_link_state", s)) s.response.success = false;
    return s.response;
  }
  // Waits (wall clock) until pending_commands reaches `n`; false on timeout.
  bool waitPending(uint32_t n, double timeout = 10.0) const {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < deadline) {
      if (step(0).pending_commands == n) return true;
      ros::WallDuration(0.02).sleep();
    }
    return false;
  }
  // Sets some of the physics parameters (cfg/Physics.cfg) through ~set_parameters; *now gets
  // the node's answer, the whole configuration (bools as 0 / 1). False on a failed call.
  struct Params {
    std::map<std::string, double> doubles;
    std::map<std::string, int> ints;
    std::map<std::string, bool> bools;
  };
  bool reconfigure(const Params& set, std::map<std::string, double>* now = nullptr) const {
    dynamic_reconfigure::Reconfigure r;
    // (Double|Int|Bool)Parameter: each a name and a value of its type
    const auto add = [](auto& out, const auto& in) {
      for (const auto& [name, value] : in) {
        out.emplace_back();
        out.back().name = name;
        out.back().value = value;
      }
    };
    const auto read = [now](const auto& in) {
      for (const auto& p : in) (*now)[p.name] = double(p.value);  // a bool as 0 / 1
    };
    add(r.request.config.doubles, set.doubles);
    add(r.request.config.ints, set.ints);
    add(r.request.config.bools, set.bools);
    if (!ros::service::call(node_ + "/set_parameters", r)) return false;
    if (now) {
      read(r.response.config.doubles);
      read(r.response.config.ints);
      read(r.response.config.bools);
    }
    return true;
  }
  const std::string& node() const { return node_; }

 private:
  std::string node_;
};

inline Vec3 position(const ragdoll_sim::GetLinkState::Response& s) {
  return Vec3(s.pose.position.x, s.pose.position.y, s.pose.position.z);
}
inline Eigen::Quaterniond orientation(const ragdoll_sim::GetLinkState::Response& s) {
  return Eigen::Quaterniond(s.pose.orientation.w, s.pose.orientation.x, s.pose.orientation.y,
                            s.pose.orientation.z);
}
inline Vec3 linear(const ragdoll_sim::GetLinkState::Response& s) {
  return Vec3(s.twist.linear.x, s.twist.linear.y, s.twist.linear.z);
}
inline Vec3 angular(const ragdoll_sim::GetLinkState::Response& s) {
  return Vec3(s.twist.angular.x, s.twist.angular.y, s.twist.angular.z);
}
inline Vec3 com(const ragdoll_sim::GetLinkState::Response& s) {
  return Vec3(s.com.x, s.com.y, s.com.z);
}

// Total linear momentum of a ragdoll: sum of m_i v_com_i over its simulated links (the ball
// chains' dummy links are no bodies: ~get_link_state refuses them). *links_found: how many.
inline Vec3 momentum(const SimClient& sim, const std::string& ragdoll,
                     const std::vector<LinkMass>& links, int* links_found) {
  Vec3 p = Vec3::Zero();
  *links_found = 0;
  for (const LinkMass& l : links) {
    const ragdoll_sim::GetLinkState::Response s = sim.link(ragdoll, l.name);
    if (!s.success) continue;
    ++*links_found;
    p += l.mass * (linear(s) + angular(s).cross(com(s) - position(s)));
  }
  return p;
}

}  // namespace ragdoll_test
