// rostest: poking with rviz's "Publish Point" tool (/clicked_point). A: a point just in front of
// the torso gives the ragdoll ~poke/impulse (8 N*s) of momentum, from the point towards the
// torso's centre of mass, and the torso moves that way; B: points too far from
// every link, in another frame or not finite only warn and change nothing; C: 100 pokes in a
// second are all applied and counted in ~stats (`pokes`), with at most a few INFO lines.
#include <gtest/gtest.h>

#include <atomic>
#include <limits>
#include <memory>

#include <geometry_msgs/PointStamped.h>
#include <ragdoll_sim/NodeStats.h>

#include "node_log.hpp"
#include "sim_client.hpp"
#include "tf_snapshots.hpp"

using namespace ragdoll_test;

namespace {

const double kPoke = 8.0;  // ~poke/impulse in poke.test

struct Fixture {
  ros::NodeHandle nh;
  std::vector<LinkMass> links;
  std::unique_ptr<TfSnapshots> tf;
  ros::Publisher clicked_pub;
  std::unique_ptr<NodeWarnings> warnings;
  ros::Subscriber rosout_sub, stats_sub;
  std::atomic<int> poke_lines{0};          // the node's INFO lines about pokes
  std::atomic<uint64_t> pokes{0};          // ~stats pokes
  std::atomic<bool> have_stats{false};

  void init() {
    links = urdfLinks();
    tf = std::make_unique<TfSnapshots>(nh, linkNames(links));
    clicked_pub = nh.advertise<geometry_msgs::PointStamped>("/clicked_point", 1000);
    warnings = std::make_unique<NodeWarnings>(nh, "/ragdoll_sim");
    rosout_sub = nh.subscribe<rosgraph_msgs::Log>(
        "/rosout", 1000, [this](const rosgraph_msgs::Log::ConstPtr& m) {
          if (m->name == "/ragdoll_sim" && m->level == rosgraph_msgs::Log::INFO &&
              m->msg.rfind("poke:", 0) == 0)
            ++poke_lines;
        });
    stats_sub = nh.subscribe<ragdoll_sim::NodeStats>(
        "/ragdoll_sim/stats", 10, [this](const ragdoll_sim::NodeStats::ConstPtr& m) {
          pokes = m->pokes;
          have_stats = true;
        });
  }

  // Waits until ~stats reports at least n pokes; then the count.
  uint64_t waitPokes(uint64_t n, double timeout) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && (!have_stats || pokes < n) && ros::WallTime::now() < deadline)
      ros::WallDuration(0.02).sleep();
    return pokes;
  }

  const LinkMass* link(const std::string& name) const {
    for (const LinkMass& l : links)
      if (l.name == name) return &l;
    return nullptr;
  }

  // Momentum from two snapshots 0.25 s of sim time apart, the first received after `after`.
  bool measure(Vec3* p, const ros::WallTime& after, Snapshot* a_out = nullptr,
               Snapshot* b_out = nullptr) {
    Snapshot a = tf->waitFor(ros::Time(), after);
    if (!a.valid()) return false;
    Snapshot b = tf->waitFor(a.stamp + ros::Duration(0.25));
    if (!b.valid()) return false;
    *p = momentum(a, b, links);
    if (a_out) *a_out = a;
    if (b_out) *b_out = b;
    return true;
  }

  void click(const Vec3& p, const std::string& frame = "world") {
    geometry_msgs::PointStamped m;
    m.header.frame_id = frame;
    m.header.stamp = ros::Time::now();
    m.point.x = p.x();
    m.point.y = p.y();
    m.point.z = p.z();
    clicked_pub.publish(m);
  }
};

Fixture* fx = nullptr;

}  // namespace

