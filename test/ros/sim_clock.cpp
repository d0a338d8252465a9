// rostest: the node on /use_sim_time publishes /clock every physics step (~clock_rate 0), and
// every stamp it publishes (TF, joint_states, link_states, markers) is a /clock value it
// published. An impulse stamped 0.3 s of sim time ahead acts exactly from that step.
#include <gtest/gtest.h>

#include <memory>
#include <mutex>
#include <set>

#include <ragdoll_sim/ApplyImpulse.h>
#include <ragdoll_sim/LinkStates.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/JointState.h>
#include <tf2_msgs/TFMessage.h>
#include <visualization_msgs/MarkerArray.h>

#include "node_log.hpp"
#include "sim_client.hpp"

using namespace ragdoll_test;

namespace {

const std::string kNode = "/ragdoll_sim";

struct Fixture {
  ros::NodeHandle nh;
  std::mutex mutex;
  std::vector<ros::Time> clock;
  std::map<std::string, std::vector<ros::Time>> stamps;  // topic -> stamps received
  std::vector<ragdoll_sim::LinkStates> link_states;
  ros::Subscriber clock_sub, tf_sub, js_sub, ls_sub, markers_sub;

  void init() {
    ros::TransportHints hints = ros::TransportHints().tcpNoDelay();
    clock_sub = nh.subscribe<rosgraph_msgs::Clock>(
        "/clock", 100000, [this](const rosgraph_msgs::Clock::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex);
          clock.push_back(m->clock);
        }, ros::VoidConstPtr(), hints);
    tf_sub = nh.subscribe<tf2_msgs::TFMessage>("/tf", 1000, [this](const tf2_msgs::TFMessage::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(mutex);
      for (const auto& t : m->transforms) stamps["tf"].push_back(t.header.stamp);
    });
    js_sub = nh.subscribe<sensor_msgs::JointState>("/joint_states", 1000, [this](const sensor_msgs::JointState::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(mutex);
      stamps["joint_states"].push_back(m->header.stamp);
    });
    ls_sub = nh.subscribe<ragdoll_sim::LinkStates>(kNode + "/link_states", 1000, [this](const ragdoll_sim::LinkStates::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(mutex);
      stamps["link_states"].push_back(m->header.stamp);
      link_states.push_back(*m);
    });
    markers_sub = nh.subscribe<visualization_msgs::MarkerArray>(kNode + "/markers", 100, [this](const visualization_msgs::MarkerArray::ConstPtr& m) {
      std::lock_guard<std::mutex> lock(mutex);
      for (const auto& mk : m->markers) stamps["markers"].push_back(mk.header.stamp);
    });
  }
  ros::Time latestClock() {
    std::lock_guard<std::mutex> lock(mutex);
    return clock.empty() ? ros::Time() : clock.back();
  }
  // Waits (wall clock) until the node's clock passes t.
  bool waitClock(const ros::Time& t, double timeout = 30.0) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < deadline) {
      if (latestClock() > t) return true;
      ros::WallDuration(0.02).sleep();
    }
    return false;
  }
};

Fixture* fx = nullptr;

// Linear velocity of `link` in a LinkStates message (NaN vector when absent).
Vec3 velocityOf(const ragdoll_sim::LinkStates& m, const std::string& link) {
  for (size_t i = 0; i < m.link.size(); ++i)
    if (m.link[i] == link)
      return Vec3(m.twist[i].linear.x, m.twist[i].linear.y, m.twist[i].linear.z);
  return Vec3::Constant(std::nan(""));
}

}  // namespace

TEST(SimClock, A_ClockEveryStepAndStampsAreClockValues) {
  ASSERT_TRUE(SimClient(kNode).waitUp()) << "node did not come up";
  ASSERT_TRUE(fx->waitClock(ros::Time(0.1))) << "no /clock";
  const ros::Time from = fx->latestClock();
  ASSERT_TRUE(fx->waitClock(from + ros::Duration(2.0))) << "the clock stopped";

  std::lock_guard<std::mutex> lock(fx->mutex);
  const std::vector<ros::Time>& c = fx->clock;
  ASSERT_GT(c.size(), 1000u);
  size_t not_one_step = 0;
  for (size_t k = 1; k < c.size(); ++k)
    if ((c[k] - c[k - 1]).toNSec() != 1000000) ++not_one_step;
  EXPECT_EQ(not_one_step, 0u) << "/clock does not advance by exactly one 1 ms step per message";
  const std::set<ros::Time> published(c.begin(), c.end());
  for (const char* topic : {"tf", "joint_states", "link_states", "markers"}) {
    const std::vector<ros::Time>& s = fx->stamps[topic];
    size_t checked = 0, missing = 0;
    for (const ros::Time& t : s) {
      if (t < c.front() || t > c.back()) continue;  // outside the clock messages we saw
      ++checked;
      if (!published.count(t)) ++missing;
    }
    EXPECT_GT(checked, 10u) << topic << ": too few messages";
    EXPECT_EQ(missing, 0u) << topic << ": " << missing << " of " << checked
                           << " stamps are no published /clock value";
  }
}

TEST(SimClock, B_StampedCommandActsAtItsSimTime) {
  ros::Publisher pub = fx->nh.advertise<ragdoll_sim::ApplyImpulse>(kNode + "/apply_impulse", 10);
  ASSERT_TRUE(waitConnected(pub));
  ragdoll_sim::ApplyImpulse cmd;
  cmd.link = "pelvis";
  cmd.frame = "link";
  cmd.impulse.y = 10.0;
  cmd.header.stamp = fx->latestClock() + ros::Duration(0.3);
  const ros::Time due = cmd.header.stamp;
  pub.publish(cmd);
  ASSERT_TRUE(fx->waitClock(due + ros::Duration(0.5)));

  std::lock_guard<std::mutex> lock(fx->mutex);
  size_t before = 0, after = 0;
  for (const ragdoll_sim::LinkStates& m : fx->link_states) {
    const Vec3 v = velocityOf(m, "pelvis");
    ASSERT_TRUE(v.allFinite());
    if (m.header.stamp < due && m.header.stamp > due - ros::Duration(0.3)) {
      ++before;
      EXPECT_LT(v.norm(), 1e-9) << "pelvis moving at " << m.header.stamp << " before " << due;
    } else if (m.header.stamp > due) {
      ++after;
      EXPECT_GT(v.y(), 0.05) << "pelvis still at rest at " << m.header.stamp << " after " << due;
    }
  }
  EXPECT_GT(before, 3u);
  EXPECT_GT(after, 3u);
}

int main(int argc, char** argv) {
  return runFixtureTests(argc, argv, "sim_clock_test", 2, fx);
}
