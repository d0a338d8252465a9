// Settings changed on a live World: SolverSettings (World::setSolverSettings), materials
// (setMaterials, setShapeMaterial) and the internal tuning switches. Nothing is rebuilt: a
// sleeping island stays asleep and kept contacts take new coefficients at once.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"
#include "world_tuning.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {
constexpr double kDt = 1.0 / 240.0;

bool sameBits(const Vec3& a, const Vec3& b) { return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0; }
}  // namespace

TEST(SolverSettings, RangesAreCheckedAndNothingChanges) {
  EXPECT_EQ(solverSettingsError(SolverSettings()), "");
  World w;
  SolverSettings bad;
  bad.substeps = 0;
  EXPECT_NE(solverSettingsError(bad).find("substeps"), std::string::npos);
  EXPECT_THROW(w.setSolverSettings(bad), std::invalid_argument);
  EXPECT_EQ(w.def().solver.substeps, SolverSettings().substeps);
  bad = SolverSettings();
  bad.joint_hertz = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(w.setSolverSettings(bad), std::invalid_argument);
  EXPECT_EQ(w.def().solver.joint_hertz, SolverSettings().joint_hertz);
  SolverSettings good;
  good.substeps = 5;
  w.setSolverSettings(good);
  EXPECT_EQ(w.def().solver.substeps, 5);
}

TEST(SolverSettings, SettingTheSameStepsBitForBit) {
  World a, b;
  BodyId ba, bb;
  for (World* w : {&a, &b}) {
    addGround(*w);
    const BodyId x = addBox(*w, Vec3(0.2, 0.1, 0.1), 1.0, Vec3(0, 0, 0.3));
    w->setBodyState(x, Transform(Vec3(0, 0, 0.3), Quat(Eigen::AngleAxisd(0.3, Vec3::UnitY()))),
                    Vec3(0.5, 0, 0), Vec3(0, 1, 0));
    (w == &a ? ba : bb) = x;
  }
  for (int i = 0; i < 300; ++i) {
    a.setSolverSettings(a.def().solver);
    a.step(kDt);
    b.step(kDt);
    ASSERT_TRUE(sameBits(a.comPosition(ba), b.comPosition(bb))) << "step " << i;
    ASSERT_TRUE(sameBits(a.bodyState(ba).angular_velocity, b.bodyState(bb).angular_velocity));
  }
}

TEST(SolverSettings, SubstepChangeKeepsSleepAndWarmStarts) {
  WorldDef def;
  def.sleep.rest_substeps = 0;  // every awake island on the full substeps
  World w(def);
  addGround(w);
  const Vec3 half(0.2, 0.2, 0.2);
  const BodyId sleeper = addBox(w, half, 1.0, Vec3(0, 0, 0.2));
  for (int i = 0; i < 2000 && w.isAwake(sleeper); ++i) w.step(kDt);
  ASSERT_FALSE(w.isAwake(sleeper));
  const BodyId rester = addBox(w, half, 2.0, Vec3(5, 0, 0.2));
  for (int i = 0; i < 60; ++i) w.step(kDt);  // rests on the ground, awake (sleeps after 0.5 s)
  ASSERT_TRUE(w.isAwake(rester));
  const auto supportOf = [&](BodyId b) {
    double sum = 0.0;
    for (const ContactInfo& c : w.contacts())
      if (c.body_a == b || c.body_b == b) sum += c.normal_impulse;
    return sum;
  };
  const double sleeper_support = supportOf(sleeper);
  ASSERT_GT(sleeper_support, 0.0);
  SolverSettings s = w.def().solver;
  s.substeps = 4;
  s.contact_hertz = 240.0;
  w.setSolverSettings(s);
  w.step(kDt);
  EXPECT_FALSE(w.isAwake(sleeper));
  EXPECT_EQ(supportOf(sleeper), sleeper_support);  // its warm start is untouched
  // The rester's impulses are per substep: after the change they hold it on h = dt / 4.
  EXPECT_NEAR(supportOf(rester), 2.0 * 9.81 * kDt / 4, 0.05 * 2.0 * 9.81 * kDt / 4);
  EXPECT_LT(w.bodyState(rester).linear_velocity.norm(), 1e-3);
}