TEST(Poke, A_ClickNearTheTorsoPushesItTowardsItsCentreOfMass) {
  ASSERT_GT(fx->links.size(), 1u) << "robot_description missing or not a URDF";
  const LinkMass* torso = fx->link("torso");
  ASSERT_NE(torso, nullptr) << "URDF has no link 'torso'";
  ASSERT_TRUE(waitConnected(fx->clicked_pub)) << "node does not subscribe /clicked_point";
  Vec3 before;
  Snapshot a;
  ASSERT_TRUE(fx->measure(&before, ros::WallTime::now(), &a));
  EXPECT_LT(before.norm(), 0.05) << "ragdoll not at rest before the poke: " << str(before);

  // 0.2 m in front of (world +x) the torso's centre of mass: 0.1 m outside its collision box,
  // well within ~poke/max_distance, and farther from the arms (at the sides) and the head.
  const Vec3 com = comOf(a, *torso);
  const Vec3 point = com + Vec3(0.2, 0.0, 0.0);
  const ros::WallTime sent = ros::WallTime::now();
  fx->click(point);

  Vec3 after;
  Snapshot s1, s2;
  ASSERT_TRUE(fx->measure(&after, sent + ros::WallDuration(0.3), &s1, &s2));
  const Vec3 expected = (com - point).normalized() * kPoke;  // (-8, 0, 0)
  EXPECT_LT((after - before - expected).norm(), 0.05 * kPoke)
      << "momentum change from a poke: " << str(after - before) << ", expected " << str(expected);
  // The torso moves along the push (-x); the joints share the push with the rest at once.
  const double dt = (s2.stamp - s1.stamp).toSec();
  const Vec3 v_torso = (comOf(s2, *torso) - comOf(s1, *torso)) / dt;
  EXPECT_LT(v_torso.x(), -0.05) << "torso velocity " << str(v_torso);
  RecordProperty("momentum_change", str(after - before));
  RecordProperty("torso_velocity", str(v_torso));
}

TEST(Poke, B_BadPointsOnlyWarn) {
  Vec3 before;
  Snapshot a;
  ASSERT_TRUE(fx->measure(&before, ros::WallTime::now(), &a));
  const LinkMass* torso = fx->link("torso");
  ASSERT_NE(torso, nullptr);
  const Vec3 com = comOf(a, *torso);

  fx->click(com + Vec3(3.0, 0.0, 0.0));  // 3 m away from everything
  EXPECT_TRUE(fx->warnings->wait({"max_distance", "poke dropped"}, 5.0))
      << "no WARN about a click far from every link";
  fx->click(com + Vec3(0.2, 0.0, 0.0), "some_camera");
  EXPECT_TRUE(fx->warnings->wait({"some_camera", "poke dropped"}, 5.0))
      << "no WARN about a click in another frame";
  fx->click(Vec3(std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0));
  EXPECT_TRUE(fx->warnings->wait({"not finite", "poke dropped"}, 5.0))
      << "no WARN about a NaN click";

  Vec3 after;
  ASSERT_TRUE(fx->measure(&after, ros::WallTime::now() + ros::WallDuration(0.3)));
  EXPECT_LT((after - before).norm(), 0.05) << "dropped pokes changed the momentum: before "
                                            << str(before) << ", after " << str(after);
}

TEST(Poke, C_HundredPokesInASecondAreCountedWithFewLogLines) {
  const LinkMass* torso = fx->link("torso");
  ASSERT_NE(torso, nullptr);
  fx->waitPokes(0, 10.0);
  ASSERT_TRUE(fx->have_stats) << "no ~stats";
  ros::WallDuration(0.3).sleep();
  const uint64_t before = fx->pokes;
  // Paused, the ragdoll stays where the clicks are (pokes act while paused too).
  const SimClient sim("/ragdoll_sim");
  ASSERT_TRUE(sim.call("pause"));
  const ragdoll_sim::GetLinkState::Response s = sim.link("", "torso");
  ASSERT_TRUE(s.success) << s.message;
  const Vec3 centre = ragdoll_test::com(s);
  const int lines_before = fx->poke_lines;
  // On a line through the torso's centre of mass, alternately in front and behind.
  for (int i = 0; i < 100; ++i) {
    fx->click(centre + Vec3(i % 2 == 0 ? 0.15 : -0.15, 0.0, 0.0));
    ros::WallDuration(0.01).sleep();
  }
  const uint64_t after = fx->waitPokes(before + 100, 10.0);
  ros::WallDuration(1.0).sleep();  // lines still on their way, pokes that should not be there
  EXPECT_TRUE(sim.call("unpause"));
  EXPECT_EQ(fx->pokes - before, 100u) << "~stats pokes went from " << before << " to " << after;
  const int lines = fx->poke_lines - lines_before;
  EXPECT_GE(lines, 1) << "no INFO line about the pokes";
  EXPECT_LE(lines, 3) << lines << " INFO lines for 100 pokes in a second";
  RecordProperty("poke_info_lines", lines);
}

int main(int argc, char** argv) {
  return runFixtureTests(argc, argv, "poke_test", 2, fx);
}
