// rostest: several ragdolls in one world and the services. The node starts paused without
// gravity; the tests run in order on one node and step it themselves:
// A spawn (and refused spawns), B TF / joint_states / link_states of both, C commands
// addressed by ragdoll, D ~set_ragdoll_state, E ~step, F ~clear_forces, G ~reset, H ~delete.
#include <gtest/gtest.h>

#include <memory>
#include <mutex>

#include <ragdoll_sim/ApplyForce.h>
#include <ragdoll_sim/ApplyImpulse.h>
#include <ragdoll_sim/DeleteRagdoll.h>
#include <ragdoll_sim/LinkStates.h>
#include <ragdoll_sim/SetRagdollState.h>
#include <ragdoll_sim/SpawnRagdoll.h>
#include <sensor_msgs/JointState.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include "node_log.hpp"
#include "sim_client.hpp"

using namespace ragdoll_test;

namespace {

const std::string kNode = "/ragdoll_sim";
const Vec3 kFirstSpawn(0, 0, 5), kSecondSpawn(2, 0, 5);

struct Fixture {
  ros::NodeHandle nh;
  SimClient sim{kNode};
  std::vector<LinkMass> links;
  std::string root;
  std::unique_ptr<NodeWarnings> warnings;
  ros::Publisher impulse_pub, force_pub;
  ros::Subscriber first_js_sub, second_js_sub, link_states_sub;
  std::mutex mutex;
  sensor_msgs::JointState first_js, second_js;
  ragdoll_sim::LinkStates link_states;

  void init() {
    links = urdfLinks(&root);
    warnings = std::make_unique<NodeWarnings>(nh, kNode);
    impulse_pub = nh.advertise<ragdoll_sim::ApplyImpulse>(kNode + "/apply_impulse", 10);
    force_pub = nh.advertise<ragdoll_sim::ApplyForce>(kNode + "/apply_force", 10);
    first_js_sub = nh.subscribe<sensor_msgs::JointState>(
        "/joint_states", 10, [this](const sensor_msgs::JointState::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex);
          first_js = *m;
        });
    second_js_sub = nh.subscribe<sensor_msgs::JointState>(
        "/second/joint_states", 10, [this](const sensor_msgs::JointState::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex);
          second_js = *m;
        });
    link_states_sub = nh.subscribe<ragdoll_sim::LinkStates>(
        kNode + "/link_states", 10, [this](const ragdoll_sim::LinkStates::ConstPtr& m) {
          std::lock_guard<std::mutex> lock(mutex);
          link_states = *m;
        });
  }

  bool spawn(const std::string& name, const std::string& urdf, const std::string& file,
             const Vec3& p, std::string* message = nullptr) {
    ragdoll_sim::SpawnRagdoll s;
    s.request.name = name;
    s.request.urdf = urdf;
    s.request.urdf_file = file;
    s.request.pose.position.x = p.x();
    s.request.pose.position.y = p.y();
    s.request.pose.position.z = p.z();
    s.request.pose.orientation.w = 1.0;
    if (!ros::service::call(kNode + "/spawn", s)) return false;
    if (message) *message = s.response.message;
    return s.response.success;
  }

  // Waits (wall clock) until `pred` holds for the latest messages.
  template <class Pred>
  bool waitFor(Pred pred, double timeout = 10.0) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < deadline) {
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (pred()) return true;
      }
      ros::WallDuration(0.02).sleep();
    }
    return false;
  }
};

Fixture* fx = nullptr;

std::string urdfPath() {
  std::string p;
  ros::param::get("~urdf_path", p);
  return p;
}

}  // namespace

