// World::contactReports against closed forms: the weight at rest, kinetic friction while
// pushed, a landing's closing speed and impulse with and without restitution, rolling
// resistance's torque; impulse tracking does not change the motion.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {
constexpr double kDt = 1e-3;
constexpr double kG = 9.81;

Material surface(double mu_s, double mu_k, double e = 0.0) {
  Material m;
  m.static_friction = mu_s;
  m.kinetic_friction = mu_k;
  m.restitution = e;
  return m;
}

// The total force and torque (about its centre of mass) that the reported contacts put on
// `body`.
struct Load {
  Vec3 force = Vec3::Zero(), torque = Vec3::Zero();
};
Load loadOn(const std::vector<ContactReport>& reports, BodyId body) {
  Load l;
  for (const ContactReport& r : reports) {
    if (r.body_a == body) l.force += r.force_a, l.torque += r.torque_a;
    if (r.body_b == body) l.force += r.force_b, l.torque += r.torque_b;
  }
  return l;
}

// The pair (a, b) of the reports, in either order; null when it is not reported.
const ContactReport* pairOf(const std::vector<ContactReport>& reports, BodyId a, BodyId b) {
  for (const ContactReport& r : reports)
    if ((r.body_a == a && r.body_b == b) || (r.body_a == b && r.body_b == a)) return &r;
  return nullptr;
}

double normalForce(const ContactReport& r) {
  double n = 0.0;
  for (int i = 0; i < r.count; ++i) n += r.points[i].normal_force;
  return n;
}
double stepImpulse(const ContactReport& r) {
  double n = 0.0;
  for (int i = 0; i < r.count; ++i) n += r.points[i].step_impulse;
  return n;
}
}  // namespace

// A box, a sphere and a stack of three boxes settle on the ground: each ground pair's normal
// forces sum to the weight it carries, each box of the stack carries the boxes above it, and
// the forces on every body balance its weight. A report's forces are its last substep's, which
// go up and down by a few per cent from step to step around the step's mean (the soft
// contacts share the push-out between the substeps unevenly), so these hold on average over
// the steps at rest (sleep off, the full substeps: the rest substeps' one relax sweep leaves
// the last substep about 1 % off the mean, the next test).
TEST(ContactReports, AtRestTheNormalForcesCarryTheWeight) {
  WorldDef def;
  def.sleep.enabled = false;
  World w(def);
  const Material m = surface(0.8, 0.8);
  const BodyId ground = addGround(w, m);
  const Vec3 half(0.2, 0.15, 0.1);
  const BodyId box = addBox(w, half, 4.0, Vec3(0, 0, half.z()), m);
  const BodyId ball = addSphere(w, 0.1, 3.0, Vec3(1, 0, 0.1), m);
  const double masses[3] = {5.0, 3.0, 2.0};
  BodyId stack[3];
  for (int k = 0; k < 3; ++k)
    stack[k] = addBox(w, half, masses[k], Vec3(-1, 0, half.z() * (2 * k + 1)), m);
  for (int i = 0; i < 1000; ++i) w.step(kDt);

  struct Pair {
    BodyId a, b;
    double mass;
    const char* what;
    double normal = 0.0, force_z = 0.0;  // sums over the steps, N
  };
  Pair pairs[5] = {{ground, box, 4.0, "box"},
                   {ground, ball, 3.0, "sphere"},
                   {ground, stack[0], 10.0, "stack on the ground"},
                   {stack[0], stack[1], 5.0, "stack, upper two"},
                   {stack[1], stack[2], 2.0, "stack, top box"}};
  const BodyId bodies[5] = {box, ball, stack[0], stack[1], stack[2]};
  Load loads[5];
  constexpr int kSteps = 1000;
  std::vector<ContactReport> reports;
  for (int i = 0; i < kSteps; ++i) {
    w.step(kDt);
    w.contactReports(reports);
    for (Pair& p : pairs) {
      const ContactReport* r = pairOf(reports, p.a, p.b);
      ASSERT_NE(r, nullptr) << p.what;
      p.normal += normalForce(*r);
      p.force_z += std::abs(r->force_b.z());
    }
    for (int k = 0; k < 5; ++k) {
      const Load l = loadOn(reports, bodies[k]);
      loads[k].force += l.force;
      loads[k].torque += l.torque;
    }
  }
  for (const Pair& p : pairs) {
    const double weight = p.mass * kG;
    EXPECT_NEAR(p.normal / kSteps, weight, 0.005 * weight) << p.what;
    EXPECT_NEAR(p.force_z / kSteps, weight, 0.005 * weight) << p.what;
    std::printf("[ at rest  ] %s: normal force %.4f N, mean of %d steps (m g %.4f N)\n", p.what,
                p.normal / kSteps, kSteps, weight);
  }
  for (int k = 0; k < 5; ++k) {
    const double mass = w.bodyDef(bodies[k]).mass, weight = mass * kG;
    EXPECT_NEAR((loads[k].force / kSteps + mass * Vec3(0, 0, -kG)).norm(), 0.0, 0.005 * weight);
    EXPECT_LT((loads[k].torque / kSteps).norm(), 0.005 * weight * 0.2);
  }
  // Only touching pairs: the speculative sphere-box pairs are not reported.
  for (const ContactReport& r : reports)
    for (int i = 0; i < r.count; ++i) EXPECT_GT(r.points[i].normal_force, 0.0);
}

