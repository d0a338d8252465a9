// The shipped worlds (worlds/*.world) loaded into a Scene with config/materials.yaml, against
// closed forms: a box on the 20 degree concrete ramp stops, holds or slides as the friction of
// its material pair says; the bundled ragdoll pushed off the top of the stairs ends lower
// without sinking into a step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "ragdoll_sim/drop_check.hpp"
#include "ragdoll_sim/material_file.hpp"
#include "ragdoll_sim/scene.hpp"
#include "ragdoll_sim/urdf_loader.hpp"
#include "ragdoll_sim/world_file.hpp"

using namespace ragdoll_sim;

namespace {

const double kPi = 3.14159265358979323846;
const double kTheta = 20.0 * kPi / 180.0;  // the ramp's slope, as worlds/ramp.world says

std::string sourceFile(const std::string& relative) {
  return std::string(RAGDOLL_SIM_SOURCE_DIR) + "/" + relative;
}

WorldFileDef shippedWorld(const std::string& name) {
  const WorldLoadResult r = loadWorldFile(sourceFile("worlds/" + name + ".world"));
  EXPECT_TRUE(r.ok) << r.error;
  return r.def;
}

MaterialFileResult materials() {
  MaterialFileResult r = loadMaterialFile(sourceFile("config/materials.yaml"));
  EXPECT_TRUE(r.ok) << r.error;
  return r;
}

// The pair's coefficients as the table gives them.
Material pair(const MaterialTable& t, const std::string& a, const std::string& b) {
  EXPECT_GT(t.find(a), 0) << a;
  EXPECT_GT(t.find(b), 0) << b;
  return t.resolve(t.material(t.find(a)), t.material(t.find(b)));
}

WorldCollisionDef* findCollision(WorldFileDef& d, const std::string& model, const std::string& name) {
  for (WorldModelDef& m : d.models)
    if (m.name == model)
      for (WorldLinkDef& l : m.links)
        for (WorldCollisionDef& c : l.collisions)
          if (c.name == name) return &c;
  return nullptr;
}

// The ramp's top face, from the loaded file: its frame (x downhill, z the normal) at the middle.
struct Slope {
  Transform top;
  Vec3 normal() const { return top.q * Vec3::UnitZ(); }
  Vec3 down() const { return top.q * Vec3::UnitX(); }
};

Slope slopeOf(const WorldFileDef& d) {
  for (const WorldModelDef& m : d.models)
    if (m.name == "ramp") {
      const WorldLinkDef& l = m.links.at(0);
      const WorldCollisionDef& c = l.collisions.at(0);
      const Transform w = l.pose * c.shape.local;
      return {w * Transform(Vec3(0, 0, c.shape.geometry.half_extents.z()), Quat::Identity())};
    }
  ADD_FAILURE() << "no model 'ramp'";
  return {};
}

const Vec3 kBoxHalf(0.15, 0.15, 0.05);

RagdollDef boxDef(const std::string& material) {
  RagdollDef d;
  d.name = "box";
  LinkDef l;
  l.name = "box";
  l.mass = 2.0;
  const Vec3 e = 2 * kBoxHalf;
  l.inertia = Vec3(e.y() * e.y() + e.z() * e.z(), e.x() * e.x() + e.z() * e.z(),
                   e.x() * e.x() + e.y() * e.y()).asDiagonal() * (l.mass / 12);
  ShapeDef s;
  s.geometry = Geometry::box(kBoxHalf);
  l.shapes = {s};
  l.material = material;
  d.links = {l};
  return d;
}

struct Slide {
  double distance = 0;  // m along the slope, downhill positive
  double seconds = 0;   // sim time until it was still (or the run's end)
  bool still = false;
  bool finite = true;
};

// A box of `box_material` lying on the shipped ramp (its surface `ramp_material`, "" as the file
// says), `s0` m downhill of the top face's middle, launched along the slope at `speed` (> 0
// downhill); run for `seconds` or, with until_still, until it is still.
Slide slide(const std::string& box_material, const std::string& ramp_material, double s0, double speed,
            double seconds, bool until_still) {
  WorldFileDef world = shippedWorld("ramp");
  if (!ramp_material.empty()) findCollision(world, "ramp", "slope")->material = ramp_material;
  const Slope slope = slopeOf(world);
  SceneDef sd;
  sd.world.materials = materials().table;
  Scene scene(sd);
  std::string error;
  EXPECT_TRUE(scene.loadWorld(world, &error)) << error;
  SpawnDef spawn;
  spawn.name = "box";
  spawn.def = boxDef(box_material);
  spawn.pose = Transform(slope.top.p + slope.down() * s0 + slope.normal() * kBoxHalf.z(), slope.top.q);
  EXPECT_EQ(scene.addObject(spawn, &error), SpawnResult::Added) << error;
  EXPECT_TRUE(scene.start(&error)) << error;
  const int k = scene.find("box");
  EXPECT_GE(k, 0);
  Slide out;
  if (k < 0) return out;
  scene.setRagdollState(k, spawn.pose, slope.down() * speed, Vec3::Zero());
  const Vec3 p0 = scene.linkState(k, 0).pose.p;
  double still_for = 0;
  while (scene.time() < seconds) {
    scene.step();
    const LinkState st = scene.linkState(k, 0);
    out.finite = st.pose.p.allFinite() && st.linear_velocity.allFinite();
    if (!out.finite) break;
    out.distance = (st.pose.p - p0).dot(slope.down());
    out.seconds = scene.time();
    still_for = st.linear_velocity.norm() < 1e-3 ? still_for + scene.dt() : 0.0;
    if (until_still && still_for >= 0.2) {
      out.still = true;
      break;
    }
  }
  return out;
}

double gravity() { return -shippedWorld("ramp").gravity.z(); }

}  // namespace

