// rostest: dynamic_reconfigure of the physics (cfg/Physics.cfg) through ~set_parameters, on a
// paused node without gravity that the tests step: gravity, time step, solver settings (the
// World is rebuilt with every body's state carried over), friction, real-time factor.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <vector>

#include <ragdoll_sim/SetRagdollState.h>

#include "node_log.hpp"
#include "sim_client.hpp"

using namespace ragdoll_test;

namespace {

const std::string kNode = "/ragdoll_sim";
SimClient sim(kNode);

// Sets some parameters; returns the node's answer (the whole configuration) in *now.
bool reconfigure(const std::map<std::string, double>& doubles, const std::map<std::string, int>& ints = {},
                 std::map<std::string, double>* now = nullptr) {
  return sim.reconfigure({doubles, ints, {}}, now);
}

bool setState(const Vec3& p, const Eigen::Quaterniond& q, const Vec3& v) {
  ragdoll_sim::SetRagdollState s;
  s.request.pose.position.x = p.x();
  s.request.pose.position.y = p.y();
  s.request.pose.position.z = p.z();
  s.request.pose.orientation.x = q.x();
  s.request.pose.orientation.y = q.y();
  s.request.pose.orientation.z = q.z();
  s.request.pose.orientation.w = q.w();
  s.request.twist.linear.x = v.x();
  s.request.twist.linear.y = v.y();
  s.request.twist.linear.z = v.z();
  return ros::service::call(kNode + "/set_ragdoll_state", s) && s.response.success;
}

}  // namespace

TEST(Reconfigure, A_StartsFromTheNodesParameters) {
  ASSERT_TRUE(sim.waitUp()) << "node did not come up";
  ASSERT_TRUE(ros::service::waitForService(kNode + "/set_parameters", ros::Duration(10.0)));
  std::map<std::string, double> now;
  ASSERT_TRUE(reconfigure({}, {}, &now));
  EXPECT_EQ(now["gravity_z"], 0.0) << "the launch file's gravity, not the .cfg default";
  EXPECT_DOUBLE_EQ(now["time_step"], 0.001);
  EXPECT_EQ(now["substeps"], 3);  // the node's default
  EXPECT_DOUBLE_EQ(now["real_time_factor"], 1.0);
  EXPECT_EQ(now["sleep_enabled"], 1.0);  // ~sleep/enabled (the sleep rostest changes it)
}

TEST(Reconfigure, B_Gravity) {
  ASSERT_TRUE(reconfigure({{"gravity_z", -9.81}}));
  sim.step(100);
  for (const char* link : {"pelvis", "head", "hand_l"}) {
    const auto s = sim.link("", link);
    ASSERT_TRUE(s.success) << s.message;
    EXPECT_NEAR(linear(s).z(), -0.981, 1e-6) << link << ": free fall for 0.1 s";
  }
  ASSERT_TRUE(reconfigure({{"gravity_z", 0.0}}));
  const Vec3 v0 = linear(sim.link("", "pelvis"));
  sim.step(100);
  EXPECT_LT((linear(sim.link("", "pelvis")) - v0).norm(), 1e-6) << "gravity 0 again";
}

TEST(Reconfigure, C_TimeStep) {
  ASSERT_TRUE(reconfigure({{"time_step", 0.002}}));
  const double t0 = sim.step(0).sim_time;
  EXPECT_NEAR(sim.step(10).sim_time - t0, 0.02, 1e-12);
  ASSERT_TRUE(reconfigure({{"time_step", 0.001}}));
  const double t1 = sim.step(0).sim_time;
  EXPECT_NEAR(sim.step(10).sim_time - t1, 0.01, 1e-12);
}

TEST(Reconfigure, D_SolverSettingsKeepTheState) {
  ASSERT_TRUE(setState(Vec3(0, 0, 5), Eigen::Quaterniond::Identity(), Vec3(0.5, 0, 0)));
  sim.step(20);
  const auto before = sim.link("", "head");
  std::map<std::string, double> now;
  ASSERT_TRUE(reconfigure({}, {{"substeps", 8}, {"position_iterations", 4}}, &now));
  EXPECT_EQ(now["substeps"], 8);
  EXPECT_EQ(now["position_iterations"], 4);
  const auto after = sim.link("", "head");
  EXPECT_LT((position(after) - position(before)).norm(), 1e-12);
  EXPECT_LT((linear(after) - linear(before)).norm(), 1e-12);
  sim.step(100);
  EXPECT_NEAR(position(sim.link("", "head")).x() - position(after).x(), 0.05, 1e-3);
}

