// Material pair table: listed pairs win in either order, others follow the combine rule, and
// the world uses the resolved coefficients (a listed low-friction pair slides farther).
#include <gtest/gtest.h>

#include "ragdoll_sim/world.hpp"

using namespace ragdoll_sim;

TEST(MaterialTable, ListedPairsAndCombineRules) {
  MaterialTable t;
  const int steel = t.add("steel", {0.74, 0.57, 0.6});
  const int ice = t.add("ice", {0.1, 0.03, 0.1});
  const int rubber = t.add("rubber", {1.0, 0.8, 0.5});
  t.setPair(steel, ice, {0.05, 0.02, 0.2});
  const Material a = t.resolve(t.material(ice), t.material(steel));
  EXPECT_DOUBLE_EQ(a.static_friction, 0.05);
  EXPECT_DOUBLE_EQ(a.kinetic_friction, 0.02);
  const Material b = t.resolve(t.material(steel), t.material(rubber));
  EXPECT_DOUBLE_EQ(b.static_friction, std::sqrt(0.74 * 1.0));
  EXPECT_DOUBLE_EQ(b.restitution, 0.6);
  EXPECT_DOUBLE_EQ(b.rolling_resistance, 0.0);
  Material soft = t.material(rubber);
  soft.rolling_resistance = 0.07;
  EXPECT_DOUBLE_EQ(t.resolve(t.material(steel), soft).rolling_resistance, 0.07);  // max
  t.friction_rule = CombineRule::Min;
  EXPECT_DOUBLE_EQ(t.resolve(t.material(steel), t.material(rubber)).kinetic_friction, 0.57);
  EXPECT_EQ(t.find("rubber"), rubber);
  EXPECT_EQ(t.find("wood"), -1);
  CombineRule r;
  EXPECT_TRUE(parseCombineRule("average", &r));
  EXPECT_EQ(r, CombineRule::Average);
  EXPECT_FALSE(parseCombineRule("median", &r));
}

TEST(MaterialTable, WorldUsesListedPair) {
  auto slide = [](bool listed) {
    WorldDef def;
    const int ground = def.materials.add("ground", {0.8, 0.8, 0.0});
    const int skate = def.materials.add("skate", {0.8, 0.8, 0.0});
    if (listed) def.materials.setPair(ground, skate, {0.1, 0.1, 0.0});
    World w(def);
    BodyDef g;
    g.type = BodyType::Static;
    w.addShape(w.createBody(g), {Geometry::plane(Vec3::UnitZ(), 0), Transform(), def.materials.material(ground)});
    BodyDef d;
    d.pose.p = Vec3(0, 0, 0.1);
    d.mass = 1.0;
    d.inertia = Mat3::Identity() * 0.01;
    d.linear_velocity = Vec3(2, 0, 0);
    const BodyId b = w.createBody(d);
    w.addShape(b, {Geometry::box(Vec3(0.1, 0.1, 0.1)), Transform(), def.materials.material(skate)});
    for (int i = 0; i < 3000; ++i) w.step(1e-3);
    return w.comPosition(b).x();
  };
  const double mu = 0.1, expected = 4.0 / (2 * mu * 9.81);
  EXPECT_NEAR(slide(true), expected, 0.03 * expected);
  EXPECT_LT(slide(false), 0.3);
}
