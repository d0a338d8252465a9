// Contact compliance per material (Material::contact_hertz, contact_damping_ratio): a sphere
// landing on a compliant surface is stopped as a damped spring-mass would stop it, the softer
// surface of a pair sets the pair's compliance, and 0 Hz keeps the rigid contact.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "ragdoll_sim/material_file.hpp"
#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {
constexpr double kDt = 1e-3;
constexpr double kG = 9.81;

Material compliant(double hertz, double zeta) {
  Material m;
  m.contact_hertz = hertz;
  m.contact_damping_ratio = zeta;
  return m;
}

// A mass landing at speed v on a spring-damper of natural frequency f and damping ratio zeta
// under gravity, while the contact pushes: compression y'' = g - w^2 y - 2 zeta w y', y(0) = 0,
// y'(0) = v (RK4 at 1 us): the largest contact acceleration (contact force / m) and the time
// to the deepest point.
struct Spring {
  double peak = 0.0, stop_time = 0.0;
};
Spring springMass(double v, double f, double zeta) {
  const double w = 2.0 * M_PI * f, dt = 1e-6;
  const auto acc = [&](double y, double u) { return kG - w * w * y - 2.0 * zeta * w * u; };
  double y = 0.0, u = v;
  Spring s;
  for (int i = 0; i < 2000000; ++i) {
    const double a = w * w * y + 2.0 * zeta * w * u;  // contact force / m
    if (i > 0 && (y < 0.0 || a < 0.0)) break;
    s.peak = std::max(s.peak, a);
    if (u > 0.0) s.stop_time = (i + 1) * dt;
    const double k1y = u, k1u = acc(y, u);
    const double k2y = u + 0.5 * dt * k1u, k2u = acc(y + 0.5 * dt * k1y, u + 0.5 * dt * k1u);
    const double k3y = u + 0.5 * dt * k2u, k3u = acc(y + 0.5 * dt * k2y, u + 0.5 * dt * k2u);
    const double k4y = u + dt * k3u, k4u = acc(y + dt * k3y, u + dt * k3u);
    y += dt / 6.0 * (k1y + 2 * k2y + 2 * k3y + k4y);
    u += dt / 6.0 * (k1u + 2 * k2u + 2 * k3u + k4u);
  }
  return s;
}

struct Drop {
  double peak_acceleration = 0.0;  // largest reported peak_force / m over the landing
  double stop_time = -1.0;         // s from the touch to the lowest point
  double rest_depth = 0.0;         // m, depth reported at rest
  double rest_force = 0.0;         // N, normal force reported at rest
};

// A sphere of 1 kg starting just above the ground at v downwards, on surfaces `ground` and
// `ball`; 1.5 s of steps with impulse tracking on.
Drop dropSphere(const Material& ground, const Material& ball, double v) {
  World w;
  w.setContactImpulseTracking(true);
  addGround(w, ground);
  const double r = 0.1, mass = 1.0, gap = 0.01;
  const BodyId b = addBody(w, Geometry::sphere(r), mass, Mat3::Identity() * 0.4 * mass * r * r,
                           Transform(Vec3(0, 0, r + gap), Quat::Identity()), ball,
                           Vec3(0, 0, -v));
  Drop d;
  std::vector<ContactReport> reports;
  const double t_touch = (std::sqrt(v * v + 2 * kG * gap) - v) / kG;
  bool touched = false;
  double vz_prev = -v;
  for (int i = 0; i < 1500; ++i) {
    w.step(kDt);
    w.contactReports(reports);
    for (const ContactReport& c : reports)
      for (int k = 0; k < c.count; ++k) {
        d.peak_acceleration = std::max(d.peak_acceleration, c.points[k].peak_force / mass);
        touched |= c.points[k].step_impulse > 0.0;
      }
    const double vz = w.bodyState(b).linear_velocity.z();
    if (touched && d.stop_time < 0.0 && vz >= 0.0)  // lowest point: vz crosses 0
      d.stop_time = w.time() - kDt * vz / (vz - vz_prev) - t_touch;
    vz_prev = vz;
  }
  for (const ContactReport& c : reports)
    for (int k = 0; k < c.count; ++k) {
      d.rest_depth = std::max(d.rest_depth, c.points[k].depth);
      d.rest_force += c.points[k].normal_force;
    }
  return d;
}
}  // namespace

