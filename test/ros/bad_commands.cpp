// rostest: every kind of bad input the node takes, on every topic and service, with the node
// paused (nothing moves unless a command lands). For each: a WARN on /rosout naming the
// problem (the node throttles per problem kind, so all of them show although they come within
// a second), a refused service answers success = false with the same words. Afterwards: no
// link state changed, 300 steps later the ragdolls are still at rest (a bad target accepted
// would drive the joints), ~link_states is finite, the node answers, and ~stats accounts for
// every command: received = applied + rejected + dropped + queued, with applied = 0.
// Tests run in order on one node.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <mutex>

#include <geometry_msgs/PointStamped.h>
#include <ragdoll_sim/ApplyForce.h>
#include <ragdoll_sim/ApplyImpulse.h>
#include <ragdoll_sim/DeleteRagdoll.h>
#include <ragdoll_sim/LinkStates.h>
#include <ragdoll_sim/NodeStats.h>
#include <ragdoll_sim/SetRagdollState.h>
#include <ragdoll_sim/SpawnRagdoll.h>
#include <sensor_msgs/JointState.h>
#include <visualization_msgs/InteractiveMarkerFeedback.h>

#include "node_log.hpp"
#include "sim_client.hpp"

using namespace ragdoll_test;
using visualization_msgs::InteractiveMarkerFeedback;

namespace {

const std::string kNode = "/ragdoll_sim";
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();
const char* kModel = RAGDOLL_SIM_SOURCE_DIR "/urdf/ragdoll.urdf";

std::string joined(const std::vector<std::string>& words) {
  std::string s;
  for (const std::string& w : words) s += (s.empty() ? "\"" : ", \"") + w + "\"";
  return s;
}

bool finite(const geometry_msgs::Pose& p, const geometry_msgs::Twist& t) {
  for (double v : {p.position.x, p.position.y, p.position.z, p.orientation.w, p.orientation.x,
                   p.orientation.y, p.orientation.z, t.linear.x, t.linear.y, t.linear.z,
                   t.angular.x, t.angular.y, t.angular.z})
    if (!std::isfinite(v)) return false;
  return true;
}

struct Fixture {
  ros::NodeHandle nh;
  SimClient sim{kNode};
  ros::Publisher impulse_pub, force_pub, target_pub, click_pub, feedback_pub;
  ros::Subscriber link_states_sub, stats_sub;
  std::unique_ptr<NodeWarnings> warnings;
  std::mutex mutex;
  ragdoll_sim::LinkStates link_states;
  ragdoll_sim::NodeStats stats;
  bool have_stats = false;
  uint64_t sent = 0, sent_bad = 0;  // command-topic messages (~apply_*, ~target_pose)
  // (ragdoll, link) -> state at the start
  std::map<std::pair<std::string, std::string>, ragdoll_sim::GetLinkState::Response> start;