// Every collision of every shipped world names a surface of the table (a typo would fall back
// to the default surface with a WARN).
TEST(ShippedWorlds, EveryCollisionNamesATableMaterial) {
  const MaterialTable table = materials().table;
  for (const char* name : {"stairs", "ramp", "playground"}) {
    const WorldFileDef world = shippedWorld(name);
    int collisions = 0;
    for (const WorldModelDef& m : world.models)
      for (const WorldLinkDef& l : m.links)
        for (const WorldCollisionDef& c : l.collisions) {
          ++collisions;
          EXPECT_GT(table.find(c.material), 0)
              << name << " " << m.name << " " << c.name << ": '" << c.material << "'";
        }
    EXPECT_GT(collisions, 0) << name;
  }
}

TEST(ShippedWorlds, RampIsTwentyDegreesOfConcrete) {
  WorldFileDef world = shippedWorld("ramp");
  const Slope s = slopeOf(world);
  EXPECT_NEAR(std::acos(s.normal().z()), kTheta, 1e-9);
  EXPECT_NEAR(s.down().z(), -std::sin(kTheta), 1e-9);
  // Its top face passes through the line x = 0, z = 2.5 sin 20 (along y), as the file says.
  EXPECT_NEAR(s.top.p.x(), 0.0, 1e-6);
  EXPECT_NEAR(s.top.p.z(), 2.5 * std::sin(kTheta), 1e-6);
  ASSERT_NE(findCollision(world, "ramp", "slope"), nullptr);
  EXPECT_EQ(findCollision(world, "ramp", "slope")->material, "concrete");
}

// Launched downhill with v, a box whose kinetic friction beats the slope stops after
// v^2 / (2 g (mu_k cos theta - sin theta)).
TEST(ShippedWorlds, RampBoxLaunchedDownStopsAtTheClosedForm) {
  const Material m = pair(materials().table, "wood", "concrete");
  EXPECT_NEAR(m.kinetic_friction, 0.62, 1e-12);  // the table: wood-concrete 0.62 / -
  const double v = 2.5, g = gravity();
  const double expected = v * v / (2 * g * (m.kinetic_friction * std::cos(kTheta) - std::sin(kTheta)));
  const Slide s = slide("wood", "", -2.0, v, 6.0, true);
  std::printf("ramp down: wood on concrete, v=%.2f m/s: %.4f m (closed form %.4f m, %+.2f %%) in %.2f s\n", v,
              s.distance, expected, 100 * (s.distance / expected - 1), s.seconds);
  EXPECT_TRUE(s.finite);
  EXPECT_TRUE(s.still);
  EXPECT_NEAR(s.distance, expected, 0.03 * expected);
}

// Launched uphill with v: it stops after v^2 / (2 g (mu_k cos theta + sin theta)) and stays.
TEST(ShippedWorlds, RampBoxLaunchedUpStopsAtTheClosedForm) {
  const Material m = pair(materials().table, "wood", "concrete");
  const double v = 3.0, g = gravity();
  const double expected = v * v / (2 * g * (m.kinetic_friction * std::cos(kTheta) + std::sin(kTheta)));
  const Slide s = slide("wood", "", 1.5, -v, 6.0, true);
  std::printf("ramp up: wood on concrete, v=%.2f m/s: %.4f m (closed form %.4f m, %+.2f %%) in %.2f s\n", v,
              -s.distance, expected, 100 * (-s.distance / expected - 1), s.seconds);
  EXPECT_TRUE(s.finite);
  EXPECT_TRUE(s.still);
  EXPECT_NEAR(-s.distance, expected, 0.03 * expected);
}

