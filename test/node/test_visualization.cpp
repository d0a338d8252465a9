// Unit tests of the node's markers (src/node/visualization.*): colours per ragdoll and object,
// the arrow fade law, and the MarkerArray the Visualizer builds from a World (no ROS master
// needed).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <set>

#include "scene_views.hpp"
#include "visualization.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::node;
using visualization_msgs::Marker;
using visualization_msgs::MarkerArray;

namespace {

double dist(const Rgba& a, const Rgba& b) {
  return std::sqrt((a.r - b.r) * (a.r - b.r) + (a.g - b.g) * (a.g - b.g) + (a.b - b.b) * (a.b - b.b));
}

std::vector<const Marker*> inNs(const MarkerArray& a, const std::string& ns) {
  std::vector<const Marker*> out;
  for (const Marker& m : a.markers)
    if (m.ns == ns) out.push_back(&m);
  return out;
}

Vec3 vec(const geometry_msgs::Point& p) { return Vec3(p.x, p.y, p.z); }

}  // namespace

TEST(RagdollColor, DistinctPerRagdollAndFromArrowsAndContacts) {
  const std::vector<Rgba> others{impulseArrowColor(), forceArrowColor(), contactColor()};
  // The palette's six are far apart; beyond it the golden-angle hues stay distinct.
  for (size_t i = 0; i < 32; ++i) {
    const Rgba c = ragdollColor(i);
    EXPECT_EQ(c.a, 1.0f);
    for (size_t j = 0; j < i; ++j)
      EXPECT_GT(dist(c, ragdollColor(j)), i < 6 ? 0.3 : 0.03) << "ragdolls " << i << " and " << j;
    if (i < 6) {
      for (const Rgba& o : others) EXPECT_GT(dist(c, o), 0.3) << "ragdoll " << i;
    }
    // Saturated enough to be told from the grey ground and background in a screenshot.
    const float mx = std::max({c.r, c.g, c.b}), mn = std::min({c.r, c.g, c.b});
    EXPECT_GT((mx - mn) / mx, 0.4f) << "ragdoll " << i;
  }
}

TEST(ArrowAlpha, OpaqueWhilePushingThenLinearToZero) {
  EXPECT_EQ(arrowAlpha(-3.0, 1.0), 1.0);
  EXPECT_EQ(arrowAlpha(0.0, 1.0), 1.0);
  EXPECT_NEAR(arrowAlpha(0.25, 1.0), 0.75, 1e-12);
  EXPECT_NEAR(arrowAlpha(1.0, 2.0), 0.5, 1e-12);
  EXPECT_EQ(arrowAlpha(1.0, 1.0), 0.0);
  EXPECT_EQ(arrowAlpha(5.0, 1.0), 0.0);
  EXPECT_EQ(arrowAlpha(1e-6, 0.0), 0.0);  // no fade: gone once the push is over
}