TEST(MultiRagdoll, A_Spawn) {
  ASSERT_TRUE(fx->sim.waitUp()) << "node did not come up";
  ASSERT_GT(fx->links.size(), 1u);
  std::string message;
  ASSERT_TRUE(fx->spawn("second", "", urdfPath(), kSecondSpawn, &message)) << message;
  EXPECT_TRUE(ros::param::has("/second/robot_description"));

  const auto first = fx->sim.link("", fx->root);
  const auto second = fx->sim.link("second", fx->root);
  ASSERT_TRUE(first.success) << first.message;
  ASSERT_TRUE(second.success) << second.message;
  EXPECT_LT((position(first) - kFirstSpawn).norm(), 1e-9);
  EXPECT_LT((position(second) - kSecondSpawn).norm(), 1e-9);

  // Refused: a name in use, a bad name, a broken URDF, no URDF. The node keeps serving.
  EXPECT_FALSE(fx->spawn("second", "", urdfPath(), Vec3(4, 0, 5)));
  EXPECT_FALSE(fx->spawn("bad/name", "", urdfPath(), Vec3(4, 0, 5)));
  EXPECT_FALSE(fx->spawn("broken", "<robot name='x'><link name='a'>", "", Vec3(4, 0, 5), &message));
  EXPECT_FALSE(message.empty());
  EXPECT_FALSE(fx->spawn("nothing", "", "", Vec3(4, 0, 5)));
  EXPECT_FALSE(fx->sim.link("broken", fx->root).success);
  EXPECT_TRUE(fx->sim.step(1).success);
}

TEST(MultiRagdoll, B_TopicsOfBothRagdolls) {
  tf2_ros::Buffer buffer;
  tf2_ros::TransformListener listener(buffer);
  // Paused, the node publishes only when sim time advances: step until the new subscriptions
  // are connected and have their messages.
  auto all_there = [&] {
    std::lock_guard<std::mutex> lock(fx->mutex);
    return buffer.canTransform("world", "second/head", ros::Time(0)) &&
           buffer.canTransform("world", "head", ros::Time(0)) && !fx->first_js.name.empty() &&
           !fx->second_js.name.empty() && !fx->link_states.link.empty();
  };
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(20.0);
  while (ros::ok() && ros::WallTime::now() < deadline && !all_there()) {
    fx->sim.step(1);
    ros::WallDuration(0.1).sleep();
  }
  std::string err;
  EXPECT_TRUE(buffer.canTransform("world", "second/" + fx->root, ros::Time(0), ros::Duration(1.0), &err)) << err;
  EXPECT_TRUE(buffer.canTransform("world", "second/head", ros::Time(0), ros::Duration(1.0), &err)) << err;
  EXPECT_TRUE(buffer.canTransform("world", "head", ros::Time(0), ros::Duration(1.0), &err)) << err;
  if (buffer.canTransform("world", "second/head", ros::Time(0))) {
    const auto t = buffer.lookupTransform("world", "second/" + fx->root, ros::Time(0));
    EXPECT_NEAR(t.transform.translation.x, kSecondSpawn.x(), 1e-3);
  }

  ASSERT_TRUE(fx->waitFor([] { return !fx->first_js.name.empty() && !fx->second_js.name.empty(); }))
      << "no joint_states from both ragdolls (/joint_states and /second/joint_states)";
  {
    std::lock_guard<std::mutex> lock(fx->mutex);
    EXPECT_EQ(fx->first_js.name, fx->second_js.name);
    EXPECT_EQ(fx->first_js.header.stamp, fx->second_js.header.stamp);
  }
  ASSERT_TRUE(fx->waitFor([] { return !fx->link_states.link.empty(); })) << "no ~link_states";
  std::lock_guard<std::mutex> lock(fx->mutex);
  const ragdoll_sim::LinkStates& ls = fx->link_states;
  ASSERT_EQ(ls.ragdoll.size(), ls.link.size());
  ASSERT_EQ(ls.pose.size(), ls.link.size());
  ASSERT_EQ(ls.twist.size(), ls.link.size());
  size_t firsts = 0, seconds = 0;
  for (size_t i = 0; i < ls.link.size(); ++i) {
    if (ls.ragdoll[i] == "second") {
      ++seconds;
      if (ls.link[i] == fx->root) {
        EXPECT_NEAR(ls.pose[i].position.x, kSecondSpawn.x(), 1e-3);
      }
    } else {
      ++firsts;
    }
  }
  EXPECT_GT(firsts, 5u);
  EXPECT_EQ(firsts, seconds);
}

