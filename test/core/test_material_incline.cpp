// The shipped friction table acts on the solver as its numbers say: on one incline steeper than
// rubber-concrete's kinetic coefficient and the geometric mean of their surfaces' static ones but
// below the table's static 1.0, a rubber block holds; a leather block on steel slides with the
// closed form a = g (sin(theta) - mu_k cos(theta)), mu_k = 0.2 from the leather-metal row.
#include <gtest/gtest.h>

#include <cmath>

#include "ragdoll_sim/material_file.hpp"
#include "ragdoll_sim/world.hpp"

using namespace ragdoll_sim;

namespace {

constexpr double kG = 9.81;
constexpr double kTan = 0.975;  // atan(0.725) < theta < atan(1.0), above sqrt(1.0 * 0.9)

struct Slide {
  double start_speed, end_speed;  // along the slope, down positive, at t0 and t1
  double t0, t1;
  double creep;                   // m moved down the slope by t1
};

// A 0.2 x 0.2 x 0.1 m block of `block` resting on a plane of `ground` tilted by atan(kTan).
Slide slide(const MaterialTable& table, const std::string& block, const std::string& ground) {
  const double theta = std::atan(kTan);
  WorldDef def;
  def.gravity = Vec3(0, 0, -kG);
  def.materials = table;
  def.sleep.enabled = false;
  World w(def);
  // Plane z = x tan(theta): rises along +x, its downhill direction is -(cos, 0, sin).
  const Vec3 n(-std::sin(theta), 0, std::cos(theta));
  const Vec3 down = -Vec3(std::cos(theta), 0, std::sin(theta));
  BodyDef g;
  g.type = BodyType::Static;
  w.addShape(w.createBody(g), {Geometry::plane(n, 0), Transform(), table.material(table.find(ground))});
  BodyDef d;
  const Vec3 half(0.1, 0.1, 0.05);
  d.pose = Transform(n * half.z(), Quat(Eigen::AngleAxisd(-theta, Vec3::UnitY())));
  d.mass = 2.0;
  d.inertia = (d.mass / 3.0) * Vec3(half.y() * half.y() + half.z() * half.z(),
                                    half.x() * half.x() + half.z() * half.z(),
                                    half.x() * half.x() + half.y() * half.y()).asDiagonal();
  const BodyId b = w.createBody(d);
  w.addShape(b, {Geometry::box(half), Transform(), table.material(table.find(block))});
  const Vec3 start = w.comPosition(b);
  Slide s{0, 0, 0.5, 1.5, 0};
  const double dt = 1e-3;
  for (int i = 1; i <= 1500; ++i) {
    w.step(dt);
    if (i == 500) s.start_speed = w.pointVelocity(b, w.comPosition(b)).dot(down);
  }
  s.end_speed = w.pointVelocity(b, w.comPosition(b)).dot(down);
  s.creep = (w.comPosition(b) - start).dot(down);
  return s;
}

}  // namespace

TEST(MaterialIncline, RubberHoldsOnConcreteLeatherSlidesOnSteel) {
  const MaterialFileResult r = loadMaterialFile(std::string(RAGDOLL_SIM_SOURCE_DIR) + "/config/materials.yaml");
  ASSERT_TRUE(r.ok) << r.error;
  const double theta = std::atan(kTan);

  const Slide rubber = slide(r.table, "rubber", "concrete");
  EXPECT_LT(std::abs(rubber.creep), 1e-3) << "rubber on concrete crept " << rubber.creep << " m";
  EXPECT_LT(std::abs(rubber.end_speed), 1e-3);

  const Slide leather = slide(r.table, "leather", "steel");
  const double expected = kG * (std::sin(theta) - 0.2 * std::cos(theta));
  const double a = (leather.end_speed - leather.start_speed) / (leather.t1 - leather.t0);
  EXPECT_NEAR(a, expected, 0.03 * expected) << "leather on steel";
}
