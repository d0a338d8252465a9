// FallRecorder: a box dropped on the ground (peak contact force against m g, rest after the
// impact), the bundled ragdoll lying on its back, front and side, joints that break, a body
// that goes non-finite, the angle conventions and the refusals; runFall's push and its refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>

#include "object_models.hpp"
#include "ragdoll_sim/fall_record.hpp"
#include "ragdoll_sim/fall_run.hpp"
#include "ragdoll_sim/scene.hpp"

using namespace ragdoll_sim;

namespace {

constexpr double kPi = 3.14159265358979323846;

// A 2 kg box (0.2 m cube) as a ragdoll, its bottom `height` above the ground.
SpawnDef droppedBox(double height) {
  SpawnDef s;
  s.name = "box";
  s.def = test::boxModel(Vec3(0.1, 0.1, 0.1), 2.0);
  s.pose = Transform(Vec3(0, 0, 0.1 + height), Quat::Identity());
  return s;
}

SpawnDef bundled(const Transform& pose) {
  SpawnDef s;
  s.name = "r";
  s.def = test::bundledRagdoll();
  s.pose = pose;
  return s;
}

void startScene(Scene& scene, SpawnDef spawn) {
  std::string e;
  ASSERT_EQ(scene.addRagdoll(std::move(spawn), &e), SpawnResult::Added) << e;
  ASSERT_TRUE(scene.start(&e)) << e;
}

}  // namespace

// Dropped from 0.5 m: it lands at sqrt(2 h / g); the ground then holds at least its weight
// (the impact more), and it rests after the landing and before the end.
TEST(FallRecord, DroppedBoxPeakForceAndRest) {
  Scene scene{SceneDef()};
  startScene(scene, droppedBox(0.5));
  FallRecorder rec(scene, "box");
  rec.run(scene, 1500);
  const FallRecord r = rec.record(scene);
  const double g = std::abs(scene.world().def().gravity.z());
  const double landing = std::sqrt(2 * 0.5 / g);
  ASSERT_EQ(r.links.size(), 1u);
  EXPECT_EQ(r.links[0], "body");
  EXPECT_GE(r.peak_contact_force[0], 2.0 * g * 0.999);
  EXPECT_GT(r.peak_contact_force[0], 2.0 * 2.0 * g) << "the impact exceeds the weight";
  EXPECT_GT(r.time_to_rest, landing);
  EXPECT_LT(r.time_to_rest, 1.5 - FallRecordDef().min_rest);
  EXPECT_NEAR(r.duration, 1.5, 1e-9);
  EXPECT_EQ(r.samples, 1500);
  EXPECT_FALSE(r.nan);
  EXPECT_TRUE(r.broken_joints.empty());
  EXPECT_NEAR(r.root_position.z(), 0.1, 0.01);
  EXPECT_NEAR(r.roll, 0.0, 1e-3);
  EXPECT_NEAR(r.pitch, 0.0, 1e-3);
  EXPECT_EQ(r.rest, RestClass::Upright);  // no torso link: the root's axes
  EXPECT_EQ(r.head_link, "");
  EXPECT_EQ(r.head_peak_g, 0.0);
}

// Still falling at the end: no time to rest; a rest shorter than min_rest is none either.
TEST(FallRecord, NoRestWhileFalling) {
  Scene scene{SceneDef()};
  startScene(scene, droppedBox(5.0));
  FallRecorder rec(scene, "");
  rec.run(scene, 300);
  EXPECT_TRUE(std::isnan(rec.record(scene).time_to_rest));
  FallRecordDef long_rest;
  long_rest.min_rest = 10.0;
  Scene resting{SceneDef()};
  startScene(resting, droppedBox(0.0));
  FallRecorder strict(resting, "box", long_rest);
  strict.run(resting, 500);
  EXPECT_TRUE(std::isnan(strict.record(resting).time_to_rest));
}

// The bundled ragdoll laid on the ground on its back (pitch -90 deg: the chest's +x up), its
// front, its side: classed by the torso's axes; the head's metrics come from the injury record.
TEST(FallRecord, BundledRagdollRestClasses) {
  struct Case {
    double roll, pitch;
    RestClass expect;
  };
  for (const Case c : {Case{0, -kPi / 2, RestClass::Supine}, Case{0, kPi / 2, RestClass::Prone},
                       Case{kPi / 2, 0, RestClass::Side}}) {
    Scene scene{SceneDef()};
    startScene(scene, bundled(Transform(Vec3(0, 0, 0.3), quatFromRpy(c.roll, c.pitch, 0.3))));
    FallRecorder rec(scene, "r");
    rec.run(scene, 800);
    const FallRecord r = rec.record(scene);
    EXPECT_EQ(restClassName(r.rest), std::string(restClassName(c.expect)))
        << "roll " << c.roll << " pitch " << c.pitch;
    EXPECT_EQ(r.head_link, "head");
    EXPECT_GT(r.head_peak_g, 0.0);
    EXPECT_FALSE(r.nan);
    EXPECT_LT(r.root_position.z(), 0.3);
    EXPECT_EQ(r.links.size(), scene.def(0).links.size());
  }
}

