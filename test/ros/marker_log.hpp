// Helper shared by the rostests: the node's ~markers (visualization_msgs/MarkerArray) messages
// as they arrive, with waiting for one that satisfies a condition.
#pragma once

#include <condition_variable>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <visualization_msgs/MarkerArray.h>

namespace ragdoll_test {

class MarkerLog {
 public:
  using Array = visualization_msgs::MarkerArray;

  MarkerLog(ros::NodeHandle& nh, const std::string& topic) {
    sub_ = nh.subscribe(topic, 100, &MarkerLog::onMarkers, this);
  }

  // The first message received after `after` (a count from count()) for which `pred` holds;
  // waits up to `timeout` s of wall time. False on timeout.
  bool waitFor(const std::function<bool(const Array&)>& pred, Array* out, size_t after = 0,
               double timeout = 20.0) {
    std::unique_lock<std::mutex> lock(mutex_);
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
    size_t next = after;
    while (ros::ok()) {
      for (; next < received_; ++next) {
        if (next + kept_.size() < received_) continue;  // dropped already
        const size_t k = next + kept_.size() - received_;  // index into kept_
        if (pred(kept_[k])) {
          if (out) *out = kept_[k];
          return true;
        }
      }
      if (ros::WallTime::now() >= deadline) return false;
      cv_.wait_for(lock, std::chrono::milliseconds(20));
    }
    return false;
  }

  // Number of messages received so far.
  size_t count() {
    std::lock_guard<std::mutex> lock(mutex_);
    return received_;
  }

  bool connected() const { return sub_.getNumPublishers() > 0; }

  static std::vector<const visualization_msgs::Marker*> inNs(const Array& a, const std::string& ns) {
    std::vector<const visualization_msgs::Marker*> out;
    for (const auto& m : a.markers)
      if (m.ns == ns) out.push_back(&m);
    return out;
  }

 private:
  void onMarkers(const Array::ConstPtr& msg) {
    std::lock_guard<std::mutex> lock(mutex_);
    kept_.push_back(*msg);
    ++received_;
    while (kept_.size() > 3000) kept_.pop_front();
    cv_.notify_all();
  }

  ros::Subscriber sub_;
  std::mutex mutex_;
  std::condition_variable cv_;
  std::deque<Array> kept_;
  size_t received_ = 0;
};

}  // namespace ragdoll_test
