// rostest: dragging a link with the interactive marker. The test plays rviz: it reads the drag
// handle from <node>/drag/update_full and sends InteractiveMarkerFeedback to <node>/drag/feedback.
// A: the handle floats ~drag/handle_height above the torso's centre of mass; B: dragged 0.5 m
// sideways, the torso follows it (its centre of mass comes within 0.1 m of the target);
// C: released, the pull stops (no gravity: the momentum stays constant) and the handle follows
// the torso again; D: feedback in another frame or with NaN only warns; E: the handle's
// context menu moves it to another link.
#include <gtest/gtest.h>

#include <atomic>
#include <limits>
#include <map>
#include <memory>
#include <mutex>

#include <ragdoll_sim/ApplyImpulse.h>
#include <ragdoll_sim/NodeStats.h>
#include <visualization_msgs/InteractiveMarkerFeedback.h>
#include <visualization_msgs/InteractiveMarkerInit.h>
#include <visualization_msgs/InteractiveMarkerUpdate.h>

#include "marker_log.hpp"
#include "node_log.hpp"
#include "tf_snapshots.hpp"

using namespace ragdoll_test;
using visualization_msgs::InteractiveMarkerFeedback;

namespace {

const double kHandleHeight = 0.4;  // ~drag/handle_height in drag.test

struct Fixture {
  ros::NodeHandle nh;
  std::vector<LinkMass> links;
  const LinkMass* torso = nullptr;
  std::unique_ptr<TfSnapshots> tf;
  ros::Publisher feedback_pub, impulse_pub;
  ros::Subscriber init_sub, update_sub, stats_sub;
  std::atomic<int64_t> drags{-1};  // ~stats drags; -1 until the first message
  std::unique_ptr<NodeWarnings> warnings;
  std::unique_ptr<MarkerLog> markers;
  std::mutex mutex;
  std::map<std::string, uint32_t> menu;  // context menu: title -> entry id
  std::string marker;                    // the handle's name (the ragdoll's)
  Vec3 handle = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  ros::WallTime handle_received;

  void init() {
    links = urdfLinks();
    for (const LinkMass& l : links)
      if (l.name == "torso") torso = &l;
    tf = std::make_unique<TfSnapshots>(nh, linkNames(links));
    feedback_pub = nh.advertise<InteractiveMarkerFeedback>("/ragdoll_sim/drag/feedback", 10);
    impulse_pub = nh.advertise<ragdoll_sim::ApplyImpulse>("/ragdoll_sim/apply_impulse", 10);
    init_sub = nh.subscribe("/ragdoll_sim/drag/update_full", 5, &Fixture::onInit, this);
    update_sub = nh.subscribe("/ragdoll_sim/drag/update", 50, &Fixture::onUpdate, this);
    warnings = std::make_unique<NodeWarnings>(nh, "/ragdoll_sim");
    markers = std::make_unique<MarkerLog>(nh, "/ragdoll_sim/markers");
    stats_sub = nh.subscribe<ragdoll_sim::NodeStats>(
        "/ragdoll_sim/stats", 10,
        [this](const ragdoll_sim::NodeStats::ConstPtr& m) { drags = int64_t(m->drags); });
  }

