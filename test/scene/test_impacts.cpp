// The Scene's reports by name (issue 57): bodies named as users name them, touching pairs, and
// impact events against closed forms (a drop from h hits at sqrt(2 g h); restitution e
// separates at e times that; the impulse of a ball is m v (1 + e)).
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "object_models.hpp"
#include "ragdoll_sim/scene.hpp"

using namespace ragdoll_sim;

namespace {

constexpr double kRadius = 0.1, kMass = 1.0;

RagdollDef ballModel() {
  RagdollDef def;
  def.name = "ball";
  LinkDef link;
  link.name = "ball";
  link.mass = kMass;
  link.inertia = Mat3::Identity() * (0.4 * kMass * kRadius * kRadius);
  link.shapes.push_back({Geometry::sphere(kRadius), Transform(), Material()});
  def.links.push_back(link);
  return def;
}

SpawnDef ball(const std::string& name, const Vec3& at) {
  SpawnDef s;
  s.name = name;
  s.def = ballModel();
  s.pose = Transform(at, Quat::Identity());
  return s;
}

SceneDef impactScene(double restitution) {
  SceneDef d;
  d.impacts.enabled = true;
  d.object_surface.restitution = restitution;  // the pair takes the larger (ground: 0)
  return d;
}

double gravity(const Scene& s) { return s.def().world.gravity.norm(); }

// Every event of `steps` steps.
std::vector<ImpactEvent> run(Scene& s, int steps) {
  std::vector<ImpactEvent> all;
  for (int i = 0; i < steps; ++i) {
    s.step();
    all.insert(all.end(), s.impacts().begin(), s.impacts().end());
  }
  return all;
}

void addOrFail(Scene& s, SpawnDef spawn) {
  std::string error;
  ASSERT_EQ(s.addObject(std::move(spawn), &error), SpawnResult::Added) << error;
}

}  // namespace

TEST(Impacts, BallDropHitsAtFreeFallSpeedOnce) {
  const double h = 1.0;
  Scene s(impactScene(0.0));
  addOrFail(s, ball("drop", Vec3(0, 0, h + kRadius)));
  std::string error;
  ASSERT_TRUE(s.start(&error)) << error;
  EXPECT_TRUE(s.world().contactImpulseTracking());
  const std::vector<ImpactEvent> events = run(s, 1000);  // lands at 0.45 s, then rests
  ASSERT_EQ(events.size(), 1u);
  const ImpactEvent& e = events[0];
  const double v = std::sqrt(2.0 * gravity(s) * h);
  EXPECT_NEAR(e.closing_speed, v, 0.01 * v);
  EXPECT_NEAR(e.impulse, kMass * v, 0.02 * kMass * v);  // e = 0: m v
  EXPECT_NEAR(e.time, std::sqrt(2.0 * h / gravity(s)), 0.005);
  EXPECT_EQ(e.ragdoll, "drop");
  EXPECT_EQ(e.link, "ball");
  EXPECT_EQ(e.other, "ground");
  EXPECT_NEAR(e.normal.z(), 1.0, 1e-6);  // from the ground into the ball
  EXPECT_NEAR(e.point.z(), 0.0, 0.01);
  EXPECT_GT(e.peak_force, e.impulse / s.dt());  // the impulse acts within one step
}

TEST(Impacts, RestitutionSeparatesAtEClosingWithImpulseMV1PlusE) {
  const double h = 1.0, e = 0.5;
  Scene s(impactScene(e));
  addOrFail(s, ball("drop", Vec3(0, 0, h + kRadius)));
  std::string error;
  ASSERT_TRUE(s.start(&error)) << error;
  const std::vector<ImpactEvent> events = run(s, 600);  // first landing at 0.45 s only
  ASSERT_EQ(events.size(), 1u);
  const double v = std::sqrt(2.0 * gravity(s) * h);
  EXPECT_NEAR(events[0].closing_speed, v, 0.01 * v);
  EXPECT_NEAR(events[0].separating_speed, e * events[0].closing_speed,
              0.02 * e * events[0].closing_speed);
  EXPECT_NEAR(events[0].impulse, kMass * v * (1.0 + e), 0.02 * kMass * v * (1.0 + e));
}

TEST(Impacts, RestingBallMakesNoEvents) {
  Scene s(impactScene(0.0));
  addOrFail(s, ball("rest", Vec3(0, 0, kRadius)));
  std::string error;
  ASSERT_TRUE(s.start(&error)) << error;
  EXPECT_TRUE(run(s, 300).empty());
  // It touches all along: the contact is there, only below the thresholds.
  std::vector<SceneContact> contacts;
  s.contacts(contacts);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_EQ(s.bodyName(contacts[0].a) + " " + s.bodyName(contacts[0].b) ==
                    "ground rest/ball" ||
                s.bodyName(contacts[0].a) + " " + s.bodyName(contacts[0].b) == "rest/ball ground",
            true);
}

TEST(Impacts, OffByDefaultAndTrackingFollows) {
  Scene s{SceneDef()};
  addOrFail(s, ball("drop", Vec3(0, 0, 0.5)));
  std::string error;
  ASSERT_TRUE(s.start(&error)) << error;
  EXPECT_FALSE(s.world().contactImpulseTracking());
  EXPECT_TRUE(run(s, 400).empty());  // it landed, nobody asked
  ImpactDef on;
  on.enabled = true;
  s.setImpacts(on);
  EXPECT_TRUE(s.world().contactImpulseTracking());
  ASSERT_TRUE(s.reset(&error)) << error;  // a new World keeps it
  EXPECT_TRUE(s.world().contactImpulseTracking());
  EXPECT_EQ(run(s, 400).size(), 1u);
  s.setImpacts(ImpactDef());
  EXPECT_FALSE(s.world().contactImpulseTracking());
  EXPECT_TRUE(s.impacts().empty());
  // Someone else's tracking stays on when impacts end.
  s.world().setContactImpulseTracking(true);
  s.setImpacts(on);
  s.setImpacts(ImpactDef());
  EXPECT_TRUE(s.world().contactImpulseTracking());
}