  void init() {
    impulse_pub = nh.advertise<ragdoll_sim::ApplyImpulse>(kNode + "/apply_impulse", 100);
    force_pub = nh.advertise<ragdoll_sim::ApplyForce>(kNode + "/apply_force", 100);
    target_pub = nh.advertise<sensor_msgs::JointState>(kNode + "/target_pose", 100);
    click_pub = nh.advertise<geometry_msgs::PointStamped>("/clicked_point", 10);
    feedback_pub = nh.advertise<InteractiveMarkerFeedback>(kNode + "/drag/feedback", 10);
    warnings = std::make_unique<NodeWarnings>(nh, kNode);
    link_states_sub = nh.subscribe<ragdoll_sim::LinkStates>(
        kNode + "/link_states", 10, [this](const ragdoll_sim::LinkStates::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex);
          link_states = *m;
        });
    stats_sub = nh.subscribe<ragdoll_sim::NodeStats>(
        kNode + "/stats", 10, [this](const ragdoll_sim::NodeStats::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex);
          stats = *m;
          have_stats = true;
        });
  }

  // Waits for a WARN of the node holding every word.
  void expectWarn(const std::vector<std::string>& words) {
    EXPECT_TRUE(warnings->wait(words, 5.0)) << "no WARN from " << kNode << " with " << joined(words);
  }

  template <class Msg>
  void sendBad(const ros::Publisher& pub, const Msg& m, const std::vector<std::string>& words) {
    pub.publish(m);
    ++sent;
    ++sent_bad;
    expectWarn(words);
  }

  // Latest link_states with a stamp after `after` (wall clock wait); empty header on timeout.
  ragdoll_sim::LinkStates linkStatesAfter(const ros::Time& after, double timeout = 10.0) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < deadline) {
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (link_states.header.stamp > after) return link_states;
      }
      ros::WallDuration(0.02).sleep();
    }
    return ragdoll_sim::LinkStates();
  }

  template <class Pred>
  bool waitStats(Pred pred, ragdoll_sim::NodeStats* out, double timeout = 10.0) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < deadline) {
      {
        std::lock_guard<std::mutex> lock(mutex);
        *out = stats;
        if (have_stats && pred(stats)) return true;
      }
      ros::WallDuration(0.02).sleep();
    }
    return false;
  }

  ragdoll_sim::ApplyImpulse goodImpulse() const {
    ragdoll_sim::ApplyImpulse m;
    m.link = "torso";
    m.frame = "link";
    m.impulse.x = 1.0;
    return m;
  }
  ragdoll_sim::ApplyForce goodForce() const {
    ragdoll_sim::ApplyForce m;
    m.link = "torso";
    m.frame = "link";
    m.force.x = 10.0;
    m.duration = 0.1;
    return m;
  }
  void click(const Vec3& p, const std::string& frame) {
    geometry_msgs::PointStamped m;
    m.header.frame_id = frame;
    m.point.x = p.x();
    m.point.y = p.y();
    m.point.z = p.z();
    click_pub.publish(m);
  }
  void drag(const Vec3& p, const std::string& frame) {
    InteractiveMarkerFeedback fb;
    fb.header.frame_id = frame;
    fb.client_id = "/bad_commands_test";
    fb.marker_name = "ragdoll";  // the launch-time ragdoll (URDF robot name)
    fb.control_name = "move";
    fb.event_type = InteractiveMarkerFeedback::POSE_UPDATE;
    fb.pose.position.x = p.x();
    fb.pose.position.y = p.y();
    fb.pose.position.z = p.z();
    fb.pose.orientation.w = 1.0;
    feedback_pub.publish(fb);
  }

  // Every simulated link of every ragdoll, from ~get_link_state.
  std::map<std::pair<std::string, std::string>, ragdoll_sim::GetLinkState::Response> states(
      const ragdoll_sim::LinkStates& names) {
    std::map<std::pair<std::string, std::string>, ragdoll_sim::GetLinkState::Response> out;
    for (size_t i = 0; i < names.link.size(); ++i)
      out[{names.ragdoll[i], names.link[i]}] = sim.link(names.ragdoll[i], names.link[i]);
    return out;
  }
};

Fixture* fx = nullptr;

template <class Srv>
typename Srv::Response callRefused(const std::string& service, Srv srv,
                                   const std::vector<std::string>& words) {
  EXPECT_TRUE(ros::service::call(kNode + "/" + service, srv)) << service << " call failed";
  EXPECT_FALSE(srv.response.success) << service << " accepted a bad request";
  for (const std::string& w : words)
    EXPECT_NE(srv.response.message.find(w), std::string::npos)
        << service << " answer '" << srv.response.message << "' lacks \"" << w << "\"";
  fx->expectWarn(words);
  return srv.response;
}

}  // namespace

