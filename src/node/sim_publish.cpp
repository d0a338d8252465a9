// SimNode: TF, markers, joint_states, link_states, /clock and joint_broken. Every stamp is
// simStamp(); on /use_sim_time that is the sim time, and /clock carries the same value before
// anything stamped with it goes out.
#include <algorithm>

#include <rosgraph_msgs/Clock.h>

#include "msg_convert.hpp"
#include "sim_node.hpp"

namespace ragdoll_sim {
namespace node {

// ------------------------------------------------------------------------------------------
// TF

void SimNode::buildTf(RagdollInstance& r) {
  r.tf_msgs.clear();
  for (const LinkDef& l : r.def.links) {
    geometry_msgs::TransformStamped t;
    t.header.frame_id = config_.world_frame;
    t.child_frame_id = r.frame(l.name);
    r.tf_msgs.push_back(t);
  }
  r.ball_joints.clear();
  r.ball_tf_offset.clear();
  for (size_t j = 0; j < r.def.joints.size(); ++j) {
    const RagdollJointDef& jd = r.def.joints[j];
    if (jd.kind != RagdollJointKind::Ball || jd.chain_links.empty()) continue;
    r.ball_joints.push_back(static_cast<int>(j));
    r.ball_tf_offset.push_back(static_cast<int>(r.tf_msgs.size()));
    for (const std::string& c : jd.chain_links) {
      geometry_msgs::TransformStamped t;
      t.header.frame_id = config_.world_frame;
      t.child_frame_id = r.frame(c);
      r.tf_msgs.push_back(t);
    }
  }
  r.fixed_tf_offset = r.tf_msgs.size();
  for (const FixedFrameDef& f : r.def.fixed_frames) {
    geometry_msgs::TransformStamped t;
    t.header.frame_id = config_.world_frame;
    t.child_frame_id = r.frame(f.name);
    r.tf_msgs.push_back(t);
  }
}

void SimNode::publishTf(const ros::Time& stamp) {
  tf_all_.clear();
  for (RagdollInstance& r : ragdolls_) {
    for (size_t i = 0; i < r.ragdoll.bodies.size(); ++i) {
      r.tf_msgs[i].header.stamp = stamp;
      toMsg(world_->bodyPose(r.ragdoll.bodies[i]), &r.tf_msgs[i].transform);
    }
    for (size_t k = 0; k < r.ball_joints.size(); ++k) {
      const int j = r.ball_joints[k];
      const std::vector<Transform> poses = ballChainLinkPoses(*world_, r.ragdoll, r.def, j);
      const size_t n = std::min(poses.size(), r.def.joints[static_cast<size_t>(j)].chain_links.size());
      for (size_t c = 0; c < n; ++c) {
        geometry_msgs::TransformStamped& t = r.tf_msgs[static_cast<size_t>(r.ball_tf_offset[k]) + c];
        t.header.stamp = stamp;
        toMsg(poses[c], &t.transform);
      }
    }
    for (size_t k = 0; k < r.def.fixed_frames.size(); ++k) {
      const FixedFrameDef& f = r.def.fixed_frames[k];
      geometry_msgs::TransformStamped& t = r.tf_msgs[r.fixed_tf_offset + k];
      t.header.stamp = stamp;
      toMsg(world_->bodyPose(r.ragdoll.bodies[static_cast<size_t>(f.link)]) * f.offset, &t.transform);
    }
    tf_all_.insert(tf_all_.end(), r.tf_msgs.begin(), r.tf_msgs.end());
  }
  if (!tf_all_.empty()) tf_broadcaster_->sendTransform(tf_all_);
}

// ------------------------------------------------------------------------------------------
// Markers

void SimNode::publishMarkers(const ros::Time& stamp) {
  const visualization_msgs::MarkerArray& markers = visualizer_->update(*world_, stamp, simTime());
  if (markers_delete_all_) {
    // A deleted ragdoll's markers go away: DELETEALL first, then the current set.
    visualization_msgs::MarkerArray all;
    visualization_msgs::Marker clear;
    clear.header.frame_id = config_.world_frame;
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

void SimNode::buildJointState(RagdollInstance& r) {
  // Names as in the AxisTable (the URDF revolute joints, which ~target_pose takes too).
  r.joint_state.name.clear();
  for (const AxisInfo& a : r.axes.axes()) r.joint_state.name.push_back(a.name);
  r.joint_sources.clear();
  for (size_t j = 0; j < r.def.joints.size(); ++j) {
    RagdollInstance::JointSource src;
    src.id = r.ragdoll.joints[j];
    src.kind = r.def.joints[j].kind;
    src.first = r.axes.first(static_cast<int>(j));
    r.joint_sources.push_back(src);
  }
  r.joint_state.position.assign(r.joint_state.name.size(), 0.0);
  r.joint_state.velocity.assign(r.joint_state.name.size(), 0.0);
  r.prev_positions.assign(r.joint_state.name.size(), 0.0);
  r.prev_joint_ns = -1;
}

void SimNode::publishJointStates(const ros::Time& stamp) {
  for (RagdollInstance& r : ragdolls_) {
    std::vector<double>& q = r.joint_state.position;
    for (const RagdollInstance::JointSource& s : r.joint_sources) {
      const size_t i = static_cast<size_t>(s.first);
      if (s.kind == RagdollJointKind::Ball) {
        const std::array<double, 3> a = world_->ballAngles(s.id);
        q[i] = a[0];
        q[i + 1] = a[1];
        q[i + 2] = a[2];
      } else if (s.kind == RagdollJointKind::Prismatic) {
        q[i] = world_->prismaticPosition(s.id);
      } else if (s.kind == RagdollJointKind::Hinge) {
        q[i] = world_->hingeAngle(s.id);
      }  // fixed: no position
    }
    // Velocities: finite differences over the sim time since the last message.
    if (r.prev_joint_ns >= 0 && sim_ns_ > r.prev_joint_ns) {
      const double h = static_cast<double>(sim_ns_ - r.prev_joint_ns) * 1e-9;
      for (size_t i = 0; i < q.size(); ++i) r.joint_state.velocity[i] = (q[i] - r.prev_positions[i]) / h;
    } else {
      std::fill(r.joint_state.velocity.begin(), r.joint_state.velocity.end(), 0.0);
    }
    r.prev_positions = q;
    r.prev_joint_ns = sim_ns_;
    r.joint_state.header.stamp = stamp;
    r.joint_states_pub.publish(r.joint_state);
  }
}

void SimNode::buildLinkStates() {
  link_states_ = ragdoll_sim::LinkStates();
  link_states_.header.frame_id = config_.world_frame;
  link_state_bodies_.clear();
  for (const RagdollInstance& r : ragdolls_) {
    for (size_t i = 0; i < r.ragdoll.bodies.size(); ++i) {
      link_states_.ragdoll.push_back(r.name);
      link_states_.link.push_back(r.def.links[i].name);
      link_state_bodies_.push_back(r.ragdoll.bodies[i]);
    }
  }
  link_states_.pose.resize(link_state_bodies_.size());
  link_states_.twist.resize(link_state_bodies_.size());
}

void SimNode::publishLinkStates(const ros::Time& stamp) {
  if (link_states_pub_.getNumSubscribers() == 0) return;
  for (size_t i = 0; i < link_state_bodies_.size(); ++i) {
    const BodyId b = link_state_bodies_[i];
    const Transform pose = world_->bodyPose(b);
    toMsg(pose, &link_states_.pose[i]);
    toMsg(world_->pointVelocity(b, pose.p), &link_states_.twist[i].linear);
    toMsg(world_->bodyState(b).angular_velocity, &link_states_.twist[i].angular);
  }
  link_states_.header.stamp = stamp;
  link_states_pub_.publish(link_states_);
}

// ------------------------------------------------------------------------------------------
// Clock, events, the publish cycle

void SimNode::publishClock(bool force) {
  if (!publish_clock_ || sim_ns_ == last_clock_ns_) return;
  if (!force && config_.clock_rate > 0.0 && sim_ns_ < next_clock_ns_) return;
  rosgraph_msgs::Clock c;
  c.clock = simStamp();
  clock_pub_.publish(c);
  last_clock_ns_ = sim_ns_;
  if (config_.clock_rate > 0.0)
    next_clock_ns_ = sim_ns_ + std::max<int64_t>(1, std::llround(1e9 / config_.clock_rate));
}

void SimNode::publishBrokenJoints() {
  for (JointId id : world_->takeBrokenJoints()) {
    for (const RagdollInstance& r : ragdolls_) {
      const auto it = std::find(r.ragdoll.joints.begin(), r.ragdoll.joints.end(), id);
      if (it == r.ragdoll.joints.end()) continue;
      const RagdollJointDef& j = r.def.joints[static_cast<size_t>(it - r.ragdoll.joints.begin())];
      publishClock(/*force=*/true);
      ragdoll_sim::JointBroken msg;
      msg.header.stamp = simStamp();
      msg.header.frame_id = config_.world_frame;
      msg.ragdoll = r.name;
      msg.joint = j.name;
      msg.parent_link = r.def.links[static_cast<size_t>(j.parent)].name;
      msg.child_link = r.def.links[static_cast<size_t>(j.child)].name;
      msg.force = world_->jointForce(id);
      msg.torque = world_->jointTorque(id);
      broken_pub_.publish(msg);
      ROS_INFO("joint '%s' of '%s' broke at sim time %.3f s: '%s' came off '%s' (anchor force "
               "%.1f N, break_force %g N; lock torque %.1f N m, break_torque %g N m)",
               j.name.c_str(), r.name.c_str(), simTime(), msg.child_link.c_str(),
               msg.parent_link.c_str(), msg.force, j.spring.break_force, msg.torque,
               j.spring.break_torque);
      break;
    }
  }
}

void SimNode::publish() {
  publishClock(/*force=*/true);  // the stamps below are a published clock value
  const ros::Time stamp = simStamp();
  // TF and the states only when sim time advanced (or the set of ragdolls changed): a
  // repeated stamp would make every tf2 listener complain (TF_REPEATED_DATA) while paused.
  if (steps_ != last_publish_step_) {
    publishTf(stamp);
    publishJointStates(stamp);
    publishLinkStates(stamp);
    last_publish_step_ = steps_;
  }
  interaction_->update(simTime());
  if (config_.publish_markers && markers_pub_.getNumSubscribers() > 0) publishMarkers(stamp);
  if (stats_pub_.getNumSubscribers() > 0) publishStats(stamp);
}

void SimNode::publishStats(const ros::Time& stamp) {
  ragdoll_sim::NodeStats m;
  m.header.stamp = stamp;
  m.received = received_;
  m.applied = applied_;
  m.rejected = rejected_;
  m.dropped = queue_.dropped();
  m.queued = static_cast<uint32_t>(queue_.size());
  m.max_queued = static_cast<uint32_t>(queue_.maxSize());
  m.queue_capacity = static_cast<uint32_t>(queue_.capacity());
  m.body_faults = body_faults_;
  m.steps = static_cast<uint64_t>(steps_);
  m.skipped_steps = static_cast<uint64_t>(pacer_.droppedSteps());
  m.sim_time = simTime();
  m.awake_bodies = static_cast<uint32_t>(world_->awakeBodyCount());
  m.resting_bodies = static_cast<uint32_t>(world_->islandCounters().resting_bodies);
  stats_pub_.publish(m);
}

}  // namespace node
}  // namespace ragdoll_sim