TEST(Impacts, RagdollHeadFirstDropHitsAtFreeFallSpeed) {
  const double h = 0.5;
  Scene s(impactScene(0.0));
  SpawnDef doll;
  doll.name = "doll";
  doll.def = test::bundledRagdoll();
  // Upside down: the head's sphere (top 0.76 m above the pelvis origin) is the lowest point.
  doll.pose = Transform(Vec3(0, 0, 0.76 + h), Quat(Eigen::AngleAxisd(M_PI, Vec3::UnitX())));
  std::string error;
  ASSERT_EQ(s.addRagdoll(doll, &error), SpawnResult::Added) << error;
  ASSERT_TRUE(s.start(&error)) << error;
  std::vector<ImpactEvent> first;
  for (int i = 0; i < 600 && first.empty(); ++i) {
    s.step();
    first = s.impacts();
  }
  ASSERT_FALSE(first.empty());
  EXPECT_EQ(first[0].ragdoll, "doll");
  EXPECT_EQ(first[0].link, "head");
  EXPECT_EQ(first[0].other, "ground");
  const double v = std::sqrt(2.0 * gravity(s) * h);
  EXPECT_NEAR(first[0].closing_speed, v, 0.01 * v);
}

TEST(Impacts, BallOnStaticObjectNamesItsLink) {
  Scene s(impactScene(0.0));
  addOrFail(s, test::boxObject("table", Vec3(0.5, 0.5, 0.1), 1.0, Vec3(0, 0, 0.1), true));
  addOrFail(s, ball("drop", Vec3(0, 0, 0.2 + 0.6 + kRadius)));
  std::string error;
  ASSERT_TRUE(s.start(&error)) << error;
  const std::vector<ImpactEvent> events = run(s, 500);
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].other, "table/body");
  EXPECT_EQ(events[0].ragdoll + "/" + events[0].link, "drop/ball");
  const double v = std::sqrt(2.0 * gravity(s) * 0.6);
  EXPECT_NEAR(events[0].closing_speed, v, 0.01 * v);
}

TEST(BodyNames, RefsAndNamesFollowRemovalAndReset) {
  Scene s{SceneDef()};
  addOrFail(s, ball("a", Vec3(0, 0, 1)));
  addOrFail(s, test::boxObject("wall", Vec3(0.1, 1, 1), 1.0, Vec3(3, 0, 1), true));
  addOrFail(s, ball("b", Vec3(1, 0, 1)));
  std::string error;
  ASSERT_TRUE(s.start(&error)) << error;
  SpawnDef doll;
  doll.name = "doll";
  doll.def = test::bundledRagdoll();
  doll.pose = Transform(Vec3(-2, 0, 1.2), Quat::Identity());
  ASSERT_EQ(s.addRagdoll(doll, &error), SpawnResult::Added) << error;

  auto nameOf = [&](BodyId id) { return s.bodyName(s.bodyRef(id)); };
  const int k = s.find("doll");
  const int head = s.findLink(k, "head");
  EXPECT_EQ(nameOf(s.bodies(k).bodies[size_t(head)]), "doll/head");
  EXPECT_EQ(nameOf(s.bodies(s.find("b")).bodies[0]), "b/ball");
  EXPECT_EQ(nameOf(s.staticObjectBodies(0)[0]), "wall/body");
  EXPECT_EQ(nameOf(s.ground()), "ground");
  const BodyRef g = s.bodyRef(s.ground());
  EXPECT_EQ(g.ragdoll, -1);
  EXPECT_EQ(g.static_object, -1);

  const BodyId old_a = s.bodies(s.find("a")).bodies[0];
  ASSERT_TRUE(s.remove("a", &error)) << error;
  // Indices moved: "b" and "doll" are one lower now.
  EXPECT_EQ(s.bodyRef(s.bodies(s.find("b")).bodies[0]).ragdoll, s.find("b"));
  EXPECT_EQ(nameOf(s.bodies(s.find("b")).bodies[0]), "b/ball");
  EXPECT_EQ(nameOf(s.bodies(s.find("doll")).bodies[size_t(head)]), "doll/head");
  EXPECT_EQ(s.bodyRef(old_a).ragdoll, -1);  // a removed body is nobody's

  ASSERT_TRUE(s.reset(&error)) << error;  // new World, new ids
  for (size_t r = 0; r < s.ragdollCount(); ++r)
    for (size_t l = 0; l < s.bodies(int(r)).bodies.size(); ++l) {
      const BodyRef ref = s.bodyRef(s.bodies(int(r)).bodies[l]);
      EXPECT_EQ(ref.ragdoll, int(r));
      EXPECT_EQ(ref.link, int(l));
    }
  EXPECT_EQ(nameOf(s.staticObjectBodies(0)[0]), "wall/body");
  EXPECT_EQ(nameOf(s.ground()), "ground");
  ASSERT_TRUE(s.remove("wall", &error)) << error;
  EXPECT_EQ(nameOf(s.bodies(s.find("doll")).bodies[size_t(head)]), "doll/head");
  EXPECT_EQ(s.bodyName(BodyRef{5, -1, 0}), "");  // no such ragdoll
}