TEST(MultiRagdoll, C_CommandsAddressARagdoll) {
  ASSERT_TRUE(waitConnected(fx->impulse_pub));
  ragdoll_sim::ApplyImpulse cmd;
  cmd.ragdoll = "second";
  cmd.link = fx->root;
  cmd.frame = "link";
  cmd.impulse.y = 10.0;
  fx->impulse_pub.publish(cmd);  // paused: applies at once (zero stamp)
  int found = 0;
  Vec3 p2 = Vec3::Zero();
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(10.0);
  while (ros::WallTime::now() < deadline && p2.norm() < 1e-6) {
    p2 = momentum(fx->sim, "second", fx->links, &found);
    ros::WallDuration(0.05).sleep();
  }
  EXPECT_LT((p2 - Vec3(0, 10, 0)).norm(), 1e-6) << "momentum of 'second': " << str(p2);
  const Vec3 p1 = momentum(fx->sim, "", fx->links, &found);
  EXPECT_GT(found, 5);
  EXPECT_LT(p1.norm(), 1e-9) << "the first ragdoll moved: " << str(p1);

  cmd.ragdoll = "nobody";
  fx->impulse_pub.publish(cmd);
  EXPECT_TRUE(fx->warnings->wait({"unknown ragdoll", "nobody"}, 5.0));
}

TEST(MultiRagdoll, D_SetRagdollState) {
  ragdoll_sim::SetRagdollState s;
  s.request.ragdoll = "second";
  s.request.pose.position.x = 0.0;
  s.request.pose.position.y = 3.0;
  s.request.pose.position.z = 5.0;
  s.request.pose.orientation.z = std::sin(M_PI / 4);  // yaw 90 deg
  s.request.pose.orientation.w = std::cos(M_PI / 4);
  s.request.twist.linear.x = 1.0;
  const auto head_before = fx->sim.link("second", "head");
  const auto root_before = fx->sim.link("second", fx->root);
  ASSERT_TRUE(ros::service::call(kNode + "/set_ragdoll_state", s));
  ASSERT_TRUE(s.response.success) << s.response.message;

  const auto root = fx->sim.link("second", fx->root);
  const auto head = fx->sim.link("second", "head");
  EXPECT_LT((position(root) - Vec3(0, 3, 5)).norm(), 1e-9);
  EXPECT_LT((linear(root) - Vec3(1, 0, 0)).norm(), 1e-9);
  EXPECT_LT((linear(head) - Vec3(1, 0, 0)).norm(), 1e-9);
  // Rigid: the head keeps its distance from the root link.
  EXPECT_NEAR((position(head) - position(root)).norm(),
              (position(head_before) - position(root_before)).norm(), 1e-9);

  const double t0 = fx->sim.step(0).sim_time;
  const auto stepped = fx->sim.step(100);
  EXPECT_NEAR(stepped.sim_time - t0, 0.1, 1e-9);
  const auto moved = fx->sim.link("second", fx->root);
  EXPECT_NEAR(position(moved).x(), 0.1, 1e-3) << "1 m/s for 0.1 s";

  s.request.ragdoll = "nobody";
  ASSERT_TRUE(ros::service::call(kNode + "/set_ragdoll_state", s));
  EXPECT_FALSE(s.response.success);
}

TEST(MultiRagdoll, E_StepOnlyWhilePaused) {
  ASSERT_TRUE(fx->sim.call("unpause"));
  EXPECT_FALSE(fx->sim.step(10).success);
  ASSERT_TRUE(fx->sim.call("pause"));
  const double t0 = fx->sim.step(0).sim_time;
  const auto r = fx->sim.step(250);
  EXPECT_TRUE(r.success);
  EXPECT_NEAR(r.sim_time - t0, 0.25, 1e-9);
  EXPECT_FALSE(fx->sim.link("", "no_such_link").success);
}

TEST(MultiRagdoll, F_ClearForces) {
  ASSERT_TRUE(waitConnected(fx->force_pub));
  int found = 0;
  const Vec3 p0 = momentum(fx->sim, "", fx->links, &found);
  ragdoll_sim::ApplyForce f;
  f.link = "torso";
  f.frame = "link";
  f.force.x = 10.0;
  f.duration = -1.0;  // until cleared
  fx->force_pub.publish(f);
  ros::WallDuration(0.5).sleep();  // delivery; the node is paused, nothing happens meanwhile
  fx->sim.step(100);
  const Vec3 p1 = momentum(fx->sim, "", fx->links, &found);
  EXPECT_NEAR((p1 - p0).norm(), 1.0, 0.02) << "10 N for 0.1 s: " << str(p1 - p0);
  ASSERT_TRUE(fx->sim.call("clear_forces"));
  fx->sim.step(100);
  const Vec3 p2 = momentum(fx->sim, "", fx->links, &found);
  EXPECT_LT((p2 - p1).norm(), 1e-6) << "a cleared force still acts: " << str(p2 - p1);
}

