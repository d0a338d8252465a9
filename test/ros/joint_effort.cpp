// rostest: ~joint_effort. On urdf/pendulum.urdf with its base pinned and gravity off, an effort
// tau on the hinge turns the bar the way of tau: after n steps its angle (read from
// /pend/joint_states) is tau t^2 / (2 I) within 2 %, I = the bar's inertia about the hinge,
// and joint_states reports the effort. Bad commands (an unknown joint, NaN, above ~max_torque,
// lengths that differ, two ragdolls in one message) each give one WARN naming the problem,
// move nothing, and the sim goes on. Tests run in order and share one node.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <memory>
#include <mutex>
#include <sstream>

#include <ragdoll_sim/SetRagdollState.h>
#include <ragdoll_sim/SpawnRagdoll.h>
#include <sensor_msgs/JointState.h>

#include "node_log.hpp"
#include "sim_client.hpp"

using namespace ragdoll_test;

namespace {

const std::string kNode = "/ragdoll_sim";
// urdf/pendulum.urdf: the bar (1 kg, Ixx 0.021 kg m^2 about its centre 0.25 m below the hinge).
constexpr double kInertia = 0.021 + 1.0 * 0.25 * 0.25;

struct Fixture {
  ros::NodeHandle nh;
  SimClient sim{kNode};
  ros::Publisher effort_pub;
  ros::Subscriber pend_sub;
  std::unique_ptr<NodeWarnings> warnings;
  std::mutex mutex;
  sensor_msgs::JointState pend;

  void init() {
    effort_pub = nh.advertise<sensor_msgs::JointState>(kNode + "/joint_effort", 10);
    pend_sub = nh.subscribe<sensor_msgs::JointState>(
        "/pend/joint_states", 50, [this](const sensor_msgs::JointState::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex);
          pend = *m;
        });
    warnings = std::make_unique<NodeWarnings>(nh, kNode);
  }
  // The pendulum's joint state once the node published the state after the last ~step.
  sensor_msgs::JointState settled() {
    ros::WallDuration(0.3).sleep();  // a few publish cycles: the last one shows the last step
    std::lock_guard<std::mutex> lock(mutex);
    return pend;
  }
  void send(const std::vector<std::string>& names, const std::vector<double>& efforts) {
    sensor_msgs::JointState m;
    m.name = names;
    m.effort = efforts;
    effort_pub.publish(m);
    ros::WallDuration(0.2).sleep();  // the node's loop applies it (also while paused)
  }
};

Fixture* fx = nullptr;

double value(const std::vector<double>& v, const sensor_msgs::JointState& s, const std::string& n) {
  for (size_t i = 0; i < s.name.size() && i < v.size(); ++i)
    if (s.name[i] == n) return v[i];
  return std::numeric_limits<double>::quiet_NaN();
}

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The pendulum at rest where it is (joint velocities zero).
void stopPendulum() {
  const ragdoll_sim::GetLinkState::Response base = fx->sim.link("pend", "base");
  ASSERT_TRUE(base.success) << base.message;
  ragdoll_sim::SetRagdollState set;
  set.request.ragdoll = "pend";
  set.request.pose = base.pose;
  ASSERT_TRUE(ros::service::call(kNode + "/set_ragdoll_state", set));
  ASSERT_TRUE(set.response.success) << set.response.message;
}

}  // namespace

TEST(JointEffort, A_EffortTurnsTheHingeAsTauOverI) {
  ASSERT_TRUE(fx->sim.waitUp()) << "node did not come up";
  ragdoll_sim::SpawnRagdoll spawn;
  spawn.request.name = "pend";
  spawn.request.urdf = readFile(std::string(RAGDOLL_SIM_SOURCE_DIR) + "/urdf/pendulum.urdf");
  spawn.request.pose.position.x = 3.0;  // away from the ragdoll
  spawn.request.pose.position.z = 5.0;
  spawn.request.fixed_base = true;
  ASSERT_TRUE(ros::service::call(kNode + "/spawn", spawn));
  ASSERT_TRUE(spawn.response.success) << spawn.response.message;
  ASSERT_TRUE(waitConnected(fx->effort_pub)) << "node does not subscribe ~joint_effort";
  ASSERT_TRUE(waitConnected(fx->pend_sub)) << "no /pend/joint_states";
  ASSERT_TRUE(fx->sim.step(10).success);
  const sensor_msgs::JointState start = fx->settled();
  const double q0 = value(start.position, start, "hinge");
  ASSERT_TRUE(std::isfinite(q0)) << "no hinge in /pend/joint_states";

  const double tau = -0.5;  // N m
  fx->send({"pend/hinge"}, {tau});
  const int n = 200;
  const ragdoll_sim::Step::Response r = fx->sim.step(n);
  ASSERT_TRUE(r.success) << r.message;
  const sensor_msgs::JointState s = fx->settled();
  const double dq = value(s.position, s, "hinge") - q0;
  const double t = n * 1e-3;
  const double expected = tau * t * t / (2 * kInertia);
  EXPECT_NEAR(dq, expected, 0.02 * std::abs(expected)) << "the hinge turned " << dq << " rad";
  EXPECT_NEAR(value(s.effort, s, "hinge"), tau, 1e-6) << "joint_states.effort";
  std::printf("[ effort   ] tau %.2f N m for %.3f s: hinge turned %.5f rad, tau t^2/(2I) = "
              "%.5f rad (%.2f %%); joint_states.effort %.4f\n", tau, t, dq, expected,
              100 * (dq / expected - 1), value(s.effort, s, "hinge"));

  fx->send({"pend/hinge"}, {0.0});  // ends it
  stopPendulum();
}

TEST(JointEffort, B_BadCommandsWarnAndMoveNothing) {
  ASSERT_TRUE(fx->sim.step(5).success);
  const sensor_msgs::JointState before = fx->settled();
  const double q0 = value(before.position, before, "hinge");
  ASSERT_TRUE(std::isfinite(q0));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  struct Bad {
    std::vector<std::string> names;
    std::vector<double> efforts;
    std::vector<std::string> words;  // what the WARN must say
  };
  const std::vector<Bad> bad = {
      {{"pend/no_such_joint"}, {1.0}, {"no_such_joint"}},
      {{"pend/hinge"}, {nan}, {"'hinge'", "not finite"}},
      {{"pend/hinge"}, {250.0}, {"'hinge'", "250", "max_torque = 100"}},
      {{"pend/hinge"}, {1.0, 2.0}, {"1 names but 2 efforts"}},
      {{"pend/hinge", "elbow_l"}, {1.0, 1.0}, {"one ragdoll per message"}},
  };
  for (const Bad& b : bad) {
    fx->send(b.names, b.efforts);
    std::string all;
    for (const std::string& w : b.words) all += " '" + w + "'";
    EXPECT_TRUE(fx->warnings->wait(b.words, 5.0)) << "no WARN with" << all;
    ros::WallDuration(0.2).sleep();
    EXPECT_EQ(fx->warnings->count(b.words), 1u) << "WARNs with" << all;
  }
  const ragdoll_sim::Step::Response r = fx->sim.step(200);
  ASSERT_TRUE(r.success) << "the sim stopped: " << r.message;
  const sensor_msgs::JointState s = fx->settled();
  const double q = value(s.position, s, "hinge");
  ASSERT_TRUE(std::isfinite(q));
  EXPECT_NEAR(q, q0, 1e-6) << "a dropped command moved the hinge";
  EXPECT_NEAR(value(s.effort, s, "hinge"), 0.0, 1e-9);
}

int main(int argc, char** argv) { return runFixtureTests(argc, argv, "joint_effort_test", 2, fx); }