namespace {
// A box sliding along x on the ground; returns its speed after `steps` more steps.
struct Slide {
  World w;
  BodyId box;
  explicit Slide(const WorldDef& def, const Material& ground_m, const Material& box_m) : w(def) {
    addGround(w, ground_m);
    box = addBox(w, Vec3(0.2, 0.2, 0.1), 1.0, Vec3(0, 0, 0.1), box_m);
    for (int i = 0; i < 60; ++i) w.step(kDt);  // settled on the ground
    w.setBodyState(box, w.bodyPose(box), Vec3(2.0, 0, 0), Vec3::Zero());
    for (int i = 0; i < 10; ++i) w.step(kDt);  // sliding, its contacts kept from step to step
  }
  double speedAfter(int steps) {
    for (int i = 0; i < steps; ++i) w.step(kDt);
    return w.bodyState(box).linear_velocity.x();
  }
};
}  // namespace

TEST(Materials, ShapeMaterialActsOnKeptContacts) {
  Material rough;
  rough.static_friction = rough.kinetic_friction = 0.5;
  Slide s(WorldDef(), rough, rough);
  const double v0 = s.speedAfter(0);
  EXPECT_LT(s.speedAfter(10), v0 - 0.1);  // rough: 0.5 g decelerates ~0.2 m/s in 10 steps
  Material ice;
  ice.static_friction = ice.kinetic_friction = 0.0;
  s.w.setShapeMaterial(s.box, 0, ice);
  EXPECT_EQ(s.w.bodyShapes(s.box)[0].material.kinetic_friction, 0.0);
  const double v1 = s.speedAfter(1);
  EXPECT_NEAR(s.speedAfter(20), v1, 1e-6);  // frictionless from the first step on
  Material bad;
  bad.kinetic_friction = -1;
  EXPECT_THROW(s.w.setShapeMaterial(s.box, 0, bad), std::invalid_argument);
  EXPECT_THROW(s.w.setShapeMaterial(s.box, 1, ice), std::out_of_range);
}

TEST(Materials, TableChangeActsOnKeptContacts) {
  WorldDef def;
  Material ground_m, box_m;
  ground_m.id = def.materials.add("ground", Material());
  box_m.id = def.materials.add("box", Material());
  Material pair;
  pair.static_friction = pair.kinetic_friction = 0.5;
  def.materials.setPair(ground_m.id, box_m.id, pair);
  Slide s(def, ground_m, box_m);
  const double v0 = s.speedAfter(0);
  EXPECT_LT(s.speedAfter(10), v0 - 0.1);
  MaterialTable table = s.w.def().materials;
  pair.static_friction = pair.kinetic_friction = 0.0;
  table.setPair(ground_m.id, box_m.id, pair);
  s.w.setMaterials(table);
  const double v1 = s.speedAfter(1);
  EXPECT_NEAR(s.speedAfter(20), v1, 1e-6);
  MaterialTable bad = table;
  Material worse;
  worse.restitution = 2.0;
  bad.add("worse", worse);
  EXPECT_THROW(s.w.setMaterials(bad), std::invalid_argument);
  EXPECT_EQ(s.w.def().materials.find("worse"), -1);
}

TEST(WorldTuningRanges, CacheDistanceIsCheckedAndNamed) {
  World w;
  WorldTuning t;
  EXPECT_EQ(worldTuningError(t), "");
  t.manifold_cache_distance = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(worldTuningError(t).find("manifold_cache_distance"), std::string::npos);
  EXPECT_THROW(WorldInternals::setTuning(w, t), std::invalid_argument);
  EXPECT_EQ(WorldInternals::tuning(w).manifold_cache_distance, kManifoldCacheDistance);
  t.manifold_cache_distance = 0.0;  // off
  WorldInternals::setTuning(w, t);
  EXPECT_EQ(WorldInternals::tuning(w).manifold_cache_distance, 0.0);
}

TEST(WorldTuningRanges, RangeReserveIsCheckedAndNamed) {
  WorldTuning t;
  for (const int ok : {-1, 0, 1}) {
    t.range_reserve = ok;
    EXPECT_EQ(worldTuningError(t), "") << ok;
  }
  for (const int bad : {-2, 2}) {
    t.range_reserve = bad;
    EXPECT_NE(worldTuningError(t).find("range_reserve"), std::string::npos) << bad;
  }
}
