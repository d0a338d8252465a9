// rostest: a long ~step (many ragdolls, many steps) runs in the node's loop, not in the service
// callback: ~get_link_state and ~pause answer within 100 ms meanwhile, and ~pause ends the
// step early with a reply that says how many steps ran.
#include <gtest/gtest.h>

#include <algorithm>
#include <future>
#include <string>
#include <vector>

#include <ragdoll_sim/SpawnRagdoll.h>

#include "node_log.hpp"
#include "sim_client.hpp"

using namespace ragdoll_test;

namespace {

const std::string kNode = "/ragdoll_sim";
constexpr int kRagdolls = 40;
constexpr uint32_t kSteps = 100000;  // ~max_steps_per_call: minutes of work at this size
constexpr double kAnswerWithin = 0.1;  // s

SimClient sim(kNode);

double seconds(ros::WallTime since) { return (ros::WallTime::now() - since).toSec(); }

}  // namespace

TEST(StepBusy, OtherServicesAnswerDuringALongStep) {
  ASSERT_TRUE(sim.waitUp()) << "node did not come up";
  ros::NodeHandle nh;
  std::string urdf;
  ASSERT_TRUE(ros::param::get("~urdf_path", urdf));
  for (int i = 0; i < kRagdolls; ++i) {
    ragdoll_sim::SpawnRagdoll s;
    s.request.name = "r" + std::to_string(i);
    s.request.urdf_file = urdf;
    s.request.pose.position.x = 2.0 * (i % 8) + 2.0;
    s.request.pose.position.y = 2.0 * (i / 8);
    s.request.pose.position.z = 3.0;
    ASSERT_TRUE(ros::service::call(kNode + "/spawn", s) && s.response.success)
        << s.response.message;
  }
  // Persistent connections: the times below are the node's, not the connection set-up's.
  ros::ServiceClient get_link =
      nh.serviceClient<ragdoll_sim::GetLinkState>(kNode + "/get_link_state", true);
  ros::ServiceClient pause = nh.serviceClient<std_srvs::Empty>(kNode + "/pause", true);
  ragdoll_sim::GetLinkState g;
  g.request.ragdoll = "r0";
  g.request.link = "pelvis";
  ASSERT_TRUE(get_link.call(g) && g.response.success) << g.response.message;
  const ros::WallTime t0 = ros::WallTime::now();
  ASSERT_TRUE(sim.step(10).success);
  const double per_step = seconds(t0) / 10;

  const ros::WallTime started = ros::WallTime::now();
  std::future<ragdoll_sim::Step::Response> step =
      std::async(std::launch::async, [] { return sim.step(kSteps); });
  ros::WallDuration(0.5).sleep();  // the step is under way
  std::vector<double> answers;
  double first_time = -1.0, last_time = -1.0;
  for (int i = 0; i < 10; ++i) {
    const ros::WallTime t = ros::WallTime::now();
    ASSERT_TRUE(get_link.call(g) && g.response.success) << g.response.message;
    answers.push_back(seconds(t));
    if (first_time < 0) first_time = g.response.sim_time;
    last_time = g.response.sim_time;
    ros::WallDuration(0.05).sleep();
  }
  EXPECT_EQ(step.wait_for(std::chrono::seconds(0)), std::future_status::timeout)
      << "the step ended before ~pause";
  EXPECT_GT(last_time, first_time) << "sim time advances while ~get_link_state answers";
  std::sort(answers.begin(), answers.end());
  EXPECT_LT(answers.back(), kAnswerWithin) << "slowest ~get_link_state during the step";
  std_srvs::Empty e;
  const ros::WallTime p = ros::WallTime::now();
  ASSERT_TRUE(pause.call(e));
  const double pause_answer = seconds(p);
  EXPECT_LT(pause_answer, kAnswerWithin);
  ASSERT_EQ(step.wait_for(std::chrono::seconds(5)), std::future_status::ready)
      << "~pause ends the step";
  const ragdoll_sim::Step::Response r = step.get();
  const double ran = seconds(started);
  EXPECT_FALSE(r.success);
  EXPECT_NE(r.message.find("~pause"), std::string::npos) << r.message;
  EXPECT_GT(r.steps_done, 0u);
  EXPECT_LT(r.steps_done, kSteps);
  EXPECT_NE(r.message.find(std::to_string(r.steps_done) + " of " + std::to_string(kSteps)),
            std::string::npos) << r.message;
  std::printf("[ step     ] %d ragdolls, %.2f ms per step: ~get_link_state answered in %.1f ms "
              "(median) / %.1f ms (slowest), ~pause in %.1f ms; ~pause ended ~step after %u of "
              "%u steps, %.2f s\n", kRagdolls + 1, per_step * 1e3,
              answers[answers.size() / 2] * 1e3, answers.back() * 1e3, pause_answer * 1e3, r.steps_done, kSteps, ran);
  // A short step afterwards still runs to the end.
  const ragdoll_sim::Step::Response after = sim.step(3);
  EXPECT_TRUE(after.success) << after.message;
  EXPECT_EQ(after.steps_done, 3u);
}

TEST(StepBusy, RefusedWhileRunning) {
  ASSERT_TRUE(sim.call("unpause"));
  const ragdoll_sim::Step::Response r = sim.step(5);
  EXPECT_FALSE(r.success);
  EXPECT_NE(r.message.find("call ~pause first"), std::string::npos) << r.message;
  EXPECT_EQ(r.steps_done, 0u);
  ASSERT_TRUE(sim.call("pause"));
}

int main(int argc, char** argv) {
  return runRosTests(argc, argv, "step_busy_test", 2, [] {}, [] {});
}