// Joints that cannot hold the limbs' weight break once the feet land (in free fall no joint
// carries anything): each reported once, by its RagdollDef name.
TEST(FallRecord, BrokenJointsReported) {
  SceneDef def;
  def.joint_defaults.break_force = 1.0;  // N
  Scene scene{def};
  startScene(scene, bundled(Transform(Vec3(0, 0, 1.2), Quat::Identity())));
  FallRecorder rec(scene, "r");
  rec.run(scene, 300);
  const FallRecord r = rec.record(scene);
  ASSERT_FALSE(r.broken_joints.empty());
  std::set<std::string> names;
  for (const RagdollJointDef& j : scene.def(0).joints) names.insert(j.name);
  std::set<std::string> seen;
  for (const std::string& j : r.broken_joints) {
    EXPECT_TRUE(names.count(j)) << j;
    EXPECT_TRUE(seen.insert(j).second) << j << " reported twice";
  }
  Scene whole{SceneDef()};
  startScene(whole, bundled(Transform(Vec3(0, 0, 1.2), Quat::Identity())));
  FallRecorder intact(whole, "r");
  intact.run(whole, 300);
  EXPECT_TRUE(intact.record(whole).broken_joints.empty());
}

// A body given a NaN velocity: the World resets it (a body fault) and the record is flagged.
TEST(FallRecord, NonFiniteBodyFlagged) {
  Scene scene{SceneDef()};
  startScene(scene, droppedBox(0.2));
  FallRecorder rec(scene, "box");
  rec.run(scene, 20);
  EXPECT_FALSE(rec.record(scene).nan);
  const BodyId b = scene.bodies(0).bodies[0];
  const double nan = std::numeric_limits<double>::quiet_NaN();
  scene.world().setBodyState(b, scene.world().bodyPose(b), Vec3(nan, 0, 0), Vec3::Zero());
  rec.run(scene, 20);
  const FallRecord r = rec.record(scene);
  EXPECT_TRUE(r.nan);
  EXPECT_EQ(r.body_faults, 1);
}

TEST(FallRecord, RpyRoundTripAndClasses) {
  for (const double roll : {-2.0, -0.3, 0.0, 1.1})
    for (const double pitch : {-1.2, 0.0, 0.4, 1.5})
      for (const double yaw : {-3.0, 0.0, 0.7, 2.9}) {
        const Vec3 rpy = rpyFromQuat(quatFromRpy(roll, pitch, yaw));
        EXPECT_NEAR(rpy.x(), roll, 1e-9);
        EXPECT_NEAR(rpy.y(), pitch, 1e-9);
        EXPECT_NEAR(rpy.z(), yaw, 1e-9);
      }
  const FallRecordDef d;
  EXPECT_EQ(classifyRest(quatFromRpy(0, 0, 1.0), d), RestClass::Upright);
  EXPECT_EQ(classifyRest(quatFromRpy(0.4, 0, 0), d), RestClass::Upright);  // 23 deg tilt
  EXPECT_EQ(classifyRest(quatFromRpy(0, -kPi / 2, 2.0), d), RestClass::Supine);
  EXPECT_EQ(classifyRest(quatFromRpy(0, kPi / 2, -1.0), d), RestClass::Prone);
  EXPECT_EQ(classifyRest(quatFromRpy(-kPi / 2, 0, 0), d), RestClass::Side);
  EXPECT_EQ(classifyRest(quatFromRpy(kPi, 0, 0), d), RestClass::Other);   // head down
  EXPECT_EQ(classifyRest(quatFromRpy(0, 0.65, 0), d), RestClass::Other);  // 37 deg: between
  EXPECT_EQ(classifyRest(quatFromRpy(0, 0.9, 0), d), RestClass::Prone);   // 52 deg: lying
}

TEST(FallRecord, RefusalsNameTheProblem) {
  Scene scene{SceneDef()};
  startScene(scene, droppedBox(0.0));
  auto message = [&](const std::string& ragdoll, const FallRecordDef& d) -> std::string {
    try {
      FallRecorder r(scene, ragdoll, d);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_NE(message("nobody", {}).find("'nobody'"), std::string::npos);
  FallRecordDef d;
  d.torso_link = "chest";
  EXPECT_NE(message("box", d).find("'chest' (torso_link)"), std::string::npos);
  d = FallRecordDef();
  d.rest_speed = -1.0;
  EXPECT_NE(message("box", d).find("rest_speed"), std::string::npos);
  d = FallRecordDef();
  d.upright_angle = 2.0;
  EXPECT_NE(message("box", d).find("upright_angle"), std::string::npos);
  EXPECT_EQ(message("box", {}), "");
}

// runFall: a 2 kg box resting on the ground pushed along +x slides that way and stops; a push
// on an unknown link, or above the scene's max_impulse, is refused naming it.
TEST(FallRecord, RunFallPushAndRefusals) {
  FallRunDef d;
  d.model = std::make_shared<const RagdollDef>(test::boxModel(Vec3(0.1, 0.1, 0.1), 2.0));
  d.name = "crate";
  d.pose = Transform(Vec3(0, 0, 0.1), Quat::Identity());
  d.push_link = "body";
  d.push_impulse = Vec3(4.0, 0, 0);  // 2 m/s
  d.steps = 1000;
  const FallRecord r = runFall(d);
  EXPECT_EQ(r.ragdoll, "crate");
  EXPECT_GT(r.root_position.x(), 0.05);
  EXPECT_GT(r.time_to_rest, 0.0);
  EXPECT_FALSE(r.nan);
  auto refusal = [](const FallRunDef& bad) -> std::string {
    try {
      runFall(bad);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  };
  FallRunDef bad = d;
  bad.push_link = "lid";
  EXPECT_NE(refusal(bad).find("no link 'lid'"), std::string::npos) << refusal(bad);
  bad = d;
  bad.push_impulse = Vec3(2000.0, 0, 0);
  EXPECT_NE(refusal(bad).find("push: "), std::string::npos) << refusal(bad);
  EXPECT_NE(refusal(bad).find("max_impulse"), std::string::npos) << refusal(bad);
  bad = d;
  bad.model = nullptr;
  EXPECT_NE(refusal(bad).find("no model"), std::string::npos);
}