  void setHandle(const std::string& name, const geometry_msgs::Pose& p) {
    std::lock_guard<std::mutex> lock(mutex);
    marker = name;
    handle = Vec3(p.position.x, p.position.y, p.position.z);
    handle_received = ros::WallTime::now();
  }
  void onInit(const visualization_msgs::InteractiveMarkerInit::ConstPtr& m) {
    if (m->markers.empty()) return;
    {
      std::lock_guard<std::mutex> lock(mutex);
      for (const auto& e : m->markers[0].menu_entries) menu[e.title] = e.id;
    }
    setHandle(m->markers[0].name, m->markers[0].pose);
  }
  void onUpdate(const visualization_msgs::InteractiveMarkerUpdate::ConstPtr& m) {
    for (const auto& im : m->markers) setHandle(im.name, im.pose);
    for (const auto& p : m->poses) setHandle(p.name, p.pose);
  }
  // The handle's last position, once one was received after `after`.
  bool handleAfter(const ros::WallTime& after, Vec3* out, std::string* name, double timeout = 10.0) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < deadline) {
      {
        std::lock_guard<std::mutex> lock(mutex);
        if (!marker.empty() && handle_received >= after) {
          *out = handle;
          if (name) *name = marker;
          return true;
        }
      }
      ros::WallDuration(0.02).sleep();
    }
    return false;
  }

  // Waits until the last handle pose is within `tol` of `link`'s centre of mass + the handle
  // height (latest TF); *off is the last distance seen.
  bool handleOver(const LinkMass& link, double tol, double* off, double timeout = 10.0) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout);
    while (ros::ok() && ros::WallTime::now() < deadline) {
      const Snapshot s = tf->latest();
      Vec3 h;
      {
        std::lock_guard<std::mutex> lock(mutex);
        h = handle;
      }
      if (s.valid() && h.allFinite()) {
        *off = (h - (comOf(s, link) + Vec3(0, 0, kHandleHeight))).norm();
        if (*off < tol) return true;
      }
      ros::WallDuration(0.02).sleep();
    }
    return false;
  }

  void send(uint8_t event, const Vec3& pose, const std::string& frame = "world",
            uint32_t menu_entry = 0) {
    InteractiveMarkerFeedback fb;
    fb.menu_entry_id = menu_entry;
    fb.header.frame_id = frame;
    fb.header.stamp = ros::Time::now();
    fb.client_id = "/drag_test";
    fb.marker_name = marker;
    fb.control_name = "move";
    fb.event_type = event;
    fb.pose.position.x = pose.x();
    fb.pose.position.y = pose.y();
    fb.pose.position.z = pose.z();
    fb.pose.orientation.w = 1.0;
    feedback_pub.publish(fb);
  }

  // Momentum from two snapshots 0.25 s of sim time apart, the first received after `after`.
  bool measure(Vec3* p, const ros::WallTime& after) {
    Snapshot a = tf->waitFor(ros::Time(), after);
    if (!a.valid()) return false;
    Snapshot b = tf->waitFor(a.stamp + ros::Duration(0.25));
    if (!b.valid()) return false;
    *p = momentum(a, b, links);
    return true;
  }
};

Fixture* fx = nullptr;
Vec3 g_target;  // B's target for the torso's centre of mass

}  // namespace

TEST(Drag, A_HandleFloatsAboveTheTorso) {
  ASSERT_NE(fx->torso, nullptr) << "robot_description missing or without a 'torso' link";
  Vec3 handle;
  std::string name;
  ASSERT_TRUE(fx->handleAfter(ros::WallTime(), &handle, &name, 30.0))
      << "no interactive marker on /ragdoll_sim/drag/update_full";
  Snapshot s = fx->tf->next();
  ASSERT_TRUE(s.valid());
  const Vec3 expected = comOf(s, *fx->torso) + Vec3(0, 0, kHandleHeight);
  EXPECT_LT((handle - expected).norm(), 0.01)
      << "handle '" << name << "' at " << str(handle) << ", torso centre of mass + 0.4 z at "
      << str(expected);
}

TEST(Drag, B_DraggedTheTorsoFollows) {
  ASSERT_TRUE(waitConnected(fx->feedback_pub)) << "node does not subscribe drag/feedback";
  Snapshot s0 = fx->tf->next();
  ASSERT_TRUE(s0.valid());
  const Vec3 com0 = comOf(s0, *fx->torso);
  g_target = com0 + Vec3(0.0, 0.5, 0.0);
  const Vec3 handle = g_target + Vec3(0, 0, kHandleHeight);
  const size_t markers_before = fx->markers->count();
  fx->send(InteractiveMarkerFeedback::MOUSE_DOWN, com0 + Vec3(0, 0, kHandleHeight));
  fx->send(InteractiveMarkerFeedback::POSE_UPDATE, handle);
  // The pull shows as an opaque arrow while dragging.
  EXPECT_TRUE(fx->markers->waitFor([](const MarkerLog::Array& m) {
    for (const auto* a : MarkerLog::inNs(m, "arrows"))
      if (a->action == visualization_msgs::Marker::ADD && a->color.a > 0.99f) return true;
    return false; }, nullptr, markers_before, 20.0)) << "no arrow for the drag's pull";

  // Within 3 s of sim time the torso's centre of mass comes within 0.1 m of the target.
  Snapshot start = fx->tf->waitFor(s0.stamp, ros::WallTime::now());
  ASSERT_TRUE(start.valid());
  Snapshot end = fx->tf->waitFor(start.stamp + ros::Duration(3.0), ros::WallTime(), 60.0);
  ASSERT_TRUE(end.valid());
  double closest = std::numeric_limits<double>::infinity();
  for (const Snapshot& s : fx->tf->range(start.stamp, end.stamp))
    closest = std::min(closest, (comOf(s, *fx->torso) - g_target).norm());
  const double final_distance = (comOf(end, *fx->torso) - g_target).norm();
  EXPECT_LT(closest, 0.1) << "the torso never came near the dragged handle";
  EXPECT_LT(final_distance, 0.2) << "the torso does not stay near the handle: "
                                 << str(comOf(end, *fx->torso)) << " vs " << str(g_target);
  // ~stats counts the drag once (it started with the mouse down, the pose update moved it).
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(5.0);
  while (fx->drags < 1 && ros::WallTime::now() < deadline) ros::WallDuration(0.02).sleep();
  EXPECT_EQ(fx->drags, 1) << "~stats drags";
  RecordProperty("closest_m", std::to_string(closest));
  RecordProperty("after_3s_m", std::to_string(final_distance));
}