TEST(Visualizer, ShapesColouredPerRagdollFollowTheBodies) {
  test::TwoRagdolls scene(1.0);
  Visualizer viz(MarkerSettings(), "world");
  viz.setScene(scene.world, scene.views(), scene.ground);
  // Per ragdoll: pelvis box (1) + torso capsule (cylinder + 2 spheres); plus the ground slab.
  EXPECT_EQ(viz.shapeMarkerCount(), 9u);
  MarkerArray a = viz.update(scene.world, ros::Time(10.0), 0.0);
  ASSERT_EQ(a.markers.size(), 9u);
  std::map<std::string, std::set<std::tuple<float, float, float>>> colours;
  std::map<std::string, std::set<int>> ids;
  for (const Marker& m : a.markers) {
    EXPECT_EQ(m.header.frame_id, "world");
    EXPECT_EQ(m.header.stamp, ros::Time(10.0));
    EXPECT_EQ(m.action, Marker::ADD);
    colours[m.ns].insert({m.color.r, m.color.g, m.color.b});
    EXPECT_TRUE(ids[m.ns].insert(m.id).second) << "duplicate id " << m.id << " in " << m.ns;
  }
  ASSERT_EQ(colours.size(), 3u);
  ASSERT_EQ(colours["first"].size(), 1u);
  ASSERT_EQ(colours["second"].size(), 1u);
  EXPECT_NE(*colours["first"].begin(), *colours["second"].begin());
  const Rgba c0 = ragdollColor(0);
  EXPECT_EQ(*colours["first"].begin(), std::make_tuple(c0.r, c0.g, c0.b));
  EXPECT_EQ(inNs(a, "ground").size(), 1u);
  // The first marker of "second" is its pelvis box at (0, 2, 1).
  const Marker* box = inNs(a, "second")[0];
  EXPECT_EQ(box->type, Marker::CUBE);
  EXPECT_NEAR((Vec3(box->pose.position.x, box->pose.position.y, box->pose.position.z) -
               Vec3(0, 2, 1)).norm(), 0.0, 1e-9);
  // Moved body, moved marker.
  scene.world.setBodyState(scene.b.bodies[0], Transform(Vec3(3, 2, 1), Quat::Identity()),
                           Vec3::Zero(), Vec3::Zero());
  a = viz.update(scene.world, ros::Time(10.1), 0.1);
  box = inNs(a, "second")[0];
  EXPECT_NEAR(box->pose.position.x, 3.0, 1e-9);
}

TEST(Visualizer, ImpulseArrowFadesOverSimTimeThenOneDelete) {
  test::TwoRagdolls scene(1.0);
  MarkerSettings s;
  s.arrow_fade = 0.5;
  Visualizer viz(s, "world");
  viz.setScene(scene.world, scene.views(), scene.ground);
  const BodyId torso = scene.a.bodies[1];
  const Vec3 point(0.12, 0, 1.4);
  viz.addImpulse(scene.world, torso, point, Vec3(-20, 0, 0), 2.0);
  MarkerArray a = viz.update(scene.world, ros::Time(1), 2.0);
  auto arrows = inNs(a, "arrows");
  ASSERT_EQ(arrows.size(), 1u);
  EXPECT_EQ(arrows[0]->type, Marker::ARROW);
  EXPECT_EQ(arrows[0]->action, Marker::ADD);
  EXPECT_FLOAT_EQ(arrows[0]->color.a, 1.0f);
  ASSERT_EQ(arrows[0]->points.size(), 2u);
  // Head at the point, tail 20 N*s * 0.02 m/(N*s) = 0.4 m against the impulse.
  EXPECT_NEAR((vec(arrows[0]->points[1]) - point).norm(), 0.0, 1e-9);
  EXPECT_NEAR((vec(arrows[0]->points[0]) - (point + Vec3(0.4, 0, 0))).norm(), 0.0, 1e-9);
  const int id = arrows[0]->id;

  // Half the fade time later: half transparent, and it moved with the torso.
  scene.world.setBodyState(torso, Transform(Vec3(0, 0, 2.1), Quat::Identity()), Vec3::Zero(),
                           Vec3::Zero());
  a = viz.update(scene.world, ros::Time(2), 2.25);
  arrows = inNs(a, "arrows");
  ASSERT_EQ(arrows.size(), 1u);
  EXPECT_NEAR(arrows[0]->color.a, 0.5, 1e-6);
  EXPECT_NEAR(arrows[0]->points[1].z, 2.4, 1e-9);

  // Past the fade time: one DELETE for its id, then nothing.
  a = viz.update(scene.world, ros::Time(3), 2.5);
  arrows = inNs(a, "arrows");
  ASSERT_EQ(arrows.size(), 1u);
  EXPECT_EQ(arrows[0]->action, Marker::DELETE);
  EXPECT_EQ(arrows[0]->id, id);
  EXPECT_EQ(viz.arrowCount(), 0u);
  a = viz.update(scene.world, ros::Time(4), 2.6);
  EXPECT_TRUE(inNs(a, "arrows").empty());
  EXPECT_EQ(a.markers.size(), viz.shapeMarkerCount());
}