TEST(MultiRagdoll, G_ResetPutsEveryRagdollBack) {
  ASSERT_TRUE(fx->sim.call("reset"));
  const auto first = fx->sim.link("", fx->root);
  const auto second = fx->sim.link("second", fx->root);
  EXPECT_LT((position(first) - kFirstSpawn).norm(), 1e-9);
  EXPECT_LT((position(second) - kSecondSpawn).norm(), 1e-9);
  EXPECT_LT(linear(second).norm(), 1e-12);
  fx->sim.step(100);
  int found = 0;
  EXPECT_LT(momentum(fx->sim, "", fx->links, &found).norm(), 1e-9) << "forces left after reset";
  EXPECT_LT(momentum(fx->sim, "second", fx->links, &found).norm(), 1e-9);
}

TEST(MultiRagdoll, H_Delete) {
  // The first ragdoll moving; deleting the second must carry its state over exactly.
  ragdoll_sim::SetRagdollState s;
  s.request.pose.position.z = 5.0;
  s.request.pose.orientation.w = 1.0;
  s.request.twist.linear.x = 0.5;
  s.request.twist.angular.z = 0.3;
  ASSERT_TRUE(ros::service::call(kNode + "/set_ragdoll_state", s));
  fx->sim.step(50);
  const auto before = fx->sim.link("", "head");

  ragdoll_sim::DeleteRagdoll d;
  d.request.name = "second";
  ASSERT_TRUE(ros::service::call(kNode + "/delete", d));
  EXPECT_TRUE(d.response.success) << d.response.message;
  const auto after = fx->sim.link("", "head");
  EXPECT_LT((position(after) - position(before)).norm(), 1e-12);
  EXPECT_LT((linear(after) - linear(before)).norm(), 1e-12);
  EXPECT_FALSE(fx->sim.link("second", fx->root).success);
  EXPECT_FALSE(ros::param::has("/second/robot_description"));
  ASSERT_TRUE(ros::service::call(kNode + "/delete", d));
  EXPECT_FALSE(d.response.success) << "deleted twice";

  // link_states without it; the first keeps moving.
  fx->sim.step(10);
  EXPECT_TRUE(fx->waitFor([] {
    const auto& ls = fx->link_states;
    return !ls.ragdoll.empty() &&
           std::find(ls.ragdoll.begin(), ls.ragdoll.end(), "second") == ls.ragdoll.end();
  })) << "'second' still in ~link_states";
  const auto later = fx->sim.link("", fx->root);
  fx->sim.step(100);
  EXPECT_NEAR(position(fx->sim.link("", fx->root)).x() - position(later).x(), 0.05, 1e-3);

  // A new ragdoll may take the name again.
  EXPECT_TRUE(fx->spawn("second", "", urdfPath(), kSecondSpawn));
}

TEST(MultiRagdoll, I_SpawnIntoTheGroundIsLifted) {
  // Its root 1 m below the ground: lifted to rest on the ground, and the reply says so.
  std::string message;
  ASSERT_TRUE(fx->spawn("sunk", "", urdfPath(), Vec3(8, 0, -1), &message)) << message;
  EXPECT_NE(message.find("lifted"), std::string::npos) << message;
  const auto root = fx->sim.link("sunk", fx->root);
  ASSERT_TRUE(root.success) << root.message;
  EXPECT_GT(position(root).z(), 0.3);
  ASSERT_EQ(fx->sim.step(3000).steps_done, 3000u);
  for (const LinkMass& l : fx->links) {
    const auto s = fx->sim.link("sunk", l.name);
    if (!s.success) continue;  // a massless link lumped into its parent
    EXPECT_GT(position(s).z(), -0.01) << l.name;
    EXPECT_LT(position(s).z(), 2.0) << l.name;
  }
}

int main(int argc, char** argv) {
  return runFixtureTests(argc, argv, "multi_ragdoll_test", 2, fx);
}
