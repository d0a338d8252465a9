// rostest, end to end: what a person sees. Starts Xvfb on a free display and rviz on it with
// the shipped config (argv[1]) and LIBGL_ALWAYS_SOFTWARE=1, waits for the ragdoll to land and
// for rviz to draw it, then checks screenshots (imagemagick `import`): the pixels in the
// ragdoll's marker colour cover a plausible part of the screen (0.2 % .. 60 %), stay put while
// nothing moves, and move after a poke on /clicked_point. The screenshots are kept next to the
// JUnit report (rviz_view_before_poke.png, rviz_view_after_poke.png, rviz_view_rviz.log).
#include <gtest/gtest.h>

#include <memory>
#include <string>

#include <geometry_msgs/PointStamped.h>
#include <urdf_parser/urdf_parser.h>

#include "marker_log.hpp"
#include "node_log.hpp"
#include "screen.hpp"
#include "tf_snapshots.hpp"

using namespace ragdoll_test;

namespace {

std::string g_config;       // config/ragdoll.rviz
std::string g_results_dir;  // where the JUnit report goes (--gtest_output=xml:DIR/file.xml)

struct Fixture {
  ros::NodeHandle nh;
  std::vector<LinkMass> links;
  std::unique_ptr<TfSnapshots> tf;
  std::unique_ptr<MarkerLog> markers;
  ros::Publisher clicked_pub;
  std::unique_ptr<Xvfb> xvfb;
  std::unique_ptr<Child> rviz;

  void init() {
    links = urdfLinks();
    tf = std::make_unique<TfSnapshots>(nh, linkNames(links));
    markers = std::make_unique<MarkerLog>(nh, "/ragdoll_sim/markers");
    clicked_pub = nh.advertise<geometry_msgs::PointStamped>("/clicked_point", 10);
  }

  // Waits until no link moves more than 5 mm in 0.5 s of sim time; the last snapshot.
  Snapshot atRest(double timeout) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < deadline) {
      Snapshot a = tf->next();
      if (!a.valid()) continue;
      Snapshot b = tf->waitFor(a.stamp + ros::Duration(0.5));
      if (!b.valid()) continue;
      double moved = 0.0;
      for (const LinkMass& l : links)
        moved = std::max(moved, (b.position(l.name) - a.position(l.name)).norm());
      if (moved < 0.005) return b;
    }
    return Snapshot();
  }
};

Fixture* fx = nullptr;

std::string artifact(const std::string& name) { return g_results_dir + "/rviz_view_" + name; }

}  // namespace