TEST(Visualizer, ForceArrowOpaqueForItsDurationOrUntilCleared) {
  test::TwoRagdolls scene(1.0);
  MarkerSettings s;
  s.arrow_fade = 1.0;
  Visualizer viz(s, "world");
  viz.setScene(scene.world, scene.views(), scene.ground);
  viz.addForce(scene.world, scene.a.bodies[0], Vec3(0, 0, 1), Vec3(0, 300, 0), 0.0, 2.0);
  viz.addForce(scene.world, scene.b.bodies[0], Vec3(0, 2, 1), Vec3(0, 0, 100), 0.0, -1.0);
  auto alphas = [&](double t) {
    std::map<int, float> out;
    for (const Marker* m : inNs(viz.update(scene.world, ros::Time(1), t), "arrows"))
      out[m->id] = m->action == Marker::DELETE ? -1.0f : m->color.a;
    return out;
  };
  auto al = alphas(1.9);
  ASSERT_EQ(al.size(), 2u);
  EXPECT_FLOAT_EQ(al[0], 1.0f);
  EXPECT_FLOAT_EQ(al[1], 1.0f);
  al = alphas(2.5);  // the 2 s force is over: fading; the other one lasts
  EXPECT_NEAR(al[0], 0.5, 1e-6);
  EXPECT_FLOAT_EQ(al[1], 1.0f);
  viz.endForces(2.5);  // ~clear_forces
  al = alphas(3.25);
  EXPECT_EQ(al[0], -1.0f);
  EXPECT_NEAR(al[1], 0.25, 1e-6);
  al = alphas(3.6);
  EXPECT_EQ(al.count(0), 0u);
  EXPECT_EQ(al[1], -1.0f);
}

TEST(Visualizer, ContactsWhenEnabledDeletedWhenGone) {
  test::TwoRagdolls scene(0.1, /*gravity=*/true);  // pelvis boxes resting on the ground
  MarkerSettings s;
  s.contacts = true;
  Visualizer viz(s, "world");
  viz.setScene(scene.world, scene.views(), scene.ground);
  for (int i = 0; i < 50; ++i) scene.world.step(1e-3);
  MarkerArray a = viz.update(scene.world, ros::Time(1), 0.05);
  auto contacts = inNs(a, "contacts");
  ASSERT_EQ(contacts.size(), 2u);
  EXPECT_EQ(contacts[0]->type, Marker::SPHERE_LIST);
  EXPECT_EQ(contacts[1]->type, Marker::LINE_LIST);
  EXPECT_GE(contacts[0]->points.size(), 8u);  // 4 corners per box
  EXPECT_EQ(contacts[1]->points.size(), 2 * contacts[0]->points.size());
  for (const auto& p : contacts[0]->points) EXPECT_NEAR(p.z, 0.0, 0.01);

  // Lift both ragdolls off the ground: the contact markers go with one DELETE each.
  for (const Ragdoll* r : {&scene.a, &scene.b})
    for (BodyId b : r->bodies) {
      const Transform pose = scene.world.bodyPose(b);
      scene.world.setBodyState(b, Transform(pose.p + Vec3(0, 0, 2), pose.q), Vec3::Zero(), Vec3::Zero());
    }
  scene.world.setGravity(Vec3::Zero());
  scene.world.step(1e-3);
  a = viz.update(scene.world, ros::Time(2), 0.051);
  contacts = inNs(a, "contacts");
  ASSERT_EQ(contacts.size(), 2u);
  EXPECT_EQ(contacts[0]->action, Marker::DELETE);
  EXPECT_EQ(contacts[1]->action, Marker::DELETE);
  a = viz.update(scene.world, ros::Time(3), 0.052);
  EXPECT_TRUE(inNs(a, "contacts").empty());

  // Disabled: never any contact markers.
  Visualizer off(MarkerSettings(), "world");
  test::TwoRagdolls resting(0.1, true);
  off.setScene(resting.world, resting.views(), resting.ground);
  for (int i = 0; i < 50; ++i) resting.world.step(1e-3);
  EXPECT_TRUE(inNs(off.update(resting.world, ros::Time(1), 0.05), "contacts").empty());
}

