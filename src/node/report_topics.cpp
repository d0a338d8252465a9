#include "report_topics.hpp"

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>

#include "msg_convert.hpp"
#include "names.hpp"
#include "node_context.hpp"
#include "ragdoll_sim/Impact.h"

namespace ragdoll_sim {
namespace node {

namespace {

void toWrench(const Vec3& force, const Vec3& torque, geometry_msgs::Wrench* w) {
  toMsg(force, &w->force);
  toMsg(torque, &w->torque);
}

void fill(const InjuryReport& r, const ros::Time& stamp, const std::string& frame,
          ragdoll_sim::Injury* m) {
  m->header.stamp = stamp;
  m->header.frame_id = frame;
  m->ragdoll = r.ragdoll;
  m->head_link = r.head_link;
  m->neck_joint = r.neck_joint;
  m->reason = r.reason;
  m->start_time = r.start_time;
  m->end_time = r.end_time;
  m->peak_g = r.peak_g;
  m->peak_time = r.peak_time;
  m->hic15 = r.hic15;
  m->hic15_t1 = r.hic15_t1;
  m->hic15_t2 = r.hic15_t2;
  m->hic36 = r.hic36;
  m->hic36_t1 = r.hic36_t1;
  m->hic36_t2 = r.hic36_t2;
  m->peak_angular_acceleration = r.peak_angular_acceleration;
  m->peak_neck_force = r.peak_neck_force;
  m->peak_neck_torque = r.peak_neck_torque;
}

}  // namespace

std::string injurySummary(const InjuryReport& r) {
  char text[1024];
  std::snprintf(
      text, sizeof text, "injury of '%s' (%s, sim time %.3f .. %.3f s): head '%s' peak %.2f g at %.3f s, HIC15 "
      "%.1f, HIC36 %.1f, peak angular acceleration %.0f rad/s^2; neck '%s' peak %.0f N, %.1f N m",
      r.ragdoll.c_str(), r.reason.c_str(), r.start_time, r.end_time, r.head_link.c_str(),
      r.peak_g, r.peak_time, r.hic15, r.hic36, r.peak_angular_acceleration,
      r.neck_joint.c_str(), r.peak_neck_force, r.peak_neck_torque);
  return text;
}

ReportTopics::ReportTopics(NodeContext& ctx) : ctx_(ctx) {
  ros::NodeHandle& pnh = ctx_.pnh;
  // A ~step call publishes a burst, one message per rate period of the steps it runs, faster
  // than a loaded machine's transport sends them: the queues hold a second of them at 100 Hz.
  contacts_pub_ = pnh.advertise<ragdoll_sim::ContactsState>("contacts", 100);
  link_loads_pub_ = pnh.advertise<ragdoll_sim::LinkLoads>("link_loads", 100);
  // Events: a fall can hit with many links in one step.
  impacts_pub_ = pnh.advertise<ragdoll_sim::Impact>("impacts", 100);
  injury_pub_ = pnh.advertise<ragdoll_sim::Injury>("injury", 20);
  reset_srv_ = pnh.advertiseService("injury/reset", &ReportTopics::onResetInjury, this);
  contacts_msg_.header.frame_id = ctx_.config.world_frame;
  link_loads_msg_.header.frame_id = ctx_.config.world_frame;
}

// ------------------------------------------------------------------------------------------
// Names and injury settings

void ReportTopics::rebuild() {
  const Scene& s = *ctx_.scene;
  ragdoll_sim::LinkLoads& m = link_loads_msg_;
  m.link_ragdoll.clear();
  m.link.clear();
  m.joint_ragdoll.clear();
  m.joint.clear();
  m.joint_child.clear();
  for (size_t k = 0; k < s.ragdollCount(); ++k) {
    const RagdollDef& def = s.def(static_cast<int>(k));
    for (const LinkDef& l : def.links) {
      m.link_ragdoll.push_back(s.name(static_cast<int>(k)));
      m.link.push_back(l.name);
    }
    for (const RagdollJointDef& j : def.joints) {
      m.joint_ragdoll.push_back(s.name(static_cast<int>(k)));
      m.joint.push_back(j.name);
      m.joint_child.push_back(def.links[static_cast<size_t>(j.child)].name);
    }
  }
  m.contact_wrench.resize(m.link.size());
  m.joint_wrench.resize(m.joint.size());

  // Head and neck of the ragdolls new since the last call (objects have no injury record).
  Scene& scene = *ctx_.scene;
  const NodeConfig& c = ctx_.config;
  std::vector<RagdollId> present;
  for (size_t k = 0; k < scene.ragdollCount(); ++k) {
    const int i = static_cast<int>(k);
    if (scene.isObject(i)) continue;
    present.push_back(scene.id(i));
    if (std::find(injury_configured_.begin(), injury_configured_.end(), scene.id(i)) !=
        injury_configured_.end())
      continue;
    InjuryDef def = c.scene.injury;
    def.head_link = c.injury_head_link;
    def.neck_joint = c.injury_neck_joint;
    std::string param = "~injury/head_link, ~injury/neck_joint";
    const auto own = c.injury_ragdolls.find(scene.name(i));
    if (own != c.injury_ragdolls.end()) {
      def.head_link = own->second.head_link;
      def.neck_joint = own->second.neck_joint;
      param = "~injury/ragdolls/" + scene.name(i);
    }
    if (!def.enabled || (def.head_link.empty() && def.neck_joint.empty())) continue;
    std::string error;
    if (!scene.setInjury(i, def, &error)) {
      // The launch-time ragdoll and a named one are those the parameters were written for.
      const std::string text = param + " (head '" + def.head_link + "', neck '" +
                               def.neck_joint + "') do not fit ragdoll '" + scene.name(i) +
                               "': " + error + "; its head is '" + scene.headLink(i) +
                               "', its neck '" + scene.neckJoint(i) + "'";
      if (k == 0 || own != c.injury_ragdolls.end()) ROS_ERROR("%s", text.c_str());
      else ROS_WARN("%s", text.c_str());
    }
  }
  injury_configured_ = std::move(present);
}

// ------------------------------------------------------------------------------------------
// Per step and per publish cycle

void ReportTopics::afterStep() {
  const Scene& s = *ctx_.scene;
  if (impacts_subscribed_ && !s.impacts().empty()) {
    const ros::Time stamp = ctx_.clock.stamp(s.timeNs());
    ragdoll_sim::Impact m;
    m.header.stamp = stamp;
    m.header.frame_id = ctx_.config.world_frame;
    for (const ImpactEvent& e : s.impacts()) {
      m.ragdoll = e.ragdoll;
      m.link = e.link;
      m.other = e.other;
      m.point = toPoint(e.point);
      toMsg(e.normal, &m.normal);
      m.closing_speed = e.closing_speed;
      m.separating_speed = e.separating_speed;
      m.impulse = e.impulse;
      m.peak_force = e.peak_force;
      impacts_pub_.publish(m);
    }
  }
  if (!s.injuryReports().empty())
    for (const InjuryReport& r : s.injuryReports()) publishInjury(r);
  const double rate = ctx_.config.contacts_rate;
  if (rate > 0 && contacts_subscribed_ && s.timeNs() >= next_contacts_ns_) {
    publishContacts();
    next_contacts_ns_ = s.timeNs() + std::max<int64_t>(1, std::llround(1e9 / rate));
  }
}

void ReportTopics::publish(bool markers_subscribed, bool advanced) {
  contacts_subscribed_ = contacts_pub_.getNumSubscribers() > 0;
  impacts_subscribed_ = impacts_pub_.getNumSubscribers() > 0;
  const bool impacts =
      impacts_subscribed_ || (markers_subscribed && ctx_.config.markers.impact_flash > 0.0);
  if (impacts != impacts_on_) {  // only a change touches the Scene
    ImpactDef def = ctx_.config.scene.impacts;
    def.enabled = impacts;
    ctx_.scene->setImpacts(def);
    impacts_on_ = impacts;
  }
  if (!contacts_subscribed_) next_contacts_ns_ = 0;  // a new subscriber gets one at once
  else if (advanced && ctx_.config.contacts_rate <= 0) publishContacts();
  if (advanced && link_loads_pub_.getNumSubscribers() > 0) publishLinkLoads();
}

void ReportTopics::publishContacts() {
  const Scene& s = *ctx_.scene;
  const World& world = s.world();
  s.contacts(contacts_);
  ragdoll_sim::ContactsState& m = contacts_msg_;
  m.header.stamp = ctx_.clock.stamp(s.timeNs());
  m.states.resize(contacts_.size());
  for (size_t i = 0; i < contacts_.size(); ++i) {
    const SceneContact& c = contacts_[i];
    const ContactReport& r = c.report;
    ragdoll_sim::ContactState& st = m.states[i];
    st.collision1_name = s.bodyName(c.a);
    st.collision2_name = s.bodyName(c.b);
    st.info = st.collision1_name + " -> " + st.collision2_name + ", " +
              std::to_string(r.count) + " point(s)";
    st.shape1 = r.shape_a;
    st.shape2 = r.shape_b;
    const size_t n = static_cast<size_t>(std::max(0, r.count));
    st.wrenches.resize(n);
    st.contact_positions.resize(n);
    st.contact_normals.resize(n);
    st.depths.resize(n);
    st.normal_forces.resize(n);
    st.friction_forces.resize(n);
    const Vec3 com_a = world.isValid(r.body_a) ? world.bodyState(r.body_a).com_position
                                               : Vec3::Zero();
    for (size_t p = 0; p < n; ++p) {
      const ContactPointReport& pt = r.points[p];
      const Vec3 on_b = pt.normal_force * r.normal + pt.friction_force;
      toWrench(-on_b, (pt.point - com_a).cross(-on_b), &st.wrenches[p]);
      toMsg(pt.point, &st.contact_positions[p]);
      toMsg(r.normal, &st.contact_normals[p]);
      st.depths[p] = pt.depth;
      st.normal_forces[p] = pt.normal_force;
      toMsg(pt.friction_force, &st.friction_forces[p]);
    }
    toWrench(r.force_a, r.torque_a, &st.total_wrench);
    toWrench(r.force_a, r.torque_a, &st.wrench1);
    toWrench(r.force_b, r.torque_b, &st.wrench2);
  }
  contacts_pub_.publish(m);
}

void ReportTopics::publishLinkLoads() {
  const Scene& s = *ctx_.scene;
  ragdoll_sim::LinkLoads& m = link_loads_msg_;
  m.header.stamp = ctx_.clock.stamp(s.timeNs());
  size_t li = 0, ji = 0;
  for (size_t k = 0; k < s.ragdollCount(); ++k) {
    s.loads(static_cast<int>(k), link_loads_, joint_loads_);
    const RagdollDef& def = s.def(static_cast<int>(k));
    // A Scene that reports fewer entries than the model has leaves zeros, never a short list.
    for (size_t i = 0; i < def.links.size() && li < m.contact_wrench.size(); ++i, ++li) {
      if (i < link_loads_.size())
        toWrench(link_loads_[i].contact_force, link_loads_[i].contact_torque, &m.contact_wrench[li]);
      else
        m.contact_wrench[li] = geometry_msgs::Wrench();
    }
    for (size_t j = 0; j < def.joints.size() && ji < m.joint_wrench.size(); ++j, ++ji) {
      if (j < joint_loads_.size())
        toWrench(joint_loads_[j].wrench.force, joint_loads_[j].wrench.torque, &m.joint_wrench[ji]);
      else
        m.joint_wrench[ji] = geometry_msgs::Wrench();
    }
  }
  link_loads_pub_.publish(m);
}

// ------------------------------------------------------------------------------------------
// Injury

void ReportTopics::publishInjury(const InjuryReport& r) {
  const Scene& s = *ctx_.scene;
  ragdoll_sim::Injury m;
  fill(r, ctx_.clock.stamp(s.timeNs()), ctx_.config.world_frame, &m);
  injury_pub_.publish(m);
  ROS_INFO("%s", injurySummary(r).c_str());
}

bool ReportTopics::onResetInjury(ragdoll_sim::ResetInjury::Request& req,
                                 ragdoll_sim::ResetInjury::Response& res) {
  Scene& scene = *ctx_.scene;
  const int k = scene.find(req.ragdoll);
  const auto refuse = [&](const std::string& kind, const std::string& text) {
    res.success = false;
    res.message = "injury/reset rejected: " + text;
    ctx_.warn("injury/reset/" + kind, res.message);
    return true;
  };
  if (k < 0 || scene.isObject(k))
    return refuse("unknown ragdoll", "no ragdoll named " + scene::quoted(req.ragdoll) +
                                         (k >= 0 ? " (it is an object)" : ""));
  if (scene.headLink(k).empty())
    return refuse("no head", "ragdoll '" + scene.name(k) + "' has no injury record (" +
                                 (ctx_.config.scene.injury.enabled
                                      ? "no head link: set ~injury/head_link)"
                                      : "~injury/enabled is false)"));
  const InjuryReport r = scene.resetInjury(k);
  fill(r, ctx_.clock.stamp(scene.timeNs()), ctx_.config.world_frame, &res.injury);
  injury_pub_.publish(res.injury);
  res.success = true;
  res.message = injurySummary(r);
  ROS_INFO("%s", res.message.c_str());
  return true;
}

}  // namespace node
}  // namespace ragdoll_sim