// Peak acceleration and the time to the deepest point against the damped spring-mass (at
// zeta 0 about v w and a quarter period); once damped to rest the sphere sinks g / w^2 and the
// reported force is its weight. (The soft step's implicit damper over a substep lowers the
// first substep's force by 1 / (1 + 2 zeta w h): keep 2 zeta w h small.)
TEST(ContactCompliance, LandingFollowsTheDampedSpringMass) {
  const double v = 3.0;
  for (const auto& [f, zeta] : {std::make_pair(10.0, 0.0), std::make_pair(20.0, 0.0),
                                std::make_pair(10.0, 0.3), std::make_pair(20.0, 0.5)}) {
    const Drop d = dropSphere(compliant(f, zeta), Material(), v);
    const Spring expected = springMass(v, f, zeta);
    EXPECT_NEAR(d.peak_acceleration, expected.peak, 0.05 * expected.peak)
        << f << " Hz, zeta " << zeta;
    EXPECT_NEAR(d.stop_time, expected.stop_time, 0.05 * expected.stop_time)
        << f << " Hz, zeta " << zeta;
    const double omega = 2 * M_PI * f, sag = kG / (omega * omega);
    if (zeta > 0.0) {
      EXPECT_NEAR(d.rest_depth, sag, 0.05 * sag) << f << " Hz";
      EXPECT_NEAR(d.rest_force, kG, 0.005 * kG) << f << " Hz";
    }
    std::printf("[ compliance ] %4.1f Hz zeta %.1f: peak %.2f m/s^2 (spring-mass %.2f, v w "
                "%.2f), stop %.4f s (spring-mass %.4f, 1/(4f) %.4f), rest depth %.5f m (g/w^2 "
                "%.5f)\n",
                f, zeta, d.peak_acceleration, expected.peak, v * omega, d.stop_time,
                expected.stop_time, 0.25 / f, d.rest_depth, sag);
  }
}

// The softer surface of a pair gives its compliance, whichever side it is on; the softer of
// two grounds gives the lower peak; a rigid ground stops the sphere within a substep or two.
TEST(ContactCompliance, SofterSurfaceGivesTheLowerPeak) {
  const double v = 3.0;
  const Drop soft = dropSphere(compliant(10.0, 0.2), Material(), v);
  const Drop hard = dropSphere(compliant(30.0, 0.2), Material(), v);
  const Drop rigid = dropSphere(Material(), Material(), v);
  EXPECT_LT(soft.peak_acceleration, 0.5 * hard.peak_acceleration);
  EXPECT_LT(hard.peak_acceleration, 0.2 * rigid.peak_acceleration);
  // The pair rule: a soft ball on a harder compliant ground is the soft ball's pair.
  const Drop ball_soft = dropSphere(compliant(30.0, 0.2), compliant(10.0, 0.2), v);
  const Drop ground_soft = dropSphere(compliant(10.0, 0.2), compliant(30.0, 0.2), v);
  EXPECT_DOUBLE_EQ(ball_soft.peak_acceleration, ground_soft.peak_acceleration);
  EXPECT_NEAR(ball_soft.peak_acceleration, soft.peak_acceleration, 1e-9 * soft.peak_acceleration);
  std::printf("[ compliance ] peak: 10 Hz %.1f, 30 Hz %.1f, rigid %.1f m/s^2\n",
              soft.peak_acceleration, hard.peak_acceleration, rigid.peak_acceleration);
}

TEST(ContactCompliance, PairRuleAndRanges) {
  MaterialTable t;
  Material a = compliant(20.0, 0.5), b = compliant(8.0, 0.1), rigid;
  a.id = t.add("a", a);
  b.id = t.add("b", b);
  rigid.id = t.add("rigid", rigid);
  for (const auto& [x, y] : {std::make_pair(a, b), std::make_pair(b, a)}) {
    const Material m = t.resolve(x, y);
    EXPECT_EQ(m.contact_hertz, 8.0);
    EXPECT_EQ(m.contact_damping_ratio, 0.1);
  }
  EXPECT_EQ(t.resolve(rigid, a).contact_hertz, 20.0);
  EXPECT_EQ(t.resolve(a, rigid).contact_damping_ratio, 0.5);
  EXPECT_EQ(t.resolve(rigid, rigid).contact_hertz, 0.0);
  // Equal frequencies: the higher damping ratio, in either order.
  Material c = compliant(8.0, 0.7);
  c.id = t.add("c", c);
  EXPECT_EQ(t.resolve(b, c).contact_damping_ratio, 0.7);
  EXPECT_EQ(t.resolve(c, b).contact_damping_ratio, 0.7);
  // A listed pair with 4 coefficients keeps the surfaces' compliance; with 5 or 6, its own.
  Material p;
  p.contact_hertz = 50.0;
  p.contact_damping_ratio = 2.0;
  t.setPair(a.id, rigid.id, p, 4);
  EXPECT_EQ(t.resolve(a, rigid).contact_hertz, 20.0);
  t.setPair(a.id, rigid.id, p, 6);
  EXPECT_EQ(t.resolve(rigid, a).contact_hertz, 50.0);
  EXPECT_EQ(t.resolve(rigid, a).contact_damping_ratio, 2.0);

  EXPECT_EQ(materialError(compliant(20.0, 0.5)), "");
  EXPECT_NE(materialError(compliant(-1.0, 0.5)).find("contact_hertz"), std::string::npos);
  EXPECT_NE(materialError(compliant(NAN, 0.5)).find("contact_hertz"), std::string::npos);
  EXPECT_NE(materialError(compliant(10.0, -0.1)).find("contact_damping_ratio"), std::string::npos);
  EXPECT_NE(materialError(compliant(INFINITY, 1.0)).find("contact_hertz"), std::string::npos);
}