TEST(Visualizer, SceneChangeDropsArrowsAndOldestArrowsGoBeyondTheCap) {
  test::TwoRagdolls scene(1.0);
  MarkerSettings s;
  s.max_arrows = 3;
  Visualizer viz(s, "world");
  viz.setScene(scene.world, scene.views(), scene.ground);
  for (int i = 0; i < 5; ++i)
    viz.addImpulse(scene.world, scene.a.bodies[0], Vec3(0, 0, 1), Vec3(1, 0, 0), 0.0);
  EXPECT_EQ(viz.arrowCount(), 3u);
  MarkerArray a = viz.update(scene.world, ros::Time(1), 0.0);
  std::set<int> added, deleted;
  for (const Marker* m : inNs(a, "arrows"))
    (m->action == Marker::DELETE ? deleted : added).insert(m->id);
  EXPECT_EQ(added, (std::set<int>{2, 3, 4}));
  EXPECT_EQ(deleted, (std::set<int>{0, 1}));
  viz.setScene(scene.world, scene.views(), scene.ground);  // e.g. ~reset
  EXPECT_EQ(viz.arrowCount(), 0u);
  deleted.clear();
  for (const Marker* m : inNs(viz.update(scene.world, ros::Time(2), 0.0), "arrows")) {
    EXPECT_EQ(m->action, Marker::DELETE);
    deleted.insert(m->id);
  }
  EXPECT_EQ(deleted, (std::set<int>{2, 3, 4}));
}

TEST(Visualizer, PullArrowUpdatedInPlaceThenFades) {
  test::TwoRagdolls scene(1.0);
  MarkerSettings s;
  s.arrow_fade = 1.0;
  Visualizer viz(s, "world");
  viz.setScene(scene.world, scene.views(), scene.ground);
  const BodyId torso = scene.a.bodies[1];
  viz.setPull(0, scene.world, torso, Vec3(0, 0, 1.4), Vec3(0, 100, 0));
  viz.setPull(0, scene.world, torso, Vec3(0, 0, 1.4), Vec3(0, 0, 200));  // same arrow, new force
  viz.endForces(0.0);  // ~clear_forces leaves a drag alone
  ASSERT_EQ(viz.arrowCount(), 1u);
  MarkerArray a = viz.update(scene.world, ros::Time(1), 5.0);
  auto arrows = inNs(a, "arrows");
  ASSERT_EQ(arrows.size(), 1u);
  EXPECT_FLOAT_EQ(arrows[0]->color.a, 1.0f);
  // 200 N * 0.002 m/N = 0.4 m, pointing up at the point.
  EXPECT_NEAR((vec(arrows[0]->points[0]) - Vec3(0, 0, 1.0)).norm(), 0.0, 1e-9);
  const int id = arrows[0]->id;
  viz.endPull(0, 5.0);  // released
  a = viz.update(scene.world, ros::Time(2), 5.5);
  arrows = inNs(a, "arrows");
  ASSERT_EQ(arrows.size(), 1u);
  EXPECT_NEAR(arrows[0]->color.a, 0.5, 1e-6);
  // A new drag with the same key is a new arrow; the old one fades on.
  viz.setPull(0, scene.world, torso, Vec3(0, 0, 1.4), Vec3(50, 0, 0));
  a = viz.update(scene.world, ros::Time(3), 5.6);
  std::map<int, float> alpha;
  for (const Marker* m : inNs(a, "arrows")) alpha[m->id] = m->color.a;
  ASSERT_EQ(alpha.size(), 2u);
  EXPECT_NEAR(alpha[id], 0.4, 1e-6);
  EXPECT_FLOAT_EQ(alpha[id + 1], 1.0f);
}