TEST(BadCommands, A_SetupTwoRagdollsAtRest) {
  ASSERT_TRUE(fx->sim.waitUp()) << "node did not come up";
  ragdoll_sim::SpawnRagdoll s;
  s.request.name = "second";
  s.request.urdf_file = kModel;
  s.request.pose.position.x = 3.0;
  s.request.pose.position.z = 5.0;
  s.request.pose.orientation.w = 1.0;
  ASSERT_TRUE(ros::service::call(kNode + "/spawn", s));
  ASSERT_TRUE(s.response.success) << s.response.message;

  // A near-unit quaternion is normalized, not refused: "second" stays where it is.
  const ragdoll_sim::GetLinkState::Response root = fx->sim.link("second", "pelvis");
  ASSERT_TRUE(root.success);
  ragdoll_sim::SetRagdollState set;
  set.request.ragdoll = "second";
  set.request.pose = root.pose;
  set.request.pose.orientation.w *= 1.005;
  set.request.pose.orientation.x *= 1.005;
  set.request.pose.orientation.y *= 1.005;
  set.request.pose.orientation.z *= 1.005;
  ASSERT_TRUE(ros::service::call(kNode + "/set_ragdoll_state", set));
  EXPECT_TRUE(set.response.success) << set.response.message;
  const ragdoll_sim::GetLinkState::Response moved = fx->sim.link("second", "pelvis");
  EXPECT_NEAR(orientation(moved).norm(), 1.0, 1e-12);
  EXPECT_LT((orientation(moved).coeffs() - orientation(root).coeffs()).norm(), 1e-9);

  // One step (no gravity: nothing moves) so that ~link_states lists every simulated link (a
  // paused node publishes them once per step).
  ASSERT_TRUE(waitConnected(fx->link_states_sub));
  ASSERT_TRUE(fx->sim.step(1).success);
  const ragdoll_sim::LinkStates names = fx->linkStatesAfter(ros::Time(0));
  ASSERT_GT(names.link.size(), 20u) << "no ~link_states of both ragdolls";
  fx->start = fx->states(names);
  // At rest up to what the spawn leaves: centres are placed on the 0.23 nm grid of the core
  // (translation invariance, src/core/body.hpp), and the joints take up that fraction of a
  // nanometre in the first steps (~1e-8 m/s).
  for (const auto& [key, s0] : fx->start) {
    ASSERT_TRUE(s0.success) << key.first << "/" << key.second;
    EXPECT_LT(linear(s0).norm(), 1e-7) << key.first << "/" << key.second << " not at rest";
  }
  ASSERT_TRUE(waitConnected(fx->impulse_pub));
  ASSERT_TRUE(waitConnected(fx->force_pub));
  ASSERT_TRUE(waitConnected(fx->target_pub));
  ASSERT_TRUE(waitConnected(fx->click_pub));
  ASSERT_TRUE(waitConnected(fx->feedback_pub));
  ASSERT_TRUE(waitConnected(fx->stats_sub));
}

TEST(BadCommands, B_Impulses) {
  ragdoll_sim::ApplyImpulse m = fx->goodImpulse();
  m.ragdoll = "nobody";
  fx->sendBad(fx->impulse_pub, m, {"impulse rejected: unknown ragdoll 'nobody'"});
  m = fx->goodImpulse();
  m.link = "no_such_link";
  fx->sendBad(fx->impulse_pub, m, {"impulse on 'no_such_link' rejected: unknown link 'no_such_link'"});
  m.link = "";
  fx->sendBad(fx->impulse_pub, m, {"impulse on '' rejected: empty link name"});
  m.link = "waist_link1";
  fx->sendBad(fx->impulse_pub, m, {"'waist_link1' is a massless dummy link"});
  m = fx->goodImpulse();
  m.frame = "camera_impulse";
  fx->sendBad(fx->impulse_pub, m, {"impulse on 'torso' rejected: unknown frame 'camera_impulse'"});
  m = fx->goodImpulse();
  m.impulse.y = kNaN;
  fx->sendBad(fx->impulse_pub, m, {"impulse on 'torso' rejected: impulse (1, nan, 0) is not finite"});
  m = fx->goodImpulse();
  m.point.z = kInf;
  fx->sendBad(fx->impulse_pub, m, {"impulse on 'torso' rejected: point (0, 0, inf) is not finite"});
  m = fx->goodImpulse();
  m.impulse.x = 1e7;
  fx->sendBad(fx->impulse_pub, m, {"impulse on 'torso' rejected", "exceeds max_impulse"});
  m = fx->goodImpulse();
  m.point.x = 50.0;
  fx->sendBad(fx->impulse_pub, m, {"impulse on 'torso' rejected", "max_lever_arm"});
}