// Released at rest, tan theta < mu_s: it holds.
TEST(ShippedWorlds, RampBoxAtRestHoldsWhenStaticFrictionBeatsTheSlope) {
  const Material m = pair(materials().table, "wood", "concrete");
  ASSERT_GT(m.static_friction, std::tan(kTheta));
  const Slide s = slide("wood", "", 0.0, 0.0, 3.0, false);
  std::printf("ramp rest: wood on concrete (mu_s %.2f > tan 20 = %.3f): moved %.3f mm in %.1f s\n",
              m.static_friction, std::tan(kTheta), 1e3 * s.distance, s.seconds);
  EXPECT_TRUE(s.finite);
  EXPECT_LT(std::abs(s.distance), 1e-3);
}

// Released at rest on a low-friction pair (the ramp's surface made teflon, a steel box: the
// table's steel-teflon 0.04): it slides with a = g (sin theta - mu_k cos theta).
TEST(ShippedWorlds, RampBoxAtRestSlidesWithTheClosedFormAcceleration) {
  const Material m = pair(materials().table, "steel", "teflon");
  ASSERT_LT(m.static_friction, std::tan(kTheta));
  const double g = gravity(), t = 1.0;
  const double a = g * (std::sin(kTheta) - m.kinetic_friction * std::cos(kTheta));
  const Slide s = slide("steel", "teflon", -2.0, 0.0, t, false);
  const double expected = 0.5 * a * s.seconds * s.seconds;
  std::printf("ramp slide: steel on teflon (mu_k %.2f): %.4f m in %.3f s (closed form %.4f m, %+.2f %%)\n",
              m.kinetic_friction, s.distance, s.seconds, expected, 100 * (s.distance / expected - 1));
  EXPECT_TRUE(s.finite);
  EXPECT_NEAR(s.distance, expected, 0.03 * expected);
}

// The bundled ragdoll, dropped on the top landing of the stairs and pushed towards the steps,
// tumbles down: it ends on a lower step than it started, no shape sinks into a step by more
// than 5 mm at any step, nothing goes non-finite.
TEST(ShippedWorlds, RagdollPushedDownTheStairsEndsLower) {
  const WorldFileDef world = shippedWorld("stairs");
  const MaterialFileResult mat = materials();
  const UrdfLoadResult u = loadUrdfFile(sourceFile("urdf/ragdoll.urdf"));
  ASSERT_TRUE(u.ok) << u.error;

  // The tread under (x, y): the top of the highest step box there (0: the ground).
  const auto treadUnder = [&](double x, double y) {
    double top = 0;
    for (const WorldModelDef& m : world.models)
      if (m.name == "stairs")
        for (const WorldCollisionDef& c : m.links.at(0).collisions) {
          const Vec3 p = (m.links[0].pose * c.shape.local).p, h = c.shape.geometry.half_extents;
          if (std::abs(x - p.x()) <= h.x() && std::abs(y - p.y()) <= h.y())
            top = std::max(top, p.z() + h.z());
        }
    return top;
  };
  const double rise = 0.18;
  const double landing = treadUnder(0, 0);
  ASSERT_NEAR(landing, 8 * rise, 1e-9);

  SceneDef sd;
  sd.world.materials = mat.table;
  sd.link_materials = mat.link_materials;
  Scene scene(sd);
  std::string error;
  ASSERT_TRUE(scene.loadWorld(world, &error)) << error;
  SpawnDef spawn;
  spawn.name = "ragdoll";
  spawn.def = u.def;
  spawn.pose = Transform(Vec3(0, 0, landing + 0.02 - restLowestPoint(u.def)), Quat::Identity());
  ASSERT_EQ(scene.addRagdoll(spawn, &error), SpawnResult::Added) << error;
  ASSERT_TRUE(scene.start(&error)) << error;
  const int k = scene.find("ragdoll");
  int stairs = -1;
  for (size_t i = 0; i < scene.staticObjectCount(); ++i)
    if (scene.staticObjectName(int(i)) == "stairs") stairs = int(i);
  ASSERT_GE(stairs, 0);
  std::vector<char> is_step(scene.world().bodyCount(), 0), is_ragdoll(scene.world().bodyCount(), 0);
  for (BodyId b : scene.staticObjectBodies(stairs)) is_step.at(b.index) = 1;
  for (BodyId b : scene.bodies(k).bodies) is_ragdoll.at(b.index) = 1;

  // The push: the whole body moving towards the steps at 2 m/s.
  scene.setRagdollState(k, spawn.pose, Vec3(2.0, 0, 0), Vec3::Zero());
  const int start_level = int(std::lround(treadUnder(0, 0) / rise));
  double max_penetration = 0;
  bool finite = true;
  const int root = u.def.root;
  while (scene.time() < 8.0 && finite) {
    scene.step();
    for (BodyId b : scene.bodies(k).bodies) {
      const BodyState st = scene.world().bodyState(b);
      finite = finite && st.pose.p.allFinite() && st.pose.q.coeffs().allFinite() &&
               st.linear_velocity.allFinite() && st.angular_velocity.allFinite();
    }
    for (const ContactInfo& c : scene.world().contacts())
      if ((is_step[c.body_a.index] && is_ragdoll[c.body_b.index]) ||
          (is_step[c.body_b.index] && is_ragdoll[c.body_a.index]))
        max_penetration = std::max(max_penetration, -c.separation);
  }
  const Vec3 pelvis = scene.linkState(k, root).pose.p;
  const int end_level = int(std::lround(treadUnder(pelvis.x(), pelvis.y()) / rise));
  std::printf("stairs: pelvis from step %d (x=0) to step %d (x=%.2f y=%.2f z=%.2f) in %.1f s, "
              "max penetration into a step %.2f mm, finite %d\n",
              start_level, end_level, pelvis.x(), pelvis.y(), pelvis.z(), scene.time(), 1e3 * max_penetration,
              finite ? 1 : 0);
  EXPECT_TRUE(finite);
  EXPECT_LT(end_level, start_level);
  EXPECT_LE(max_penetration, 0.005);
}