TEST(ObjectColor, OwnColourOrGreyStaticDarker) {
  LinkDef plain;
  const Rgba grey = objectColor(plain, false), dark = objectColor(plain, true);
  EXPECT_FLOAT_EQ(grey.r, grey.g);
  EXPECT_FLOAT_EQ(grey.g, grey.b);
  EXPECT_NEAR(dark.r, 0.6 * grey.r, 1e-6);
  LinkDef red;
  red.has_color = true;
  red.color = {1.0, 0.0, 0.0, 1.0};
  EXPECT_FLOAT_EQ(objectColor(red, false).r, 1.0f);
  EXPECT_FLOAT_EQ(objectColor(red, false).g, 0.0f);
  EXPECT_NEAR(objectColor(red, true).r, 0.6, 1e-6);
}

TEST(Visualizer, ObjectsDrawnInTheirNamespaceStaticPlanesAsSlabs) {
  World world;
  BodyDef box_def;
  box_def.pose = Transform(Vec3(1, 2, 3), Quat::Identity());
  const BodyId box = world.createBody(box_def);
  world.addShape(box, {Geometry::box(Vec3(0.1, 0.2, 0.3)), Transform(), Material()});
  BodyDef plane_def;
  plane_def.type = BodyType::Static;
  const BodyId plane = world.createBody(plane_def);
  world.addShape(plane, {Geometry::plane(Vec3::UnitZ(), -1.0), Transform(), Material()});
  RagdollDef crate, floor;
  crate.links.resize(1);
  floor.links.resize(1);
  Visualizer viz(MarkerSettings(), "world");
  viz.setScene(world, {}, BodyId(), {{"crate", &crate, {box}, false}, {"floor", &floor, {plane}, true}});
  const MarkerArray a = viz.update(world, ros::Time(1.0), 0.0);
  const auto c = inNs(a, "crate"), f = inNs(a, "floor");
  ASSERT_EQ(c.size(), 1u);
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(c[0]->type, Marker::CUBE);
  EXPECT_NEAR(c[0]->scale.y, 0.4, 1e-12);
  EXPECT_NEAR(c[0]->pose.position.z, 3.0, 1e-12);
  EXPECT_EQ(f[0]->type, Marker::CUBE);
  EXPECT_NEAR(f[0]->pose.position.z + 0.5 * f[0]->scale.z, -1.0, 1e-9);  // top face on the plane
  EXPECT_LT(f[0]->color.r, c[0]->color.r);
}

// A world's plane that replaced the ground is drawn once, as its object; a ragdoll link that
// carries a plane keeps its other shapes drawn (the plane itself is not).
TEST(Visualizer, WorldGroundDrawnOnceAndRagdollPlanesLeftOut) {
  World world;
  BodyDef plane_def;
  plane_def.type = BodyType::Static;
  const BodyId plane = world.createBody(plane_def);
  world.addShape(plane, {Geometry::plane(Vec3::UnitZ(), 0.0), Transform(), Material()});
  const BodyId link = world.createBody(BodyDef());
  world.addShape(link, {Geometry::box(Vec3(0.1, 0.1, 0.1)), Transform(), Material()});
  world.addShape(link, {Geometry::plane(Vec3::UnitZ(), -5.0), Transform(), Material()});
  RagdollDef floor;
  floor.links.resize(1);
  Ragdoll ragdoll;
  ragdoll.bodies = {link};
  RagdollDef ragdoll_def;
  ragdoll_def.links.resize(1);
  Visualizer viz(MarkerSettings(), "world");
  viz.setScene(world, {{"r", "r", &ragdoll_def, &ragdoll}}, plane, {{"floor", &floor, {plane}, true}});
  const MarkerArray a = viz.update(world, ros::Time(1.0), 0.0);
  EXPECT_EQ(inNs(a, "floor").size(), 1u);
  EXPECT_EQ(inNs(a, "ground").size(), 0u);
  const auto r = inNs(a, "r");
  ASSERT_EQ(r.size(), 1u);
  EXPECT_EQ(r[0]->type, Marker::CUBE);
}

