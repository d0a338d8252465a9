// The Scene's reports of the last step as topics: ~contacts, ~link_loads, ~impacts, ~injury,
// and the service ~injury/reset. Each topic is filled only while it has subscribers (counted
// once per publish cycle, so a step with nobody listening costs a few flag tests), into
// buffers kept between messages. Impact detection in the Scene is on only while ~impacts (or
// the markers) has subscribers.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <ros/ros.h>

#include "ragdoll_sim/ContactsState.h"
#include "ragdoll_sim/Injury.h"
#include "ragdoll_sim/LinkLoads.h"
#include "ragdoll_sim/ResetInjury.h"
#include "ragdoll_sim/scene.hpp"

namespace ragdoll_sim {
namespace node {

struct NodeContext;

class ReportTopics {
 public:
  explicit ReportTopics(NodeContext& ctx);

  // After a spawn, removal or rebuild: link and joint names of ~link_loads, and the head and
  // neck (~injury/head_link, ~injury/neck_joint) of every ragdoll new since the last call.
  void rebuild();
  // After every step: ~impacts events, ~injury records that ended, ~contacts when due at
  // ~contacts/rate.
  void afterStep();
  // Each publish cycle: subscriber counts, impact detection on or off (for ~impacts, and for
  // the markers' flashes while they are watched); when the sim advanced since the last cycle,
  // ~contacts (rate 0) and ~link_loads.
  void publish(bool markers_subscribed, bool advanced);

 private:
  void publishContacts();
  void publishLinkLoads();
  void publishInjury(const InjuryReport& r);
  bool onResetInjury(ragdoll_sim::ResetInjury::Request& req,
                     ragdoll_sim::ResetInjury::Response& res);

  NodeContext& ctx_;
  ros::Publisher contacts_pub_, link_loads_pub_, impacts_pub_, injury_pub_;
  ros::ServiceServer reset_srv_;
  bool contacts_subscribed_ = false, impacts_subscribed_ = false;
  bool impacts_on_ = false;  // the Scene's impact detection
  int64_t next_contacts_ns_ = 0;  // sim time the next ~contacts is due (rate > 0)
  std::vector<SceneContact> contacts_;
  ragdoll_sim::ContactsState contacts_msg_;
  std::vector<LinkLoad> link_loads_;
  std::vector<JointLoad> joint_loads_;
  ragdoll_sim::LinkLoads link_loads_msg_;
  std::vector<RagdollId> injury_configured_;  // ragdolls whose head and neck were set
};

// A one-line summary of an injury record, for the log and ~injury/reset's reply.
std::string injurySummary(const InjuryReport& r);

}  // namespace node
}  // namespace ragdoll_sim
