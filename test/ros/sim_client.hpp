// Helpers shared by the rostests that drive the node through its services: step, link states
// and the total linear momentum of a ragdoll from ~get_link_state and the URDF masses.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Geometry>
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