// In the rest substeps, the normal impulse a box's manifold took over the step (tracking on)
// is its weight times the step.
TEST(ContactReports, StepImpulseIsTheWeightTimesTheStepAtRest) {
  World w;
  w.setContactImpulseTracking(true);
  const BodyId ground = addGround(w);
  const Vec3 half(0.2, 0.15, 0.1);
  const double mass = 4.0;
  const BodyId box = addBox(w, half, mass, Vec3(0, 0, half.z()));
  for (int i = 0; i < 300; ++i) w.step(kDt);  // resting, not yet asleep
  ASSERT_GT(w.islandCounters().resting_bodies, 0);
  std::vector<ContactReport> reports;
  w.contactReports(reports);
  const ContactReport* r = pairOf(reports, ground, box);
  ASSERT_NE(r, nullptr);
  EXPECT_NEAR(stepImpulse(*r) / kDt, mass * kG, 0.005 * mass * kG);
  std::printf("[ at rest  ] rest substeps: step impulse / dt %.4f N, last substep %.4f N (m g "
              "%.4f N)\n", stepImpulse(*r) / kDt, normalForce(*r), mass * kG);
}

// A box pushed along x by F > mu_s m g slides: the friction reported is mu_k m g against the
// motion, and the reported contact force plus gravity plus F is the box's m dv/dt.
TEST(ContactReports, PushedBoxReportsKineticFriction) {
  const double mu_s = 0.6, mu_k = 0.4, mass = 4.0, F = 0.8 * mass * kG;
  World w;
  const Material m = surface(mu_s, mu_k);
  const BodyId ground = addGround(w, m);
  const Vec3 half(0.2, 0.2, 0.1);
  const BodyId box = addBox(w, half, mass, Vec3(0, 0, half.z()), m);
  std::vector<ContactReport> reports;
  for (int i = 0; i < 400; ++i) {
    const Vec3 v0 = w.bodyState(box).linear_velocity;
    w.applyForce(box, Vec3(F, 0, 0), w.comPosition(box));
    w.step(kDt);
    if (i < 300) continue;  // sliding steadily by now
    w.contactReports(reports);
    const ContactReport* r = pairOf(reports, ground, box);
    ASSERT_NE(r, nullptr);
    Vec3 friction = Vec3::Zero();
    for (int k = 0; k < r->count; ++k) friction += r->points[k].friction_force;
    const double expected = mu_k * mass * kG;
    EXPECT_NEAR(friction.x(), -expected, 0.01 * expected) << "step " << i;
    const Vec3 net = loadOn(reports, box).force + Vec3(F, 0, -mass * kG);
    const Vec3 ma = mass * (w.bodyState(box).linear_velocity - v0) / kDt;
    EXPECT_NEAR((net - ma).norm(), 0.0, 0.01 * expected) << "step " << i;
    if (i == 399)
      std::printf("[ pushed   ] friction %.4f N (mu_k m g %.4f N), net %.4f N, m dv/dt %.4f N\n",
                  -friction.x(), expected, net.x(), ma.x());
  }
  EXPECT_GT(w.bodyState(box).linear_velocity.x(), 0.3);
}

// A sphere rolling against rolling resistance: the reported torque about its centre (the
// friction's lever arm plus the rolling resistance torque) is I dw/dt, the force m dv/dt.
TEST(ContactReports, RollingSphereTorqueIncludesRollingResistance) {
  const double r = 0.15, mass = 3.0, v0 = 1.5, c = 0.1;
  const Mat3 inertia = Mat3::Identity() * 0.4 * mass * r * r;
  World w;
  Material m = surface(1.0, 1.0);
  m.rolling_resistance = c;
  addGround(w, m);
  const BodyId ball = addDynamic(w, mass, inertia, Transform(Vec3(0, 0, r), Quat::Identity()),
                                 Vec3::Zero(), Vec3(v0, 0, 0), Vec3(0, v0 / r, 0));
  w.addShape(ball, {Geometry::sphere(r), Transform(), m});
  std::vector<ContactReport> reports;
  for (int i = 0; i < 200; ++i) w.step(kDt);
  const BodyState s0 = w.bodyState(ball);
  w.step(kDt);
  const BodyState s1 = w.bodyState(ball);
  w.contactReports(reports);
  const Load l = loadOn(reports, ball);
  const Vec3 Ia = inertia * (s1.angular_velocity - s0.angular_velocity) / kDt;
  const Vec3 ma = mass * (s1.linear_velocity - s0.linear_velocity) / kDt + Vec3(0, 0, mass * kG);
  // Without the rolling torque the friction's alone would turn the sphere the other way.
  const double rolling = c * r * mass * kG;
  EXPECT_NEAR(l.torque.y(), Ia.y(), 0.01 * rolling);
  EXPECT_NEAR((l.force - ma).norm(), 0.0, 0.01 * rolling / r);
  std::printf("[ rolling  ] torque %.5f N m (I dw/dt %.5f), force x %.5f N (m dv/dt %.5f)\n",
              l.torque.y(), Ia.y(), l.force.x(), ma.x());
}

