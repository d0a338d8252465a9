// rostest: the node's ~markers (MarkerArray). A: one namespace per ragdoll with one colour, as
// many shape markers as the URDF has collision shapes (a capsule is a cylinder + 2 spheres);
// B: contact points and normals once the ragdoll touches the ground (~markers/contacts);
// C: an impulse shows an opaque arrow at its point that fades over ~markers/arrow_fade s of
// sim time (stamps) and is then deleted; D: a force's arrow stays opaque for its duration, then
// fades out too.
#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <set>
#include <tuple>

#include <ragdoll_sim/ApplyForce.h>
#include <ragdoll_sim/ApplyImpulse.h>
#include <urdf_parser/urdf_parser.h>

#include "marker_log.hpp"
#include "node_log.hpp"

using namespace ragdoll_test;
using visualization_msgs::Marker;

namespace {

const double kFade = 0.5;  // ~markers/arrow_fade in markers.test
// Sim time between the messages that bracket an event: a publish period, or a late loop's
// catch-up (~max_catchup = 0.1 s of physics) before it publishes.
const double kSlack = 0.15;

struct Fixture {
  ros::NodeHandle nh;
  std::unique_ptr<MarkerLog> markers;
  ros::Publisher impulse_pub, force_pub;
  std::string robot;        // URDF robot name = the ragdoll's marker namespace
  size_t collision_markers = 0;

  void init() {
    markers = std::make_unique<MarkerLog>(nh, "/ragdoll_sim/markers");
    impulse_pub = nh.advertise<ragdoll_sim::ApplyImpulse>("/ragdoll_sim/apply_impulse", 10);
    force_pub = nh.advertise<ragdoll_sim::ApplyForce>("/ragdoll_sim/apply_force", 10);
    std::string xml;
    ros::param::get("/robot_description", xml);
    urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(xml);
    if (!model) return;
    robot = model->getName();
    for (const auto& kv : model->links_)
      for (const auto& c : kv.second->collision_array)
        if (c && c->geometry) ++collision_markers;
  }
};

Fixture* fx = nullptr;

// Sim time of a message: the stamp of its markers (all share it).
ros::Time stampOf(const MarkerLog::Array& a) {
  return a.markers.empty() ? ros::Time() : a.markers[0].header.stamp;
}

// The arrow marker `id` of a message, or null.
const Marker* arrowOf(const MarkerLog::Array& a, int id) {
  for (const Marker* m : MarkerLog::inNs(a, "arrows"))
    if (m->id == id) return m;
  return nullptr;
}

bool hasArrow(const MarkerLog::Array& a, int action) {
  for (const Marker* m : MarkerLog::inNs(a, "arrows"))
    if (m->action == action) return true;
  return false;
}

}  // namespace

TEST(Markers, A_OneColourPerRagdollAndAMarkerPerShape) {
  ASSERT_FALSE(fx->robot.empty()) << "robot_description missing or not a URDF";
  MarkerLog::Array a;
  ASSERT_TRUE(fx->markers->waitFor([](const MarkerLog::Array&) { return true; }, &a, 0, 30.0))
      << "no message on /ragdoll_sim/markers";
  std::map<std::string, std::set<std::tuple<float, float, float>>> colours;
  std::map<std::string, size_t> count;
  for (const Marker& m : a.markers) {
    EXPECT_EQ(m.header.frame_id, "world");
    colours[m.ns].insert({m.color.r, m.color.g, m.color.b});
    ++count[m.ns];
  }
  ASSERT_EQ(colours.count(fx->robot), 1u) << "no marker namespace named after the ragdoll '"
                                          << fx->robot << "'";
  EXPECT_EQ(colours[fx->robot].size(), 1u) << "the ragdoll's shapes have several colours";
  ASSERT_EQ(colours.count("ground"), 1u);
  EXPECT_NE(*colours[fx->robot].begin(), *colours["ground"].begin());
  // Every URDF collision is one marker or more (a capsule-like cylinder may be 3); no strays.
  EXPECT_GE(count[fx->robot], fx->collision_markers);
  EXPECT_LE(count[fx->robot], 3 * fx->collision_markers);
  RecordProperty("shape_markers", std::to_string(count[fx->robot]));
}

TEST(Markers, B_ContactPointsAndNormalsOnTheGround) {
  MarkerLog::Array a;
  const bool seen = fx->markers->waitFor(
      [](const MarkerLog::Array& m) {
        for (const Marker* c : MarkerLog::inNs(m, "contacts"))
          if (c->action == Marker::ADD && c->type == Marker::SPHERE_LIST && !c->points.empty())
            return true;
        return false;
      },
      &a, 0, 30.0);
  ASSERT_TRUE(seen) << "no contact markers while the ragdoll falls onto the ground";
  auto c = MarkerLog::inNs(a, "contacts");
  ASSERT_EQ(c.size(), 2u);
  const Marker* points = c[0]->type == Marker::SPHERE_LIST ? c[0] : c[1];
  const Marker* normals = c[0]->type == Marker::SPHERE_LIST ? c[1] : c[0];
  EXPECT_EQ(normals->type, Marker::LINE_LIST);
  EXPECT_EQ(normals->points.size(), 2 * points->points.size());
  size_t on_ground = 0;
  for (const auto& p : points->points) on_ground += std::abs(p.z) < 0.02;
  EXPECT_GT(on_ground, 0u) << "no contact point on the ground plane";
}