TEST(Drag, C_ReleasedThePullStops) {
  fx->send(InteractiveMarkerFeedback::MOUSE_UP, g_target + Vec3(0, 0, kHandleHeight));
  // Push the ragdoll away from where it was dragged to (a spring still holding it would pull
  // it back).
  const Snapshot now = fx->tf->next();
  ASSERT_TRUE(now.valid());
  ragdoll_sim::ApplyImpulse push;
  push.link = "pelvis";
  push.frame = "world";
  push.point.x = now.position("pelvis").x();
  push.point.y = now.position("pelvis").y();
  push.point.z = now.position("pelvis").z();
  push.impulse.x = 20.0;  // about 0.3 m/s for the whole ragdoll
  ASSERT_TRUE(waitConnected(fx->impulse_pub));
  fx->impulse_pub.publish(push);
  Snapshot away;
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(30.0);
  while (ros::ok() && ros::WallTime::now() < deadline) {
    away = fx->tf->next();
    if (away.valid() && (comOf(away, *fx->torso) - g_target).norm() > 0.2) break;
  }
  ASSERT_TRUE(away.valid());
  ASSERT_GT((comOf(away, *fx->torso) - g_target).norm(), 0.2) << "the push did not move the ragdoll";

  // No force: with gravity off, the momentum stays what the push made it.
  Vec3 p1, p2;
  ASSERT_TRUE(fx->measure(&p1, away.received));
  ASSERT_TRUE(fx->measure(&p2, fx->tf->latest().received + ros::WallDuration(0.3)));
  EXPECT_LT((p2 - p1).norm(), 0.1) << "momentum still changes after the release: " << str(p1)
                                   << " -> " << str(p2);
  EXPECT_GT(p1.x(), 10.0) << "momentum after the 20 N*s push: " << str(p1);
  // The handle follows the torso again.
  double off = 0.0;
  EXPECT_TRUE(fx->handleOver(*fx->torso, 0.05, &off))
      << "the handle does not follow the torso after the release (" << off << " m off)";
}

TEST(Drag, D_BadFeedbackOnlyWarns) {
  Vec3 before;
  ASSERT_TRUE(fx->measure(&before, ros::WallTime::now()));
  Snapshot s = fx->tf->latest();
  const Vec3 far = comOf(s, *fx->torso) + Vec3(0, 0, 2.0);
  fx->send(InteractiveMarkerFeedback::POSE_UPDATE, far, "some_camera");
  EXPECT_TRUE(fx->warnings->wait({"some_camera", "drag dropped"}, 5.0))
      << "no WARN about feedback in another frame";
  fx->send(InteractiveMarkerFeedback::POSE_UPDATE,
           Vec3(std::numeric_limits<double>::quiet_NaN(), 0.0, 1.0));
  EXPECT_TRUE(fx->warnings->wait({"not finite", "drag dropped"}, 5.0))
      << "no WARN about a NaN drag pose";
  Vec3 after;
  ASSERT_TRUE(fx->measure(&after, ros::WallTime::now() + ros::WallDuration(0.3)));
  EXPECT_LT((after - before).norm(), 0.1) << "rejected drags changed the momentum: "
                                          << str(before) << " -> " << str(after);
}

TEST(Drag, E_MenuPicksAnotherLink) {
  uint32_t entry = 0;
  {
    std::lock_guard<std::mutex> lock(fx->mutex);
    ASSERT_TRUE(fx->menu.count("pelvis")) << "no 'pelvis' entry in the handle's context menu";
    entry = fx->menu["pelvis"];
  }
  const LinkMass* pelvis = nullptr;
  for (const LinkMass& l : fx->links)
    if (l.name == "pelvis") pelvis = &l;
  ASSERT_NE(pelvis, nullptr);
  fx->send(InteractiveMarkerFeedback::MENU_SELECT, Vec3::Zero(), "world", entry);
  double off = 0.0;
  EXPECT_TRUE(fx->handleOver(*pelvis, 0.05, &off))
      << "the handle is not over the pelvis after choosing it in the menu (" << off << " m off)";
}

int main(int argc, char** argv) {
  return runFixtureTests(argc, argv, "drag_test", 2, fx);
}