TEST(BadCommands, C_Forces) {
  ragdoll_sim::ApplyForce m = fx->goodForce();
  m.force.z = kNaN;
  fx->sendBad(fx->force_pub, m, {"force on 'torso' rejected: force (10, 0, nan) is not finite"});
  m = fx->goodForce();
  m.torque.x = -kInf;
  fx->sendBad(fx->force_pub, m, {"force on 'torso' rejected: torque (-inf, 0, 0) is not finite"});
  m = fx->goodForce();
  m.force.x = 1e9;
  fx->sendBad(fx->force_pub, m, {"force on 'torso' rejected", "exceeds max_force"});
  m = fx->goodForce();
  m.torque.y = 1e9;
  fx->sendBad(fx->force_pub, m, {"force on 'torso' rejected", "exceeds max_torque"});
  m = fx->goodForce();
  m.duration = kNaN;
  fx->sendBad(fx->force_pub, m, {"force on 'torso' rejected: duration nan is not finite"});
  m = fx->goodForce();
  m.frame = "camera_force";
  fx->sendBad(fx->force_pub, m, {"force on 'torso' rejected: unknown frame 'camera_force'"});
}

TEST(BadCommands, D_TargetPoses) {
  sensor_msgs::JointState m;
  m.name = {"elbow_l", "no_such_joint"};
  m.position = {0.5, 0.5};
  fx->sendBad(fx->target_pub, m, {"target pose names unknown joint 'no_such_joint'"});
  m.name = {"elbow_l"};
  m.position = {kNaN};
  fx->sendBad(fx->target_pub, m, {"target pose position of 'elbow_l' is not finite"});
  m.position = {0.5};
  m.velocity = {kInf};
  fx->sendBad(fx->target_pub, m, {"target pose velocity of 'elbow_l' is not finite"});
  m.name = {"elbow_l", "elbow_r"};
  m.position = {0.5};
  m.velocity.clear();
  fx->sendBad(fx->target_pub, m, {"target pose has 2 names but 1 positions"});
  m.name = {"elbow_l", "elbow_l"};
  m.position = {0.5, 0.6};
  fx->sendBad(fx->target_pub, m, {"target pose names joint 'elbow_l' twice"});
  m.name = {"elbow_l", "second/elbow_r"};
  fx->sendBad(fx->target_pub, m, {"one ragdoll per message"});
  m.name.clear();
  m.position.clear();
  fx->sendBad(fx->target_pub, m, {"target pose with no joint names"});
}

TEST(BadCommands, E_ClicksAndDrags) {
  fx->click(Vec3(0, 0, 5), "camera_click");
  fx->expectWarn({"clicked point in frame 'camera_click'", "poke dropped"});
  fx->click(Vec3(kNaN, 0, 5), "world");
  fx->expectWarn({"clicked point (nan, 0, 5) is not finite", "poke dropped"});
  fx->click(Vec3(0, 0, -50), "world");
  fx->expectWarn({"from the nearest link", "max_distance", "poke dropped"});
  fx->drag(Vec3(0, 0, 5), "camera_drag");
  fx->expectWarn({"drag of 'ragdoll': pose in frame 'camera_drag'", "drag dropped"});
  fx->drag(Vec3(0, kInf, 5), "world");
  fx->expectWarn({"drag of 'ragdoll': handle position (0, inf, 5) is not finite", "drag dropped"});
}

