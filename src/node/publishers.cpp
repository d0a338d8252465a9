#include "publishers.hpp"

#include <algorithm>

#include <visualization_msgs/MarkerArray.h>

#include "msg_convert.hpp"
#include "node_context.hpp"
#include "ragdoll_sim/JointBroken.h"
#include "ragdoll_sim/NodeStats.h"

namespace ragdoll_sim {
namespace node {

Publishers::Publishers(NodeContext& ctx) : ctx_(ctx) {
  ctx_.clock.advertise(ctx_.nh);
  broken_pub_ = ctx_.pnh.advertise<ragdoll_sim::JointBroken>("joint_broken", 20);
  markers_pub_ = ctx_.pnh.advertise<visualization_msgs::MarkerArray>("markers", 1, /*latch=*/true);
  link_states_pub_ = ctx_.pnh.advertise<ragdoll_sim::LinkStates>("link_states", 10);
  stats_pub_ = ctx_.pnh.advertise<ragdoll_sim::NodeStats>("stats", 10);
}

void Publishers::addRagdoll(RagdollTopics topics) { ragdolls_.push_back(std::move(topics)); }

RagdollTopics Publishers::removeRagdoll(const std::string& name) {
  RagdollTopics out;
  for (size_t k = 0; k < ragdolls_.size(); ++k) {
    if (ragdolls_[k].name != name) continue;
    out = std::move(ragdolls_[k]);
    ragdolls_.erase(ragdolls_.begin() + static_cast<long>(k));
    break;
  }
  return out;
}

std::vector<scene::RagdollView> Publishers::views() const {
  std::vector<scene::RagdollView> views;
  const Scene& s = *ctx_.scene;
  for (size_t k = 0; k < ragdolls_.size(); ++k)
    if (!ragdolls_[k].object)
      views.push_back({ragdolls_[k].name, ragdolls_[k].tf_prefix, &s.def(int(k)), &s.bodies(int(k))});
  return views;
}

std::vector<ObjectView> Publishers::objectViews() const {
  std::vector<ObjectView> views;
  const Scene& s = *ctx_.scene;
  for (size_t k = 0; k < ragdolls_.size(); ++k)
    if (ragdolls_[k].object)
      views.push_back({ragdolls_[k].name, &s.def(int(k)), s.bodies(int(k)).bodies, false});
  for (size_t i = 0; i < s.staticObjectCount(); ++i)
    views.push_back({s.staticObjectName(int(i)), &s.staticObjectDef(int(i)),
                     s.staticObjectBodies(int(i)), true});
  return views;
}

void Publishers::rebuild() {
  // Entries in the Scene's order: ragdolls keep theirs, dynamic objects get one.
  const Scene& s = *ctx_.scene;
  std::vector<RagdollTopics> synced;
  for (size_t k = 0; k < s.ragdollCount(); ++k) {
    const std::string& name = s.name(static_cast<int>(k));
    auto it = std::find_if(ragdolls_.begin(), ragdolls_.end(),
                           [&](const RagdollTopics& r) { return r.name == name; });
    if (it != ragdolls_.end()) {
      synced.push_back(std::move(*it));
      ragdolls_.erase(it);
    } else {
      RagdollTopics r;
      r.name = name;
      r.tf_prefix = name;
      r.object = true;
      synced.push_back(std::move(r));
    }
  }
  ragdolls_ = std::move(synced);
  for (size_t k = 0; k < ragdolls_.size(); ++k) {
    buildTf(ragdolls_[k], static_cast<int>(k));
    buildJointState(ragdolls_[k], static_cast<int>(k));
  }
  buildLinkStates();
  last_publish_step_ = -1;  // publish the new set at once
}

// ------------------------------------------------------------------------------------------
// TF

std::string Publishers::frameId(const RagdollTopics& r, const std::string& link) const {
  return joinFrames(ctx_.config.frame_prefix, r.frame(link));
}

void Publishers::buildTf(RagdollTopics& r, int k) {
  const RagdollDef& def = ctx_.scene->def(k);
  const std::string& world_frame = ctx_.config.world_frame;
  r.tf_msgs.clear();
  for (const LinkDef& l : def.links) {
    geometry_msgs::TransformStamped t;
    t.header.frame_id = world_frame;
    t.child_frame_id = frameId(r, l.name);
    r.tf_msgs.push_back(t);
  }
  r.ball_joints.clear();
  r.ball_tf_offset.clear();
  for (size_t j = 0; j < def.joints.size(); ++j) {
    const RagdollJointDef& jd = def.joints[j];
    if (jd.kind != RagdollJointKind::Ball || jd.chain_links.empty()) continue;
    r.ball_joints.push_back(static_cast<int>(j));
    r.ball_tf_offset.push_back(static_cast<int>(r.tf_msgs.size()));
    for (const std::string& c : jd.chain_links) {
      geometry_msgs::TransformStamped t;
      t.header.frame_id = world_frame;
      t.child_frame_id = frameId(r, c);
      r.tf_msgs.push_back(t);
    }
  }
  r.fixed_tf_offset = r.tf_msgs.size();
  for (const FixedFrameDef& f : def.fixed_frames) {
    geometry_msgs::TransformStamped t;
    t.header.frame_id = world_frame;
    t.child_frame_id = frameId(r, f.name);
    r.tf_msgs.push_back(t);
  }
}

void Publishers::publishTf(const ros::Time& stamp) {
  const World& world = ctx_.scene->world();
  tf_all_.clear();
  for (size_t k = 0; k < ragdolls_.size(); ++k) {
    RagdollTopics& r = ragdolls_[k];
    const RagdollDef& def = ctx_.scene->def(static_cast<int>(k));
    const Ragdoll& ragdoll = ctx_.scene->bodies(static_cast<int>(k));
    for (size_t i = 0; i < ragdoll.bodies.size(); ++i) {
      r.tf_msgs[i].header.stamp = stamp;
      toMsg(world.bodyPose(ragdoll.bodies[i]), &r.tf_msgs[i].transform);
    }
    for (size_t b = 0; b < r.ball_joints.size(); ++b) {
      const int j = r.ball_joints[b];
      const std::vector<Transform> poses = ballChainLinkPoses(world, ragdoll, def, j);
      const size_t n = std::min(poses.size(), def.joints[static_cast<size_t>(j)].chain_links.size());
      for (size_t c = 0; c < n; ++c) {
        geometry_msgs::TransformStamped& t = r.tf_msgs[static_cast<size_t>(r.ball_tf_offset[b]) + c];
        t.header.stamp = stamp;
        toMsg(poses[c], &t.transform);
      }
    }
    for (size_t f = 0; f < def.fixed_frames.size(); ++f) {
      const FixedFrameDef& fd = def.fixed_frames[f];
      geometry_msgs::TransformStamped& t = r.tf_msgs[r.fixed_tf_offset + f];
      t.header.stamp = stamp;
      toMsg(world.bodyPose(ragdoll.bodies[static_cast<size_t>(fd.link)]) * fd.offset, &t.transform);
    }
    tf_all_.insert(tf_all_.end(), r.tf_msgs.begin(), r.tf_msgs.end());
  }
  if (!tf_all_.empty()) tf_broadcaster_.sendTransform(tf_all_);
}

// ------------------------------------------------------------------------------------------
// Markers

void Publishers::publishMarkers(const ros::Time& stamp) {
  const visualization_msgs::MarkerArray& markers =
      ctx_.visualizer->update(ctx_.scene->world(), stamp, ctx_.scene->time());
  if (markers_delete_all_) {
    // A deleted ragdoll's markers go away: DELETEALL first, then the current set.
    visualization_msgs::MarkerArray all;
    visualization_msgs::Marker clear;
    clear.header.frame_id = ctx_.config.world_frame;
    clear.header.stamp = stamp;
    clear.action = visualization_msgs::Marker::DELETEALL;
    all.markers.push_back(clear);
    all.markers.insert(all.markers.end(), markers.markers.begin(), markers.markers.end());
    markers_pub_.publish(all);
    markers_delete_all_ = false;
    return;
  }
  markers_pub_.publish(markers);
}

// ------------------------------------------------------------------------------------------
// joint_states and link_states

void Publishers::buildJointState(RagdollTopics& r, int k) {
  const Scene& s = *ctx_.scene;
  const RagdollDef& def = s.def(k);
  // Names as the Scene's axes (the URDF revolute joints, which ~target_pose takes too).
  r.joint_state.name = s.axisNames(k);
  r.joint_sources.clear();
  for (size_t j = 0; j < def.joints.size(); ++j) {
    RagdollTopics::JointSource src;
    src.id = s.bodies(k).joints[j];
    src.kind = def.joints[j].kind;
    src.first = s.firstAxis(k, static_cast<int>(j));
    r.joint_sources.push_back(src);
  }
  r.joint_state.position.assign(r.joint_state.name.size(), 0.0);
  r.joint_state.velocity.assign(r.joint_state.name.size(), 0.0);
  r.joint_state.effort.assign(r.joint_state.name.size(), 0.0);
  r.prev_positions.assign(r.joint_state.name.size(), 0.0);
  r.prev_joint_ns = -1;
}

void Publishers::publishJointStates(const ros::Time& stamp) {
  const World& world = ctx_.scene->world();
  const int64_t sim_ns = ctx_.scene->timeNs();
  for (size_t k = 0; k < ragdolls_.size(); ++k) {
    RagdollTopics& r = ragdolls_[k];
    if (r.object) continue;  // objects have no joint_states topic
    std::vector<double>& q = r.joint_state.position;
    for (const RagdollTopics::JointSource& s : r.joint_sources) {
      const size_t i = static_cast<size_t>(s.first);
      if (s.kind == RagdollJointKind::Ball) {
        const std::array<double, 3> a = world.ballAngles(s.id);
        q[i] = a[0];
        q[i + 1] = a[1];
        q[i + 2] = a[2];
      } else if (s.kind == RagdollJointKind::Prismatic) {
        q[i] = world.prismaticPosition(s.id);
      } else if (s.kind == RagdollJointKind::Hinge) {
        q[i] = world.hingeAngle(s.id);
      }  // fixed: no position
    }
    // Velocities: finite differences over the sim time since the last message.
    if (r.prev_joint_ns >= 0 && sim_ns > r.prev_joint_ns) {
      const double h = static_cast<double>(sim_ns - r.prev_joint_ns) * 1e-9;
      for (size_t i = 0; i < q.size(); ++i) r.joint_state.velocity[i] = (q[i] - r.prev_positions[i]) / h;
    } else {
      std::fill(r.joint_state.velocity.begin(), r.joint_state.velocity.end(), 0.0);
    }
    r.prev_positions = q;
    r.prev_joint_ns = sim_ns;
    // Efforts about the same axes (N m or N), into the message's own vector.
    std::vector<double>& effort = r.joint_state.effort;
    ctx_.scene->jointEfforts(static_cast<int>(k), effort);
    if (effort.size() != q.size()) {
      ROS_ERROR_THROTTLE(10.0, "joint_states of '%s': %zu efforts for %zu joints; sent as zeros",
                         r.name.c_str(), effort.size(), q.size());
      effort.assign(q.size(), 0.0);
    }
    r.joint_state.header.stamp = stamp;
    r.joint_states_pub.publish(r.joint_state);
  }
}

void Publishers::buildLinkStates() {
  link_states_ = ragdoll_sim::LinkStates();
  link_states_.header.frame_id = ctx_.config.world_frame;
  link_state_bodies_.clear();
  const Scene& s = *ctx_.scene;
  for (size_t k = 0; k < s.ragdollCount(); ++k) {
    const Ragdoll& ragdoll = s.bodies(static_cast<int>(k));
    for (size_t i = 0; i < ragdoll.bodies.size(); ++i) {
      link_states_.ragdoll.push_back(s.name(static_cast<int>(k)));
      link_states_.link.push_back(s.def(static_cast<int>(k)).links[i].name);
      link_state_bodies_.push_back(ragdoll.bodies[i]);
    }
  }
  link_states_.pose.resize(link_state_bodies_.size());
  link_states_.twist.resize(link_state_bodies_.size());
}

void Publishers::publishLinkStates(const ros::Time& stamp) {
  if (link_states_pub_.getNumSubscribers() == 0) return;
  const World& world = ctx_.scene->world();
  for (size_t i = 0; i < link_state_bodies_.size(); ++i) {
    const BodyId b = link_state_bodies_[i];
    const Transform pose = world.bodyPose(b);
    toMsg(pose, &link_states_.pose[i]);
    toMsg(world.pointVelocity(b, pose.p), &link_states_.twist[i].linear);
    toMsg(world.bodyState(b).angular_velocity, &link_states_.twist[i].angular);
  }
  link_states_.header.stamp = stamp;
  link_states_pub_.publish(link_states_);
}

// ------------------------------------------------------------------------------------------
// Events, stats, the publish cycle

void Publishers::publishBrokenJoints() {
  const Scene& s = *ctx_.scene;
  for (const BrokenJointReport& b : s.brokenJoints()) {
    ctx_.clock.publish(s.timeNs(), /*force=*/true, ctx_.config.clock_rate);
    ragdoll_sim::JointBroken msg;
    msg.header.stamp = ctx_.clock.stamp(s.timeNs());
    msg.header.frame_id = ctx_.config.world_frame;
    msg.ragdoll = b.ragdoll;
    msg.joint = b.joint;
    msg.parent_link = b.parent_link;
    msg.child_link = b.child_link;
    msg.force = b.force;
    msg.torque = b.torque;
    broken_pub_.publish(msg);
    ROS_INFO("joint '%s' of '%s' broke at sim time %.3f s: '%s' came off '%s' (anchor force "
             "%.1f N, break_force %g N; lock torque %.1f N m, break_torque %g N m)",
             b.joint.c_str(), b.ragdoll.c_str(), s.time(), msg.child_link.c_str(),
             msg.parent_link.c_str(), msg.force, b.break_force, msg.torque, b.break_torque);
  }
}

void Publishers::publish() {
  const Scene& s = *ctx_.scene;
  ctx_.clock.publish(s.timeNs(), /*force=*/true, ctx_.config.clock_rate);  // stamps below
  const ros::Time stamp = ctx_.clock.stamp(s.timeNs());
  // TF and the states only when sim time advanced (or the set of ragdolls changed): a
  // repeated stamp would make every tf2 listener complain (TF_REPEATED_DATA) while paused.
  const bool advanced = s.steps() != last_publish_step_;
  if (advanced) {
    publishTf(stamp);
    publishJointStates(stamp);
    publishLinkStates(stamp);
    last_publish_step_ = s.steps();
  }
  ctx_.interaction->update(s.time());
  const bool markers = ctx_.config.publish_markers && markers_pub_.getNumSubscribers() > 0;
  if (markers) publishMarkers(stamp);
  ctx_.reports->publish(markers, advanced);
  if (stats_pub_.getNumSubscribers() > 0) publishStats(stamp);
}

void Publishers::publishStats(const ros::Time& stamp) {
  const Scene& s = *ctx_.scene;
  const SceneCounters n = s.counters();
  ragdoll_sim::NodeStats m;
  m.header.stamp = stamp;
  m.received = n.received;
  m.applied = n.applied;
  m.rejected = n.rejected;
  m.dropped = n.dropped;
  m.queued = static_cast<uint32_t>(n.queued);
  m.max_queued = static_cast<uint32_t>(n.max_queued);
  m.queue_capacity = static_cast<uint32_t>(n.queue_capacity);
  m.body_faults = n.body_faults;
  m.impulses = n.impulses;
  m.forces = n.forces;
  m.active_forces = static_cast<uint32_t>(n.active_forces);
  m.pokes = ctx_.interaction->pokes();
  m.drags = ctx_.interaction->drags();
  m.steps = static_cast<uint64_t>(s.steps());
  m.skipped_steps = static_cast<uint64_t>(ctx_.pacer.droppedSteps());
  m.sim_time = s.time();
  m.awake_bodies = static_cast<uint32_t>(s.world().awakeBodyCount());
  m.resting_bodies = static_cast<uint32_t>(s.world().islandCounters().resting_bodies);
  stats_pub_.publish(m);
}

}  // namespace node
}  // namespace ragdoll_sim
