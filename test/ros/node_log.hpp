// Helpers shared by the rostests: the node's WARN (and above) messages from /rosout, waiting
// for a publisher's subscribers, and the test main.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <ros/ros.h>
#include <rosgraph_msgs/Log.h>

namespace ragdoll_test {

class NodeWarnings {
 public:
  NodeWarnings(ros::NodeHandle& nh, const std::string& node) : node_(node) {
    sub_ = nh.subscribe("/rosout", 100, &NodeWarnings::onLog, this);
  }

  // The warnings so far that contain every one of `words`.
  size_t count(const std::vector<std::string>& words) {
    std::lock_guard<std::mutex> lock(mutex_);
    size_t n = 0;
    for (const auto& w : warnings_) {
      bool all = true;
      for (const auto& word : words) all = all && w.msg.find(word) != std::string::npos;
      n += all;
    }
    return n;
  }

  // Waits up to `timeout` s for a warning of the node containing every one of `words`.
  bool wait(const std::vector<std::string>& words, double timeout) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < deadline) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        for (const auto& w : warnings_) {
          bool all = true;
          for (const auto& word : words) all = all && w.msg.find(word) != std::string::npos;
          if (all) return true;
        }
      }
      ros::WallDuration(0.02).sleep();
    }
    return false;
  }

 private:
  void onLog(const rosgraph_msgs::Log::ConstPtr& m) {
    if (m->name != node_ || m->level < rosgraph_msgs::Log::WARN) return;
    std::lock_guard<std::mutex> lock(mutex_);
    warnings_.push_back(*m);
  }

  std::string node_;
  ros::Subscriber sub_;
  std::mutex mutex_;
  std::vector<rosgraph_msgs::Log> warnings_;
};

inline bool waitConnected(const ros::Publisher& pub, double timeout = 20.0) {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
  while (ros::ok() && pub.getNumSubscribers() == 0 && ros::WallTime::now() < deadline)
    ros::WallDuration(0.02).sleep();
  return pub.getNumSubscribers() > 0;
}

inline bool waitConnected(const ros::Subscriber& sub, double timeout = 20.0) {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
  while (ros::ok() && sub.getNumPublishers() == 0 && ros::WallTime::now() < deadline)
    ros::WallDuration(0.02).sleep();
  return sub.getNumPublishers() > 0;
}

// The body of a rostest's main: gtest and ROS set up, callbacks on `spinners` threads, then
// setup(), the tests, and teardown() once the spinner has stopped (no callback still running).
template <class Setup, class Teardown>
int runRosTests(int argc, char** argv, const char* name, int spinners, Setup setup,
                Teardown teardown) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, name);
  ros::AsyncSpinner spinner(spinners);
  spinner.start();
  setup();
  const int rc = RUN_ALL_TESTS();
  spinner.stop();
  teardown();
  return rc;
}

// The usual main of a rostest client: a Fixture (with init()) built after ros::init, reachable
// through `global` while the tests run, destroyed before the spinner's threads go.
template <class Fixture>
int runFixtureTests(int argc, char** argv, const char* name, int spinners, Fixture*& global) {
  std::unique_ptr<Fixture> fixture;
  return runRosTests(
      argc, argv, name, spinners,
      [&] {
        fixture = std::make_unique<Fixture>();
        global = fixture.get();
        global->init();
      },
      [&] {
        global = nullptr;
        fixture.reset();
      });
}

}  // namespace ragdoll_test