// Issue 57: the force of each touching pair as an arrow of ~markers/force_scale, from the
// pair's centre up out of the ground (the force on the dynamic body); 0 turns them off.
TEST(Visualizer, ContactForceArrowsScaledByForceScale) {
  test::TwoRagdolls scene(0.1, /*gravity=*/true);  // pelvis boxes resting on the ground
  MarkerSettings s;
  s.contacts = true;
  s.force_scale = 0.001;
  Visualizer viz(s, "world");
  viz.setScene(scene.world, scene.views(), scene.ground);
  for (int i = 0; i < 300; ++i) scene.world.step(1e-3);
  auto arrows = inNs(viz.update(scene.world, ros::Time(1), 0.3), "contact_forces");
  // Each stick (30 kg) stands on its pelvis box: one pair each, holding m g.
  ASSERT_EQ(arrows.size(), 2u);
  for (const Marker* m : arrows) {
    EXPECT_EQ(m->type, Marker::ARROW);
    ASSERT_EQ(m->points.size(), 2u);
    const Vec3 tail = vec(m->points[0]), tip = vec(m->points[1]);
    EXPECT_NEAR(tail.z(), 0.0, 0.01);
    EXPECT_NEAR(tip.z() - tail.z(), 30.0 * 9.81 * 0.001, 0.02 * 30.0 * 9.81 * 0.001);
    EXPECT_NEAR((tip - tail).head<2>().norm(), 0.0, 1e-3);
  }
  // Lifted off: the two arrows go with one DELETE each, then nothing.
  for (const Ragdoll* r : {&scene.a, &scene.b})
    for (BodyId b : r->bodies) {
      const Transform pose = scene.world.bodyPose(b);
      scene.world.setBodyState(b, Transform(pose.p + Vec3(0, 0, 2), pose.q), Vec3::Zero(), Vec3::Zero());
    }
  scene.world.setGravity(Vec3::Zero());
  scene.world.step(1e-3);
  arrows = inNs(viz.update(scene.world, ros::Time(2), 0.301), "contact_forces");
  ASSERT_EQ(arrows.size(), 2u);
  for (const Marker* m : arrows) EXPECT_EQ(m->action, Marker::DELETE);
  EXPECT_TRUE(inNs(viz.update(scene.world, ros::Time(3), 0.302), "contact_forces").empty());

  s.force_scale = 0.0;  // off
  Visualizer off(s, "world");
  test::TwoRagdolls resting(0.1, true);
  off.setScene(resting.world, resting.views(), resting.ground);
  for (int i = 0; i < 50; ++i) resting.world.step(1e-3);
  const MarkerArray a = off.update(resting.world, ros::Time(1), 0.05);
  EXPECT_TRUE(inNs(a, "contact_forces").empty());
  EXPECT_EQ(inNs(a, "contacts").size(), 2u);  // points and normals still
}

TEST(Visualizer, ImpactFlashSizedByImpulseFadesThenOneDelete) {
  test::TwoRagdolls scene(1.0);
  MarkerSettings s;
  s.impact_flash = 0.3;
  s.impulse_scale = 0.02;
  Visualizer viz(s, "world");
  viz.setScene(scene.world, scene.views(), scene.ground);
  ImpactEvent e;
  e.point = Vec3(0.5, 0, 0);
  e.impulse = 10.0;
  e.time = 2.0;
  viz.addImpact(e);
  ASSERT_EQ(viz.flashCount(), 1u);
  auto flashes = inNs(viz.update(scene.world, ros::Time(2), 2.0), "impacts");
  ASSERT_EQ(flashes.size(), 1u);
  EXPECT_EQ(flashes[0]->type, Marker::SPHERE);
  EXPECT_NEAR(flashes[0]->scale.x, 10.0 * 0.02, 1e-9);  // 0.2 m for 10 N s
  EXPECT_NEAR(flashes[0]->pose.position.x, 0.5, 1e-9);
  const float a0 = flashes[0]->color.a;
  flashes = inNs(viz.update(scene.world, ros::Time(3), 2.15), "impacts");
  ASSERT_EQ(flashes.size(), 1u);
  EXPECT_NEAR(flashes[0]->color.a, 0.5 * a0, 1e-6);  // half of 0.3 s gone
  flashes = inNs(viz.update(scene.world, ros::Time(4), 2.31), "impacts");
  ASSERT_EQ(flashes.size(), 1u);
  EXPECT_EQ(flashes[0]->action, Marker::DELETE);
  EXPECT_EQ(viz.flashCount(), 0u);
  EXPECT_TRUE(inNs(viz.update(scene.world, ros::Time(5), 2.4), "impacts").empty());

  e.impulse = 1e4;  // clamped to max_arrow
  viz.addImpact(e);
  flashes = inNs(viz.update(scene.world, ros::Time(6), 2.0), "impacts");
  ASSERT_EQ(flashes.size(), 1u);
  EXPECT_NEAR(flashes[0]->scale.x, s.max_arrow, 1e-9);

  s.impact_flash = 0.0;  // off: no flashes
  Visualizer off(s, "world");
  off.setScene(scene.world, scene.views(), scene.ground);
  off.addImpact(e);
  EXPECT_EQ(off.flashCount(), 0u);
}