// The file's 5th and 6th numbers are the compliance; the shipped mat surface is compliant and
// the others rigid.
TEST(ContactCompliance, MaterialFileCarriesCompliance) {
  const MaterialFileResult r = loadMaterialString(R"(
materials:
  surfaces:
    foam: [0.6, 0.5, 0.0, 0.0, 8, 0.5]
    floor: [0.8, 0.7, 0.1]
  pairs:
    - [foam, floor, 0.5, 0.4, 0.0, 0.0, 12]
)");
  ASSERT_TRUE(r.ok) << r.error;
  const MaterialTable& t = r.table;
  const Material& foam = t.material(t.find("foam"));
  EXPECT_EQ(foam.contact_hertz, 8.0);
  EXPECT_EQ(foam.contact_damping_ratio, 0.5);
  EXPECT_EQ(t.resolve(foam, foam).contact_hertz, 8.0);
  const Material pair = t.resolve(foam, t.material(t.find("floor")));
  EXPECT_EQ(pair.contact_hertz, 12.0);
  EXPECT_EQ(pair.contact_damping_ratio, 1.0);  // left out: the default
  const MaterialFileResult bad = loadMaterialString(
      "materials:\n  surfaces:\n    foam: [0.6, 0.5, 0.0, 0.0, -8]\n", "m.yaml");
  EXPECT_FALSE(bad.ok);
  EXPECT_NE(bad.error.find("surfaces/foam (line 3)"), std::string::npos) << bad.error;
  EXPECT_NE(bad.error.find("contact_hertz must be a finite number >= 0, got -8"), std::string::npos)
      << bad.error;

  const MaterialFileResult shipped =
      loadMaterialFile(std::string(RAGDOLL_SIM_SOURCE_DIR) + "/config/materials.yaml");
  ASSERT_TRUE(shipped.ok) << shipped.error;
  const MaterialTable& s = shipped.table;
  ASSERT_GE(s.find("mat"), 1);
  EXPECT_GT(s.material(s.find("mat")).contact_hertz, 0.0);
  EXPECT_EQ(s.material(s.find("concrete")).contact_hertz, 0.0);
  EXPECT_EQ(s.resolve(s.material(s.find("leather")), s.material(s.find("mat"))).contact_hertz,
            s.material(s.find("mat")).contact_hertz);
}

// 0 Hz is the rigid contact bit for bit, whatever the damping ratio says.
TEST(ContactCompliance, ZeroHertzChangesNothing) {
  const auto run = [](const Material& m) {
    World w;
    addGround(w, m);
    Material box_m = m;
    box_m.restitution = 0.3;
    const BodyId box = addBox(w, Vec3(0.2, 0.1, 0.05), 2.0, Vec3(0, 0, 0.5), box_m);
    w.applyAngularImpulse(box, Vec3(0.01, 0.02, 0.0));
    for (int i = 0; i < 600; ++i) w.step(kDt);
    return w.bodyState(box);
  };
  const BodyState a = run(Material()), b = run(compliant(0.0, 7.0));
  EXPECT_EQ(std::memcmp(a.com_position.data(), b.com_position.data(), sizeof(Vec3)), 0);
  EXPECT_EQ(std::memcmp(a.pose.q.coeffs().data(), b.pose.q.coeffs().data(), 4 * sizeof(double)), 0);
  const BodyState c = run(compliant(5.0, 0.5));
  EXPECT_GT((a.com_position - c.com_position).norm(), 1e-4);  // compliance does act
}