TEST(BadCommands, F_Services) {
  ragdoll_sim::SpawnRagdoll spawn;
  spawn.request.name = "bad_urdf";
  spawn.request.urdf = "<robot name='x'><link name='a'/><joint";
  callRefused("spawn", spawn, {"spawn 'bad_urdf' rejected: failed to load the URDF"});
  spawn.request.name = "nan_pose";
  spawn.request.urdf = "";
  spawn.request.urdf_file = kModel;
  spawn.request.pose.position.z = kNaN;
  spawn.request.pose.orientation.w = 1.0;
  callRefused("spawn", spawn, {"spawn 'nan_pose' rejected: the position (0, 0, nan) is not finite"});
  spawn.request.name = "fat_quat";
  spawn.request.pose.position.z = 5.0;
  spawn.request.pose.orientation.w = 2.0;
  callRefused("spawn", spawn, {"spawn 'fat_quat' rejected: the orientation", "not a unit quaternion"});
  spawn.request.name = "nan_quat";
  spawn.request.pose.orientation.x = kNaN;
  callRefused("spawn", spawn, {"spawn 'nan_quat' rejected: the orientation is not finite"});
  spawn.request.name = "far_away";
  spawn.request.pose.orientation.x = 0.0;
  spawn.request.pose.orientation.w = 1.0;
  spawn.request.pose.position.y = 1e6;
  callRefused("spawn", spawn, {"spawn 'far_away' rejected: the position (0, 1e+06, 5) is",
                               "more than ~max_position = 10000 m"});
  spawn.request.pose.position.y = 0.0;
  spawn.request.name = "2bad";
  spawn.request.pose.orientation.x = 0.0;
  spawn.request.pose.orientation.w = 1.0;
  callRefused("spawn", spawn, {"spawn '2bad' rejected", "starts with a digit"});

  ragdoll_sim::DeleteRagdoll del;
  del.request.name = "nobody";
  callRefused("delete", del, {"delete rejected: no ragdoll named 'nobody'"});

  ragdoll_sim::SetRagdollState set;
  set.request.ragdoll = "second";
  set.request.pose.position.x = kInf;
  set.request.pose.orientation.w = 1.0;
  callRefused("set_ragdoll_state", set, {"set_ragdoll_state rejected: the position (inf, 0, 0)"});
  set.request.pose.position.x = -2e4;
  callRefused("set_ragdoll_state", set, {"set_ragdoll_state rejected: the position (-20000, 0, 0)",
                                         "~max_position"});
  set.request.pose.position.x = 3.0;
  set.request.pose.position.z = 5.0;
  set.request.pose.orientation.w = 0.5;
  callRefused("set_ragdoll_state", set,
              {"set_ragdoll_state rejected: the orientation", "has length 0.5", "not a unit quaternion"});
  set.request.pose.orientation.w = 1.0;
  set.request.twist.angular.z = kNaN;
  callRefused("set_ragdoll_state", set, {"set_ragdoll_state rejected: the twist is not finite"});
  set.request.twist.angular.z = 0.0;
  set.request.twist.linear.x = 1e6;
  callRefused("set_ragdoll_state", set, {"set_ragdoll_state rejected", "~max_linear_speed"});
  set.request.twist.linear.x = 0.0;
  set.request.ragdoll = "nobody";
  callRefused("set_ragdoll_state", set, {"set_ragdoll_state rejected: no ragdoll named 'nobody'"});

  ragdoll_sim::GetLinkState get;
  get.request.ragdoll = "second";
  get.request.link = "no_such_link";
  callRefused("get_link_state", get, {"ragdoll 'second' has no simulated link 'no_such_link'"});
  get.request.ragdoll = "nobody";
  callRefused("get_link_state", get, {"get_link_state: no ragdoll named 'nobody'"});

  // NaN is outside every range: the node refuses it and answers the values in force
  // (gravity 0 here).
  std::map<std::string, double> now;
  EXPECT_TRUE(fx->sim.reconfigure({{{"gravity_z", kNaN}}, {}, {}}, &now));
  const bool answered = now.count("gravity_z") > 0;
  if (answered) {
    EXPECT_EQ(now["gravity_z"], 0.0) << "the refused NaN gravity is in force";
  }
  EXPECT_TRUE(answered) << "no gravity_z in the answer";
  fx->expectWarn({"reconfigure refused: gravity_z = nan is outside its range [-100, 100]"});

  const double t0 = fx->sim.step(0).sim_time;
  ragdoll_sim::Step step;
  step.request.steps = 1000000000u;
  const ragdoll_sim::Step::Response r =
      callRefused("step", step, {"step rejected: 1000000000 steps exceed ~max_steps_per_call = 5000"});
  EXPECT_EQ(r.sim_time, t0) << "a refused step must not step";
}

