// rostest: rosbag record / replay gives the same poses at the same sim times. Commands are
// stamped with the sim time at which they take effect, so the node applies each at the start
// of that step whenever the message arrives (docs/interface.md "Deterministic replay").
// Run 1: commands to /rec/ragdoll_sim, recorded by `rosbag record`; both nodes are paused and
// stepped by the test.
// Run 2: `rosbag play` of that bag into the fresh /play/ragdoll_sim. Every link pose of both is
// compared at the same sim times.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <map>
#include <memory>

#include <ragdoll_sim/ApplyForce.h>
#include <ragdoll_sim/ApplyImpulse.h>
#include <sensor_msgs/JointState.h>

#include "node_log.hpp"
#include "sim_client.hpp"

using namespace ragdoll_test;

namespace {

const std::vector<std::string> kTopics = {"apply_impulse", "apply_force", "target_pose"};
const std::vector<double> kSampleTimes = {0.1, 0.3, 0.6, 1.0, 1.5};  // s of sim time

// Every simulated link's pose at each sample time.
using Trajectory = std::vector<std::map<std::string, ragdoll_sim::GetLinkState::Response>>;

pid_t start(const std::vector<std::string>& args) {
  const pid_t pid = fork();
  if (pid == 0) {
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execvp(argv[0], argv.data());
    _exit(127);
  }
  return pid;
}

int finish(pid_t pid) {
  int status = 0;
  if (waitpid(pid, &status, 0) != pid) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

bool waitSubscribers(const ros::Publisher& pub, uint32_t n, double timeout = 30.0) {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
  while (ros::ok() && pub.getNumSubscribers() < n && ros::WallTime::now() < deadline)
    ros::WallDuration(0.05).sleep();
  return pub.getNumSubscribers() >= n;
}

// Steps `sim` to each sample time and reads every link.
Trajectory sample(const SimClient& sim, const std::vector<LinkMass>& links) {
  Trajectory out;
  for (double t : kSampleTimes) {
    const double now = sim.step(0).sim_time;
    const auto r = sim.step(static_cast<uint32_t>(std::llround((t - now) * 1000.0)));
    EXPECT_TRUE(r.success) << r.message;
    EXPECT_NEAR(r.sim_time, t, 1e-9);
    std::map<std::string, ragdoll_sim::GetLinkState::Response> poses;
    for (const LinkMass& l : links) {
      const auto s = sim.link("", l.name);
      if (s.success) poses[l.name] = s;
    }
    out.push_back(poses);
  }
  return out;
}

}  // namespace

TEST(Replay, RecordedCommandsReplayToTheSamePoses) {
  ros::NodeHandle nh;
  SimClient rec("/rec/ragdoll_sim"), play("/play/ragdoll_sim");
  ASSERT_TRUE(rec.waitUp()) << "/rec/ragdoll_sim did not come up";
  ASSERT_TRUE(play.waitUp()) << "/play/ragdoll_sim did not come up";
  std::string xml;
  ASSERT_TRUE(ros::param::get("/rec/robot_description", xml));
  ros::param::set("/robot_description", xml);  // for urdfLinks()
  const std::vector<LinkMass> links = urdfLinks();
  ASSERT_GT(links.size(), 1u);
  ASSERT_EQ(rec.step(0).sim_time, 0.0);
  ASSERT_EQ(play.step(0).sim_time, 0.0);

  // --- run 1: record ---
  const std::string bag = "/tmp/ragdoll_sim_replay_" + std::to_string(getpid()) + ".bag";
  std::vector<std::string> record = {"rosbag", "record", "-O", bag, "__name:=replay_recorder"};
  for (const std::string& t : kTopics) record.push_back("/rec/ragdoll_sim/" + t);
  const pid_t recorder = start(record);
  ASSERT_GT(recorder, 0);
  ros::Publisher impulse = nh.advertise<ragdoll_sim::ApplyImpulse>("/rec/ragdoll_sim/apply_impulse", 10);
  ros::Publisher force = nh.advertise<ragdoll_sim::ApplyForce>("/rec/ragdoll_sim/apply_force", 10);
  ros::Publisher target = nh.advertise<sensor_msgs::JointState>("/rec/ragdoll_sim/target_pose", 10);
  for (const ros::Publisher* p : {&impulse, &force, &target})
    ASSERT_TRUE(waitSubscribers(*p, 2)) << p->getTopic() << ": node and recorder not both subscribed";

  ragdoll_sim::ApplyImpulse i;
  i.header.stamp = ros::Time(0.2);
  i.link = "torso";
  i.frame = "link";
  i.impulse.x = 30.0;
  ragdoll_sim::ApplyForce f;
  f.header.stamp = ros::Time(0.35);
  f.link = "head";
  f.frame = "link";
  f.force.y = 200.0;
  f.duration = 0.3;
  sensor_msgs::JointState j;
  j.header.stamp = ros::Time(0.5);
  j.name = {"elbow_l", "shoulder_l_y"};
  j.position = {1.0, -0.5};
  impulse.publish(i);
  force.publish(f);
  target.publish(j);
  ASSERT_TRUE(rec.waitPending(3)) << "the commands did not reach /rec/ragdoll_sim";
  const Trajectory recorded = sample(rec, links);
  kill(recorder, SIGINT);
  finish(recorder);
  // /usr/bin/rosbag is a Python wrapper: its `record` child closes the bag (renames
  // <bag>.active to <bag>) after the wrapper has exited, so wait for the file (bounded).
  for (int i = 0; i < 600 && access(bag.c_str(), R_OK) != 0; ++i) ros::WallDuration(0.05).sleep();
  ASSERT_EQ(access(bag.c_str(), R_OK), 0) << "rosbag record wrote no " << bag;

  // The commands acted: the torso moved on in x after the impulse at 0.2 s.
  ASSERT_EQ(recorded.size(), kSampleTimes.size());
  ASSERT_TRUE(recorded[0].count("torso") && recorded[1].count("torso"));
  EXPECT_GT(position(recorded[1].at("torso")).x() - position(recorded[0].at("torso")).x(), 0.02);

  // --- run 2: replay into the fresh node ---
  std::vector<std::string> replay = {"rosbag", "play", "-i", "--wait-for-subscribers", bag,
                                     "__name:=replay_player"};
  for (const std::string& t : kTopics)
    replay.push_back("/rec/ragdoll_sim/" + t + ":=/play/ragdoll_sim/" + t);
  EXPECT_EQ(finish(start(replay)), 0) << "rosbag play failed";
  ASSERT_TRUE(play.waitPending(3)) << "the replayed commands did not reach /play/ragdoll_sim";
  const Trajectory replayed = sample(play, links);
  std::remove(bag.c_str());

  ASSERT_EQ(replayed.size(), recorded.size());
  double max_diff = 0.0;
  bool identical = true;
  for (size_t k = 0; k < recorded.size(); ++k) {
    ASSERT_EQ(replayed[k].size(), recorded[k].size());
    ASSERT_GT(recorded[k].size(), 5u);
    for (const auto& [name, a] : recorded[k]) {
      const auto& b = replayed[k].at(name);
      const double d = std::max((position(a) - position(b)).norm(),
                                (orientation(a).coeffs() - orientation(b).coeffs()).norm());
      max_diff = std::max(max_diff, d);
      identical = identical && a.pose == b.pose && a.twist == b.twist;
      EXPECT_LE(d, 1e-9) << name << " at sim time " << kSampleTimes[k] << " s";
    }
  }
  std::printf("[ replay   ] %zu links x %zu sample times: max pose difference %.3g (%s)\n",
              recorded[0].size(), kSampleTimes.size(), max_diff,
              identical ? "bit-identical poses and twists" : "not bit-identical");
  RecordProperty("max_pose_difference", std::to_string(max_diff));
  RecordProperty("bit_identical", identical ? "true" : "false");
}

int main(int argc, char** argv) {
  return runRosTests(argc, argv, "replay_test", 2, [] {}, [] {});
}