TEST(Reconfigure, E_FrictionSlowsASlide) {
  // Lying on the ground (gravity on), pushed along x at 2 m/s for 0.5 s: with the default
  // friction (0.8 / 0.6) it stops within ~0.35 m; without friction it slides ~1 m.
  ASSERT_TRUE(reconfigure({{"gravity_z", -9.81}}));
  const Eigen::Quaterniond lying(Eigen::AngleAxisd(M_PI / 2, Vec3::UnitY()));
  auto slide = [&]() {
    EXPECT_TRUE(setState(Vec3(0, 0, 0.3), lying, Vec3::Zero()));
    sim.step(1500);  // settle
    const auto settled = sim.link("", "pelvis");
    EXPECT_TRUE(setState(position(settled), orientation(settled), Vec3(2, 0, 0)));
    sim.step(500);
    return position(sim.link("", "pelvis")).x() - position(settled).x();
  };
  const double with_friction = slide();
  ASSERT_TRUE(reconfigure({{"static_friction", 0.0}, {"kinetic_friction", 0.0}}));
  const double without = slide();
  EXPECT_LT(with_friction, 0.5);
  EXPECT_GT(without, with_friction + 0.3);
  std::printf("[ friction ] 2 m/s slide for 0.5 s: %.3f m with friction 0.8/0.6, %.3f m without\n",
              with_friction, without);
  ASSERT_TRUE(reconfigure({{"static_friction", 0.8}, {"kinetic_friction", 0.6}, {"gravity_z", 0.0}}));
}

TEST(Reconfigure, F_SlowMotion) {
  // At 0.2x real time the sim can not run ahead of 0.2 x the wall clock between two readings
  // (plus the 0.1 s of backlog ~max_catchup lets it make up); a loaded machine only makes it
  // less. Without pacing it would run at several times real time (see the second half).
  ASSERT_TRUE(reconfigure({{"real_time_factor", 0.2}}));
  ASSERT_TRUE(sim.call("unpause"));
  const ros::WallTime w0 = ros::WallTime::now();
  const double t0 = sim.step(0).sim_time;
  ros::WallDuration(2.0).sleep();
  const double t1 = sim.step(0).sim_time;
  const double wall = (ros::WallTime::now() - w0).toSec();
  ASSERT_TRUE(reconfigure({{"real_time_factor", 0.0}}));  // as fast as possible
  ros::WallDuration(1.0).sleep();
  const double t2 = sim.step(0).sim_time;
  ASSERT_TRUE(sim.call("pause"));
  EXPECT_GT(t1 - t0, 0.0);
  EXPECT_LE(t1 - t0, 0.2 * wall + 0.1 + 0.001) << "more than 0.2x real time over " << wall << " s";
  EXPECT_GT(t2 - t1, 0.0);
  std::printf("[ pacing   ] 0.2x: %.3f s of sim time in 2 s of wall clock; as fast as possible: "
              "%.3f s in ~1 s\n", t1 - t0, t2 - t1);
}

TEST(Reconfigure, G_OutOfRangeRefusedWithTheReason) {
  // The values in force before; every refused request leaves them all as they are.
  std::map<std::string, double> before, now;
  ASSERT_TRUE(reconfigure({}, {}, &before));
  ros::NodeHandle nh;
  NodeWarnings warnings(nh, kNode);
  ros::WallDuration(0.5).sleep();  // /rosout connected
  struct Case {
    std::string field;
    double value;
    std::string range;
  };
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<Case> cases = {
      {"real_time_factor", 1e-300, "0 (as fast as possible) or [0.01, 1000]"},
      {"real_time_factor", 1e-12, ""},
      {"real_time_factor", 0.001, ""},
      {"real_time_factor", -1.0, ""},
      {"real_time_factor", 5000.0, ""},
      {"substeps", 1000, "[1, 64]"},
      {"time_step", 1e-9, "[1e-05, 0.05]"},
      {"gravity_z", 1e9, "[-100, 100]"},
      {"gravity_x", inf, "[-100, 100]"},
      {"gravity_y", std::nan(""), "[-100, 100]"},
      {"restitution", 1e9, "[0, 1]"},
      {"static_friction", -1.0, "[0, 10]"},
  };
  for (const Case& c : cases) {
    // With a valid change in the same request: the whole request is refused.
    const bool is_int = c.field == "substeps";
    std::map<std::string, double> d = {{"kinetic_friction", 0.3}};
    std::map<std::string, int> i;
    if (is_int) i[c.field] = static_cast<int>(c.value);
    else d[c.field] = c.value;
    ASSERT_TRUE(reconfigure(d, i, &now)) << c.field << " " << c.value;
    EXPECT_EQ(now, before) << c.field << " = " << c.value
                           << ": the answer holds the values in force";
    now.clear();
    ASSERT_TRUE(reconfigure({}, {}, &now));
    EXPECT_EQ(now, before) << c.field << " = " << c.value << ": nothing changed";
    if (!c.range.empty())  // the first refusal per field (the WARN is throttled per field)
      EXPECT_TRUE(warnings.wait({"reconfigure refused", c.field + " = ", c.range}, 5.0))
          << c.field << " = " << c.value;
  }
  EXPECT_TRUE(warnings.wait({"real_time_factor = 1e-300", "outside"}, 5.0));
  // The ends of the ranges are taken.
  ASSERT_TRUE(reconfigure({{"real_time_factor", 0.01}}, {{"substeps", 64}}, &now));
  EXPECT_DOUBLE_EQ(now["real_time_factor"], 0.01);
  EXPECT_EQ(now["substeps"], 64);
  ASSERT_TRUE(reconfigure({{"real_time_factor", before["real_time_factor"]}},
                          {{"substeps", static_cast<int>(before["substeps"])}}, &now));
  EXPECT_EQ(now, before);
}

int main(int argc, char** argv) {
  return runRosTests(argc, argv, "reconfigure_test", 2, [] {}, [] {});
}
