// Helpers shared by the rostests: URDF masses (urdfdom) and complete TF snapshots of the ragdoll
// (all links at one stamp) collected from /tf, plus momentum from two snapshots.
#pragma once

#include <algorithm>
#include <condition_variable>
#include <deque>
#include <map>
#include <mutex>
#include <set>
#include <string>
#include <vector>

#include <Eigen/Geometry>
#include <ros/ros.h>
#include <tf2_msgs/TFMessage.h>
#include <urdf_parser/urdf_parser.h>

namespace ragdoll_test {

using Vec3 = Eigen::Vector3d;

struct LinkMass {
  std::string name;
  double mass = 0.0;
  Eigen::Isometry3d inertial = Eigen::Isometry3d::Identity();  // COM frame in the link frame
};

// Links of the URDF in the robot_description parameter (every link, dummies included; links
// without <inertial> get mass 0).
inline std::vector<LinkMass> urdfLinks(std::string* root = nullptr) {
  std::string xml;
  if (!ros::param::get("/robot_description", xml)) return {};
  urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(xml);
  if (!model) return {};
  if (root && model->getRoot()) *root = model->getRoot()->name;
  std::vector<LinkMass> out;
  for (const auto& kv : model->links_) {
    LinkMass l;
    l.name = kv.first;
    if (kv.second->inertial) {
      l.mass = kv.second->inertial->mass;
      const urdf::Pose& o = kv.second->inertial->origin;
      l.inertial.translation() = Vec3(o.position.x, o.position.y, o.position.z);
      double x, y, z, w;
      o.rotation.getQuaternion(x, y, z, w);
      l.inertial.linear() = Eigen::Quaterniond(w, x, y, z).normalized().toRotationMatrix();
    }
    out.push_back(l);
  }
  return out;
}

struct Snapshot {
  ros::Time stamp;
  ros::WallTime received;
  std::map<std::string, Eigen::Isometry3d> poses;  // child frame -> pose in the world frame
  bool valid() const { return !stamp.isZero(); }
  Vec3 position(const std::string& link) const { return poses.at(link).translation(); }
};

// Collects /tf messages with parent `world_frame` and keeps the snapshots that hold every frame in
// `frames` at one stamp.
class TfSnapshots {
 public:
  TfSnapshots(ros::NodeHandle& nh, const std::vector<std::string>& frames,
              const std::string& world_frame = "world")
      : frames_(frames.begin(), frames.end()), world_frame_(world_frame) {
    sub_ = nh.subscribe("/tf", 200, &TfSnapshots::onTf, this);
  }

  // The earliest complete snapshot with stamp >= min_stamp that was received at or after
  // min_received; waits up to `timeout` s of wall time. Invalid (zero stamp) on timeout.
  Snapshot waitFor(const ros::Time& min_stamp, const ros::WallTime& min_received = ros::WallTime(),
                   double timeout = 20.0) {
    std::unique_lock<std::mutex> lock(mutex_);
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok()) {
      for (const Snapshot& s : complete_)
        if (s.stamp >= min_stamp && s.received >= min_received) return s;
      ros::WallTime now = ros::WallTime::now();
      if (now >= deadline) break;
      cv_.wait_for(lock, std::chrono::milliseconds(20));
    }
    return Snapshot();
  }

  // The next complete snapshot received from now on.
  Snapshot next(double timeout = 20.0) { return waitFor(ros::Time(), ros::WallTime::now(), timeout); }

  // Whether some node publishes /tf to us yet.
  bool connected() const { return sub_.getNumPublishers() > 0; }

  // The complete snapshots kept (the last 2000) with from <= stamp <= to, oldest first.
  std::vector<Snapshot> range(const ros::Time& from, const ros::Time& to) {
    std::lock_guard<std::mutex> lock(mutex_);
    std::vector<Snapshot> out;
    for (const Snapshot& s : complete_)
      if (s.stamp >= from && s.stamp <= to) out.push_back(s);
    return out;
  }

  Snapshot latest() {
    std::lock_guard<std::mutex> lock(mutex_);
    return complete_.empty() ? Snapshot() : complete_.back();
  }

  Snapshot first() {
    std::lock_guard<std::mutex> lock(mutex_);
    return first_;
  }

 private:
  void onTf(const tf2_msgs::TFMessage::ConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    const ros::WallTime now = ros::WallTime::now();
    for (const auto& t : msg->transforms) {
      if (t.header.frame_id != world_frame_ && t.header.frame_id != "/" + world_frame_) continue;
      if (!frames_.count(t.child_frame_id)) continue;
      Snapshot& s = pending_[t.header.stamp];
      s.stamp = t.header.stamp;
      s.received = now;
      Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
      pose.translation() = Vec3(t.transform.translation.x, t.transform.translation.y,
                                t.transform.translation.z);
      pose.linear() = Eigen::Quaterniond(t.transform.rotation.w, t.transform.rotation.x,
                                         t.transform.rotation.y, t.transform.rotation.z)
                          .normalized()
                          .toRotationMatrix();
      s.poses[t.child_frame_id] = pose;
    }
    for (auto it = pending_.begin(); it != pending_.end();) {
      if (it->second.poses.size() == frames_.size()) {
        if (complete_.empty() || it->first > complete_.back().stamp) {
          complete_.push_back(it->second);
          if (!first_.valid()) first_ = it->second;
        }
        it = pending_.erase(it);
      } else if (!complete_.empty() && it->first <= complete_.back().stamp) {
        it = pending_.erase(it);  // incomplete and superseded
      } else {
        ++it;
      }
    }
    while (complete_.size() > 2000) complete_.pop_front();
    while (pending_.size() > 100) pending_.erase(pending_.begin());
    cv_.notify_all();
  }

  std::set<std::string> frames_;
  std::string world_frame_;
  ros::Subscriber sub_;
  std::mutex mutex_;
  std::condition_variable cv_;
  std::map<ros::Time, Snapshot> pending_;
  std::deque<Snapshot> complete_;
  Snapshot first_;
};

inline std::vector<std::string> linkNames(const std::vector<LinkMass>& links) {
  std::vector<std::string> names;
  for (const LinkMass& l : links) names.push_back(l.name);
  return names;
}

// World position of a link's centre of mass.
inline Vec3 comOf(const Snapshot& s, const LinkMass& l) {
  return (s.poses.at(l.name) * l.inertial).translation();
}

// Total linear momentum sum_i m_i (c_i(b) - c_i(a)) / (t_b - t_a). Exact for the system's centre
// of mass when no external force acts between the two snapshots.
inline Vec3 momentum(const Snapshot& a, const Snapshot& b, const std::vector<LinkMass>& links) {
  const double dt = (b.stamp - a.stamp).toSec();
  Vec3 p = Vec3::Zero();
  for (const LinkMass& l : links) p += l.mass * (comOf(b, l) - comOf(a, l)) / dt;
  return p;
}

inline std::string str(const Vec3& v) {
  char buf[128];
  snprintf(buf, sizeof(buf), "(%.4f, %.4f, %.4f)", v.x(), v.y(), v.z());
  return buf;
}

}  // namespace ragdoll_test