TEST(RvizView, RagdollVisibleAndMovesAfterAPoke) {
  ASSERT_GT(fx->links.size(), 1u) << "robot_description missing or not a URDF";
  ASSERT_FALSE(g_config.empty()) << "usage: rviz_view <config.rviz>";
  std::string xml, robot;
  ros::param::get("/robot_description", xml);
  if (urdf::ModelInterfaceSharedPtr m = urdf::parseURDF(xml)) robot = m->getName();

  fx->xvfb = std::make_unique<Xvfb>(artifact("xvfb.log"));
  const std::string display = fx->xvfb->display();
  ASSERT_FALSE(display.empty()) << "Xvfb did not start (see " << artifact("xvfb.log") << ")";
  fx->rviz = std::make_unique<Child>(
      std::vector<std::string>{"rviz", "-d", g_config},
      std::vector<std::string>{"DISPLAY=" + display, "LIBGL_ALWAYS_SOFTWARE=1"},
      artifact("rviz.log"));

  // The ragdoll's colour, from the markers rviz draws (namespace = ragdoll name).
  MarkerLog::Array a;
  ASSERT_TRUE(fx->markers->waitFor([&](const MarkerLog::Array& m) {
    return !MarkerLog::inNs(m, robot).empty(); }, &a, 0, 60.0))
      << "no markers of the ragdoll '" << robot << "'";
  const std_msgs::ColorRGBA colour = MarkerLog::inNs(a, robot)[0]->color;

  // Landed and still.
  Snapshot rest = fx->atRest(120.0);
  ASSERT_TRUE(rest.valid()) << "the ragdoll did not come to rest";

  // rviz up and drawing: screenshots until the ragdoll's colour shows (software GL on a busy
  // machine can take a while; no wall time is asserted).
  Image before;
  std::vector<bool> mask_before;
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(180.0);
  while (ros::ok() && ros::WallTime::now() < deadline) {
    ASSERT_TRUE(fx->rviz->running()) << "rviz exited (see " << artifact("rviz.log") << ")";
    ros::WallDuration(2.0).sleep();
    before = screenshot(display, artifact("before_poke.png"));
    if (!before.valid()) continue;
    mask_before = hueMask(before, colour.r, colour.g, colour.b);
    if (fraction(mask_before) >= 0.002) break;
  }
  ASSERT_TRUE(before.valid()) << "no screenshot of " << display;
  const double share = fraction(mask_before);
  EXPECT_GE(share, 0.002) << "the ragdoll's colour covers " << 100 * share
                          << " % of the screen (see " << artifact("before_poke.png") << ")";
  EXPECT_LE(share, 0.6) << "the ragdoll's colour covers " << 100 * share << " % of the screen";

  // Nothing moves: the picture stays (the baseline for "moved").
  ros::WallDuration(1.0).sleep();
  const Image still = screenshot(display, artifact("still.png"));
  ASSERT_TRUE(still.valid());
  const double still_change = changed(mask_before, hueMask(still, colour.r, colour.g, colour.b));

  // Poke the torso from the side (+y, about across the view): it lands pushed along -y. The
  // click is inside the torso's box (its half extents are 0.1 m and more), so that the poke
  // lands on the torso whatever lies beside it: clicked 0.25 m out, it went to an arm lying
  // along that side, and the torso moved 5.0 cm (poked itself, 14 to 29 cm whichever side).
  const LinkMass* torso = nullptr;
  for (const LinkMass& l : fx->links)
    if (l.name == "torso") torso = &l;
  ASSERT_NE(torso, nullptr);
  ASSERT_TRUE(waitConnected(fx->clicked_pub));
  geometry_msgs::PointStamped click;
  click.header.frame_id = "world";
  const Vec3 p = comOf(rest, *torso) + Vec3(0.0, 0.05, 0.0);
  click.point.x = p.x();
  click.point.y = p.y();
  click.point.z = p.z();
  fx->clicked_pub.publish(click);
  Snapshot moved = fx->tf->waitFor(rest.stamp, ros::WallTime::now() + ros::WallDuration(0.5));
  ASSERT_TRUE(moved.valid());
  Snapshot rest2 = fx->atRest(120.0);
  ASSERT_TRUE(rest2.valid()) << "the ragdoll did not come to rest after the poke";
  const double shift = (comOf(rest2, *torso) - comOf(rest, *torso)).norm();
  ros::WallDuration(1.5).sleep();  // rviz draws the last pose
  const Image after = screenshot(display, artifact("after_poke.png"));
  ASSERT_TRUE(after.valid());
  const std::vector<bool> mask_after = hueMask(after, colour.r, colour.g, colour.b);
  const double change = changed(mask_before, mask_after);
  EXPECT_GT(shift, 0.05) << "the poke did not move the torso";
  EXPECT_GT(change, 0.15) << "the ragdoll's pixels barely changed after the poke (torso moved "
                          << shift << " m)";
  EXPECT_GT(change, still_change + 0.1) << "as much change without a poke: " << still_change;
  EXPECT_GE(fraction(mask_after), 0.002);
  RecordProperty("colour_share_before", std::to_string(share));
  RecordProperty("colour_share_after", std::to_string(fraction(mask_after)));
  RecordProperty("changed_still", std::to_string(still_change));
  RecordProperty("changed_after_poke", std::to_string(change));
  RecordProperty("torso_shift_m", std::to_string(shift));
  RecordProperty("screenshots", artifact("before_poke.png") + " " + artifact("after_poke.png"));
  std::printf("rviz_view: colour share %.4f before, %.4f after; changed %.3f (still %.3f); torso "
              "moved %.3f m; screenshots %s, %s\n",
              share, fraction(mask_after), change, still_change, shift,
              artifact("before_poke.png").c_str(), artifact("after_poke.png").c_str());
}

int main(int argc, char** argv) {
  // rostest passes --gtest_output=xml:DIR/rosunit-rviz_view.xml: keep the screenshots in DIR.
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const std::string key = "--gtest_output=xml:";
    if (a.rfind(key, 0) == 0) {
      const std::string path = a.substr(key.size());
      const size_t slash = path.rfind('/');
      g_results_dir = slash == std::string::npos ? "." : path.substr(0, slash);
    } else if (a.size() > 5 && a.compare(a.size() - 5, 5, ".rviz") == 0) {
      g_config = a;
    }
  }
  if (g_results_dir.empty()) {
    const char* home = std::getenv("ROS_HOME");
    g_results_dir = home ? home : std::string(std::getenv("HOME") ? std::getenv("HOME") : ".") + "/.ros";
  }
  std::unique_ptr<Fixture> fixture;
  return runRosTests(
      argc, argv, "rviz_view_test", 2,
      [&] {
        fixture = std::make_unique<Fixture>();
        fx = fixture.get();
        fx->init();
      },
      [&] {
        if (fx) {
          fx->rviz.reset();
          fx->xvfb.reset();
        }
        fx = nullptr;
        fixture.reset();
      });
}