// A sphere dropped from h lands with closing speed sqrt(2 g h); the normal impulse of the
// landing (summed over its steps) is m v without restitution and m v (1 + e) with it, and it
// leaves at e v.
class Landing : public ::testing::TestWithParam<double> {};
TEST_P(Landing, ClosingSpeedImpulseAndRebound) {
  const double e = GetParam(), h = 1.0, mass = 2.0, radius = 0.1;
  World w;
  w.setContactImpulseTracking(true);
  const Material m = surface(0.5, 0.5, e);
  const BodyId ground = addGround(w, m);
  const BodyId ball = addSphere(w, radius, mass, Vec3(0, 0, radius + h), m);
  std::vector<ContactReport> reports;
  double closing = 0.0, impulse = 0.0, separating = 0.0;
  int touching_steps = 0;
  for (int i = 0; i < 1000; ++i) {
    w.step(kDt);
    w.contactReports(reports);
    const ContactReport* r = pairOf(reports, ground, ball);
    if (!r) {
      if (touching_steps > 0) break;  // it left the ground (e > 0)
      continue;
    }
    if (touching_steps == 0) closing = r->points[0].closing_speed;
    impulse += stepImpulse(*r);
    separating = r->points[0].separating_speed;
    // A resting contact carries m g dt a step: the landing is over when the rebound or the
    // rest starts.
    if (++touching_steps > 1 && stepImpulse(*r) < 2.0 * mass * kG * kDt) {
      impulse -= stepImpulse(*r);
      break;
    }
    if (e > 0.0 && separating > 0.0) break;
  }
  const double v = std::sqrt(2.0 * kG * h);
  ASSERT_GT(touching_steps, 0);
  EXPECT_NEAR(closing, v, 0.01 * v);
  const double expected = mass * v * (1.0 + e);
  EXPECT_NEAR(impulse, expected, (e > 0.0 ? 0.02 : 0.01) * expected);
  if (e > 0.0) {
    EXPECT_NEAR(separating, e * v, 0.02 * e * v);
  }
  std::printf("[ landing  ] e %.2f: closing %.4f m/s (sqrt(2gh) %.4f), impulse %.4f N s over %d "
              "steps (m v (1+e) %.4f), separating %.4f m/s (e v %.4f)\n",
              e, closing, v, impulse, touching_steps, expected, separating, e * v);
}
INSTANTIATE_TEST_SUITE_P(Restitution, Landing, ::testing::Values(0.0, 0.5));

// Tracking only reads what the solver did: a pile of boxes and spheres falling, bouncing and
// sliding moves bit for bit the same with it on; with it off, nothing is tracked.
TEST(ContactReports, TrackingDoesNotChangeTheMotion) {
  const auto run = [](bool track, std::vector<BodyState>* out) {
    World w;
    w.setContactImpulseTracking(track);
    EXPECT_EQ(w.contactImpulseTracking(), track);
    const Material m = surface(0.7, 0.5, 0.4);
    addGround(w, m);
    std::vector<BodyId> bodies;
    for (int k = 0; k < 6; ++k) {
      const Vec3 p(0.05 * k, 0.03 * k, 0.3 + 0.25 * k);
      bodies.push_back(k % 2 ? addSphere(w, 0.1, 1.0 + k, p, m)
                             : addBox(w, Vec3(0.12, 0.1, 0.08), 1.0 + k, p, m));
    }
    std::vector<ContactReport> reports;
    double tracked = 0.0;
    for (int i = 0; i < 800; ++i) {
      w.step(kDt);
      w.contactReports(reports);
      for (const ContactReport& r : reports)
        for (int k = 0; k < r.count; ++k) tracked += r.points[k].step_impulse;
    }
    if (track) EXPECT_GT(tracked, 0.0);
    else EXPECT_EQ(tracked, 0.0);
    for (const BodyId b : bodies) out->push_back(w.bodyState(b));
  };
  std::vector<BodyState> off, on;
  run(false, &off);
  run(true, &on);
  ASSERT_EQ(off.size(), on.size());
  for (size_t k = 0; k < off.size(); ++k) {
    EXPECT_EQ(std::memcmp(off[k].com_position.data(), on[k].com_position.data(), sizeof(Vec3)), 0);
    EXPECT_EQ(std::memcmp(off[k].linear_velocity.data(), on[k].linear_velocity.data(), sizeof(Vec3)), 0);
    EXPECT_EQ(std::memcmp(off[k].pose.q.coeffs().data(), on[k].pose.q.coeffs().data(),
                          4 * sizeof(double)), 0);
  }
}