// Stamped far in the future, valid impulses wait in the queue (50 places): 10 more are dropped,
// counted, and warned about.
TEST(BadCommands, G_QueueOverflow) {
  ragdoll_sim::ApplyImpulse m = fx->goodImpulse();
  m.header.stamp = ros::Time::now() + ros::Duration(1000.0);
  for (int i = 0; i < 60; ++i) {
    fx->impulse_pub.publish(m);
    ++fx->sent;
  }
  fx->expectWarn({"impulse for the first ragdoll dropped: 50 commands are already waiting",
                  "max_queued_commands"});
  ragdoll_sim::NodeStats s;
  EXPECT_TRUE(fx->waitStats([](const ragdoll_sim::NodeStats& x) { return x.dropped == 10; }, &s))
      << "dropped " << s.dropped << ", queued " << s.queued;
  EXPECT_EQ(s.queued, 50u);
  EXPECT_EQ(s.max_queued, 50u);
  EXPECT_EQ(s.queue_capacity, 50u);
  EXPECT_EQ(fx->sim.step(0).pending_commands, 50u);
}

TEST(BadCommands, H_NothingChangedNodeAliveFinite) {
  // Nothing landed: every link exactly where it was (paused, no step since the snapshot).
  ragdoll_sim::LinkStates names;
  for (const auto& [key, s] : fx->start) {
    names.ragdoll.push_back(key.first);
    names.link.push_back(key.second);
  }
  for (const auto& [key, s1] : fx->states(names)) {
    const auto& s0 = fx->start.at(key);
    ASSERT_TRUE(s1.success) << key.first << "/" << key.second;
    EXPECT_EQ(position(s1), position(s0)) << key.first << "/" << key.second;
    EXPECT_EQ(linear(s1), linear(s0)) << key.first << "/" << key.second;
    EXPECT_EQ(angular(s1), angular(s0)) << key.first << "/" << key.second;
  }

  // 300 steps without gravity: a target, force or impulse that slipped through would move it.
  const ros::Time before = fx->linkStatesAfter(ros::Time(0)).header.stamp;
  const ragdoll_sim::Step::Response r = fx->sim.step(300);
  ASSERT_TRUE(r.success) << r.message;
  EXPECT_EQ(r.pending_commands, 50u);
  const ragdoll_sim::LinkStates after = fx->linkStatesAfter(before);
  ASSERT_EQ(after.link.size(), fx->start.size()) << "no ~link_states after the steps";
  for (size_t i = 0; i < after.link.size(); ++i) {
    EXPECT_TRUE(finite(after.pose[i], after.twist[i])) << after.ragdoll[i] << "/" << after.link[i];
    const Vec3 v(after.twist[i].linear.x, after.twist[i].linear.y, after.twist[i].linear.z);
    EXPECT_LT(v.norm(), 1e-6) << after.ragdoll[i] << "/" << after.link[i] << " moves";
  }

  // Every command accounted for; none applied.
  ragdoll_sim::NodeStats s;
  EXPECT_TRUE(fx->waitStats([](const ragdoll_sim::NodeStats& x) { return x.received == fx->sent; }, &s))
      << "received " << s.received << " of " << fx->sent;
  EXPECT_EQ(s.applied, 0u);
  EXPECT_EQ(s.rejected, fx->sent_bad);
  EXPECT_EQ(s.dropped, 10u);
  EXPECT_EQ(s.received, s.applied + s.rejected + s.dropped + s.queued);
  EXPECT_EQ(s.body_faults, 0u);
  std::printf("[ stats    ] received %llu, applied %llu, rejected %llu, dropped %llu, queued %u\n",
              static_cast<unsigned long long>(s.received), static_cast<unsigned long long>(s.applied),
              static_cast<unsigned long long>(s.rejected), static_cast<unsigned long long>(s.dropped),
              s.queued);
}

int main(int argc, char** argv) {
  return runFixtureTests(argc, argv, "bad_commands_test", 2, fx);
}