// config/materials.yaml's link_materials on the bundled ragdoll: rubber soles, a leather jacket,
// so a foot on the concrete ramp and a sleeve on steel take the table's two different rows.
TEST(ShippedWorlds, BundledRagdollHasRubberSolesAndLeatherElsewhere) {
  const MaterialFileResult mat = materials();
  const UrdfLoadResult u = loadUrdfFile(sourceFile("urdf/ragdoll.urdf"));
  ASSERT_TRUE(u.ok) << u.error;
  SceneDef sd;
  sd.world.materials = mat.table;
  sd.link_materials = mat.link_materials;
  Scene scene(sd);
  std::string error;
  ASSERT_TRUE(scene.loadWorld(shippedWorld("ramp"), &error)) << error;
  SpawnDef spawn;
  spawn.name = "ragdoll";
  spawn.def = u.def;
  spawn.pose = Transform(Vec3(-3, 0, 1.5), Quat::Identity());
  ASSERT_EQ(scene.addRagdoll(spawn, &error), SpawnResult::Added) << error;
  ASSERT_TRUE(scene.start(&error)) << error;
  const MaterialTable& table = scene.world().def().materials;
  const int rubber = table.find("rubber"), leather = table.find("leather");
  ASSERT_GT(rubber, 0);
  ASSERT_GT(leather, 0);
  const int k = scene.find("ragdoll");
  int feet = 0, others = 0;
  for (size_t l = 0; l < u.def.links.size(); ++l) {
    const std::string& name = u.def.links[l].name;
    const bool foot = name == "foot_l" || name == "foot_r";
    for (const ShapeDef& s : scene.world().bodyShapes(scene.bodies(k).bodies[l])) {
      EXPECT_EQ(s.material.id, foot ? rubber : leather) << name;
      ++(foot ? feet : others);
    }
  }
  EXPECT_GT(feet, 0);
  EXPECT_GT(others, 0);
  // The ramp's concrete against each: the rubber-concrete row and, for leather, the combine rule.
  const int concrete = table.find("concrete"), steel = table.find("steel");
  ASSERT_GT(concrete, 0);
  ASSERT_GT(steel, 0);
  EXPECT_DOUBLE_EQ(table.resolve(table.material(rubber), table.material(concrete)).static_friction, 1.0);
  EXPECT_DOUBLE_EQ(table.resolve(table.material(rubber), table.material(concrete)).kinetic_friction, 0.725);
  EXPECT_DOUBLE_EQ(table.resolve(table.material(leather), table.material(steel)).static_friction, 0.4);
  EXPECT_DOUBLE_EQ(table.resolve(table.material(leather), table.material(steel)).kinetic_friction, 0.2);
}