TEST(Markers, C_ImpulseArrowFadesAndIsDeleted) {
  ASSERT_TRUE(waitConnected(fx->impulse_pub));
  // Start from a message without any arrow.
  MarkerLog::Array a;
  ASSERT_TRUE(fx->markers->waitFor([](const MarkerLog::Array& m) {
    return MarkerLog::inNs(m, "arrows").empty(); }, &a, fx->markers->count(), 20.0));
  ragdoll_sim::ApplyImpulse cmd;
  cmd.link = "torso";
  cmd.frame = "link";
  cmd.point.z = 0.2;
  cmd.impulse.x = 20.0;
  const size_t before = fx->markers->count();
  fx->impulse_pub.publish(cmd);

  MarkerLog::Array first;
  ASSERT_TRUE(fx->markers->waitFor([](const MarkerLog::Array& m) { return hasArrow(m, Marker::ADD); },
                                   &first, before, 20.0))
      << "no arrow after an impulse";
  const Marker arrow = *MarkerLog::inNs(first, "arrows")[0];
  EXPECT_EQ(arrow.type, Marker::ARROW);
  EXPECT_GT(arrow.color.a, 0.8f);
  ASSERT_EQ(arrow.points.size(), 2u);
  // Tail -> head along the impulse (+x in the torso frame, about +x in world when lying or not,
  // up to the ragdoll's yaw): 20 N*s * 0.02 m/(N*s) = 0.4 m long.
  const double len = std::hypot(arrow.points[1].x - arrow.points[0].x,
                                std::hypot(arrow.points[1].y - arrow.points[0].y,
                                           arrow.points[1].z - arrow.points[0].z));
  EXPECT_NEAR(len, 0.4, 1e-6);

  // Fading: some message shows it more transparent, then one DELETE of its id, after which
  // it is gone. The sim time (stamps) from the first arrow to the DELETE is the fade time (the
  // impulse ends when applied), give or take the slack between messages.
  const int id = arrow.id;
  MarkerLog::Array fading, deleted, later;
  EXPECT_TRUE(fx->markers->waitFor([&](const MarkerLog::Array& m) {
    const Marker* x = arrowOf(m, id);
    return x && x->action == Marker::ADD && x->color.a < 0.9f * arrow.color.a; }, &fading, before))
      << "the arrow does not fade";
  ASSERT_TRUE(fx->markers->waitFor([&](const MarkerLog::Array& m) {
    const Marker* x = arrowOf(m, id);
    return x && x->action == Marker::DELETE; }, &deleted, before, 30.0))
      << "the arrow is never deleted";
  const double life = (stampOf(deleted) - stampOf(first)).toSec();
  EXPECT_GE(life, kFade - kSlack) << "deleted after " << life << " s of sim time";
  EXPECT_LE(life, kFade + kSlack) << "deleted after " << life << " s of sim time";
  const size_t after_delete = fx->markers->count();
  ASSERT_TRUE(fx->markers->waitFor([](const MarkerLog::Array&) { return true; }, &later, after_delete));
  EXPECT_EQ(arrowOf(later, id), nullptr) << "the arrow is still sent after its DELETE";
  RecordProperty("arrow_life_sim_s", std::to_string(life));
}

TEST(Markers, D_ForceArrowOpaqueForItsDurationThenFades) {
  ragdoll_sim::ApplyForce cmd;
  cmd.link = "pelvis";
  cmd.frame = "link";
  cmd.force.y = 200.0;
  cmd.duration = 1.0;
  const size_t before = fx->markers->count();
  fx->force_pub.publish(cmd);
  MarkerLog::Array first;
  ASSERT_TRUE(fx->markers->waitFor([](const MarkerLog::Array& m) { return hasArrow(m, Marker::ADD); },
                                   &first, before, 20.0))
      << "no arrow after a force";
  const int id = MarkerLog::inNs(first, "arrows")[0]->id;
  // Opaque until the force ends, 1 s of sim time after it started (give or take the slack); an
  // array sent before the first arrow (it arrives after `before` on a loaded machine) lacks the
  // arrow without its having faded.
  MarkerLog::Array faded;
  ASSERT_TRUE(fx->markers->waitFor([&](const MarkerLog::Array& m) {
    if (stampOf(m) <= stampOf(first)) return false;
    const Marker* x = arrowOf(m, id);
    return !x || x->action == Marker::DELETE || x->color.a < 0.99f; }, &faded, before, 30.0));
  const double opaque = (stampOf(faded) - stampOf(first)).toSec();
  EXPECT_GE(opaque, 1.0 - kSlack) << "the force arrow faded after " << opaque << " s of sim time";
  MarkerLog::Array deleted;
  ASSERT_TRUE(fx->markers->waitFor([&](const MarkerLog::Array& m) {
    const Marker* x = arrowOf(m, id);
    return x && x->action == Marker::DELETE; }, &deleted, before, 30.0))
      << "the force arrow is never deleted";
  const double life = (stampOf(deleted) - stampOf(first)).toSec();
  EXPECT_GE(life, 1.0 + kFade - kSlack);
  EXPECT_LE(life, 1.0 + kFade + kSlack);
}

int main(int argc, char** argv) {
  return runFixtureTests(argc, argv, "markers_test", 2, fx);
}