// A Scene step's impact events become flashes (recordStep).
TEST(Visualizer, RecordStepTurnsSceneImpactsIntoFlashes) {
  SceneDef d;
  d.impacts.enabled = true;
  Scene scene(d);
  SpawnDef ball;
  ball.name = "ball";
  LinkDef link;
  link.name = "l";
  link.mass = 1.0;
  link.inertia = Mat3::Identity() * 0.004;
  link.shapes.push_back({Geometry::sphere(0.1), Transform(), Material()});
  ball.def.links.push_back(link);
  ball.pose = Transform(Vec3(0, 0, 1.1), Quat::Identity());
  std::string error;
  ASSERT_EQ(scene.addObject(ball, &error), SpawnResult::Added) << error;
  ASSERT_TRUE(scene.start(&error)) << error;
  Visualizer viz(MarkerSettings(), "world");
  size_t events = 0;
  for (int i = 0; i < 600; ++i) {
    scene.step();
    events += scene.impacts().size();
    viz.recordStep(scene);
  }
  EXPECT_EQ(events, 1u);
  EXPECT_EQ(viz.flashCount(), 1u);
}

TEST(Visualizer, InjuryTextOverTheHeadFollowsItsRagdoll) {
  test::TwoRagdolls scene(1.0);
  Visualizer viz(MarkerSettings(), "world");
  viz.setScene(scene.world, scene.views(), scene.ground);
  InjuryReport r;
  r.ragdoll = "first";
  r.peak_g = 42.26;
  r.hic15 = 311.6;
  EXPECT_EQ(injuryText(r), "first: peak 42.3 g, HIC15 312");
  viz.setInjury("first", 1, scene.a.bodies[1], r);
  r.hic15 = 500.0;
  viz.setInjury("first", 1, scene.a.bodies[1], r);  // a later fall replaces it
  ASSERT_EQ(viz.injuryTextCount(), 1u);
  auto texts = inNs(viz.update(scene.world, ros::Time(1), 0.0), "injury");
  ASSERT_EQ(texts.size(), 1u);
  EXPECT_EQ(texts[0]->type, Marker::TEXT_VIEW_FACING);
  EXPECT_EQ(texts[0]->text, "first: peak 42.3 g, HIC15 500");
  const Vec3 torso = scene.world.bodyPose(scene.a.bodies[1]).p;
  EXPECT_NEAR(texts[0]->pose.position.z, torso.z() + 0.35, 1e-9);
  EXPECT_NEAR(texts[0]->pose.position.x, torso.x(), 1e-9);
  // The ragdoll gone from the scene: one DELETE, then nothing.
  viz.setScene(scene.world, {scene.views()[1]}, scene.ground);
  EXPECT_EQ(viz.injuryTextCount(), 0u);
  texts = inNs(viz.update(scene.world, ros::Time(2), 0.0), "injury");
  ASSERT_EQ(texts.size(), 1u);
  EXPECT_EQ(texts[0]->action, Marker::DELETE);
  EXPECT_TRUE(inNs(viz.update(scene.world, ros::Time(3), 0.0), "injury").empty());
}
