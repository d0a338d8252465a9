// Multi-body contact cases: sphere collisions, stacks, a pyramid, a heavy box on a light one,
// a sleeping pile (the broadphase's pairs: test_broadphase.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <vector>

#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"
#include "world_tuning.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {
constexpr double kDt = 1e-3;
}  // namespace

// Head-on collision of two spheres: momentum conserved, separating speed = e * closing speed.
class SphereCollision : public ::testing::TestWithParam<double> {};
TEST_P(SphereCollision, ConservesMomentumAndRestitution) {
  const double e = GetParam();
  WorldDef def;
  def.gravity.setZero();
  World w(def);
  Material m;
  m.restitution = e;
  auto sphere = [&](double mass, double r, const Vec3& p, const Vec3& v) {
    BodyDef d;
    d.pose.p = p;
    d.mass = mass;
    d.inertia = Mat3::Identity() * 0.4 * mass * r * r;
    d.linear_velocity = v;
    const BodyId b = w.createBody(d);
    w.addShape(b, {Geometry::sphere(r), Transform(), m});
    return b;
  };
  const BodyId a = sphere(2.0, 0.1, Vec3(-0.5, 0, 0), Vec3(3, 0, 0));
  const BodyId b = sphere(1.0, 0.15, Vec3(0.5, 0, 0), Vec3(-2, 0, 0));
  const Vec3 p0 = w.linearMomentum();
  const double closing = 5.0;
  for (int i = 0; i < 400; ++i) w.step(kDt);
  const double va = w.bodyState(a).linear_velocity.x(), vb = w.bodyState(b).linear_velocity.x();
  EXPECT_LT((w.linearMomentum() - p0).norm(), 1e-9 * p0.norm());
  EXPECT_NEAR(vb - va, e * closing, 0.01 * e * closing);
  std::printf("[ spheres  ] e %.1f: separating %.4f m/s (closed form %.4f), |dp| %.1e\n", e, vb - va,
              e * closing, (w.linearMomentum() - p0).norm());
}
INSTANTIATE_TEST_SUITE_P(Restitution, SphereCollision, ::testing::Values(0.2, 0.5, 0.8, 1.0));

TEST(Stacking, TenBoxesStayStackedTenSeconds) {
  World w;
  addGround(w);
  const Vec3 half(0.25, 0.25, 0.25);
  std::vector<BodyId> boxes;
  for (int i = 0; i < 10; ++i) boxes.push_back(addBox(w, half, 1.0, Vec3(0, 0, 0.25 + 0.5 * i)));
  for (int i = 0; i < 10000; ++i) w.step(kDt);
  double drift = 0.0;
  for (int i = 0; i < 10; ++i) {
    const Vec3 p = w.comPosition(boxes[i]);
    drift = std::max(drift, std::hypot(p.x(), p.y()));
    EXPECT_NEAR(p.z(), 0.25 + 0.5 * i, 0.01) << "box " << i;
  }
  EXPECT_LT(drift, 0.01);
  std::printf("[ stack    ] 10 boxes after 10 s: horizontal drift %.2e m, top z %.4f (built 4.75)\n", drift,
              w.comPosition(boxes.back()).z());
}

TEST(Stacking, TwentyBoxPyramidStaysUp) {
  World w;
  addGround(w);
  const Vec3 half(0.25, 0.25, 0.25);
  std::vector<std::pair<BodyId, Vec3>> boxes;
  // rows of 6, 5, 4, 3, 2 = 20 boxes
  int row = 0;
  for (int n = 6; n >= 2; --n, ++row)
    for (int i = 0; i < n; ++i) {
      const Vec3 p((i - 0.5 * (n - 1)) * 0.51, 0, 0.25 + 0.5 * row);
      boxes.emplace_back(addBox(w, half, 1.0, p), p);
    }
  ASSERT_EQ(boxes.size(), 20u);
  for (int i = 0; i < 5000; ++i) w.step(kDt);
  double worst = 0.0;
  for (const auto& [b, p0] : boxes) worst = std::max(worst, (w.comPosition(b) - p0).norm());
  EXPECT_LT(worst, 0.02);
  std::printf("[ pyramid  ] 20 boxes after 5 s: max displacement %.4f m\n", worst);
}

TEST(Stacking, HeavyBoxOnLightBoxDoesNotSink) {
  World w;
  addGround(w);
  const Vec3 half(0.2, 0.2, 0.1);
  const BodyId light = addBox(w, half, 1.0, Vec3(0, 0, 0.1));
  const BodyId heavy = addBox(w, half, 100.0, Vec3(0, 0, 0.3));
  double sink = 0.0;
  for (int i = 0; i < 3000; ++i) {
    w.step(kDt);
    const double gap_bottom = w.comPosition(light).z() - half.z();
    const double gap_top = (w.comPosition(heavy).z() - half.z()) - (w.comPosition(light).z() + half.z());
    sink = std::max({sink, -gap_bottom, -gap_top});
  }
  EXPECT_LT(sink, 0.005);
  std::printf("[ ratio    ] 100 kg on 1 kg: max penetration %.4f m\n", sink);
}

namespace {
// Steps until no body is awake, at most 5000 steps; returns the steps taken.
int stepUntilAsleep(World& w) {
  int t = 0;
  while (w.awakeBodyCount() > 0 && t < 5000) {
    w.step(kDt);
    ++t;
  }
  return t;
}
}  // namespace

// Warm starting across a change of time step (the node's physics_rate at run time): a stack
// of five boxes resting at dt = 1 ms goes on at 4 ms. The impulses kept from the last step
// are per substep and are scaled by the new substep over the old (warmStartScale), so the
// first 4 ms step starts from the load the stack already carries: its top box drops 8.6 um
// in it, its fastest box moves at 5.0e-3 m/s. Taken as they were, the first substep holds a
// quarter of the load: 55 um and 1.2e-2 m/s.
TEST(Stacking, WarmStartCarriesTheLoadToANewTimeStep) {
  WorldDef def;
  def.sleep.enabled = false;  // neither asleep nor on the rest substeps when dt changes
  World w(def);
  addGround(w);
  const Vec3 half(0.2, 0.2, 0.1);
  std::vector<BodyId> boxes;
  for (int k = 0; k < 5; ++k) boxes.push_back(addBox(w, half, 2.0, Vec3(0, 0, 0.1 + 0.2 * k)));
  for (int i = 0; i < 500; ++i) w.step(kDt);
  const double z0 = w.comPosition(boxes.back()).z();
  w.step(4 * kDt);
  const double drop = z0 - w.comPosition(boxes.back()).z();
  double fastest = 0.0;
  for (const BodyId b : boxes) fastest = std::max(fastest, w.bodyState(b).linear_velocity.norm());
  EXPECT_LT(drop, 2e-5);
  EXPECT_LT(fastest, 8e-3);
  std::printf("[ stack    ] 1 ms -> 4 ms: top box dropped %.2e m, fastest box %.2e m/s\n", drop,
              fastest);
}

TEST(Sleeping, PileSleepsAndCostsNoIntegration) {
  World w;
  addGround(w);
  const Vec3 half(0.2, 0.2, 0.2);
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      for (int k = 0; k < 3; ++k) addBox(w, half, 1.0, Vec3(i * 0.45, j * 0.45, 0.2 + 0.45 * k));
  const int t = stepUntilAsleep(w);
  EXPECT_EQ(w.awakeBodyCount(), 0) << "pile still awake after 5 s";
  std::printf("[ sleep    ] 48-box pile asleep after %.3f s\n", t * kDt);
}

// A world whose bodies all sleep steps without colliding or solving (World::Impl::settled), and
// sleeping and static bodies keep last step's boxes (aabb_kept): what the world is told between
// steps must still reach it.
namespace {
bool hasContact(const World& w, BodyId a, BodyId b) {
  for (const ContactInfo& c : w.contacts())
    if ((c.body_a == a && c.body_b == b) || (c.body_a == b && c.body_b == a)) return true;
  return false;
}
}  // namespace

TEST(Sleeping, SettledWorldKeepsPosesAndContacts) {
  World w;
  const BodyId g = addGround(w);
  const BodyId lower = addBox(w, Vec3(0.2, 0.2, 0.2), 1.0, Vec3(0, 0, 0.2));
  const BodyId upper = addBox(w, Vec3(0.2, 0.2, 0.2), 1.0, Vec3(0.05, 0, 0.6));
  ASSERT_LT(stepUntilAsleep(w), 5000);
  const Transform pose = w.bodyPose(upper);
  const size_t contacts = w.contacts().size();
  for (int i = 0; i < 500; ++i) w.step(kDt);
  EXPECT_EQ(w.awakeBodyCount(), 0);
  EXPECT_EQ((w.bodyPose(upper).p - pose.p).norm(), 0.0);
  EXPECT_EQ(w.contacts().size(), contacts);
  EXPECT_TRUE(hasContact(w, g, lower));
  EXPECT_TRUE(hasContact(w, lower, upper));

  // A pair disabled while both sleep loses its contact at the next step.
  w.disableCollision(lower, upper);
  w.step(kDt);
  EXPECT_FALSE(hasContact(w, lower, upper));
  EXPECT_TRUE(hasContact(w, g, lower));

  // A wake-up after the quiet steps goes on from the same state: the top box, pushed
  // sideways, slides and stops again (kinetic friction), and the world falls asleep again.
  w.applyLinearImpulseToCenter(upper, Vec3(0.5, 0, 0));
  EXPECT_TRUE(w.isAwake(upper));
  w.step(kDt);
  EXPECT_GT(w.bodyState(upper).linear_velocity.x(), 0.1);
  EXPECT_LT(stepUntilAsleep(w), 5000);
}

TEST(Sleeping, StaticBodyMovedBesideSleepersIsCollidedAgain) {
  World w;
  addGround(w);
  const BodyId box = addBox(w, Vec3(0.2, 0.2, 0.2), 1.0, Vec3(0, 0, 0.2));
  BodyDef pd;
  pd.type = BodyType::Static;
  pd.pose.p = Vec3(10, 0, 0.05);
  const BodyId plate = w.createBody(pd);
  w.addShape(plate, {Geometry::box(Vec3(0.5, 0.5, 0.05)), Transform(), Material()});
  ASSERT_LT(stepUntilAsleep(w), 5000);
  for (int i = 0; i < 10; ++i) w.step(kDt);
  EXPECT_FALSE(hasContact(w, box, plate));
  // The plate is set right above the sleeping box (a gap of 5 mm, inside the speculative
  // distance): once the box is awake, the pair is found at the plate's new place.
  w.setBodyState(plate, Transform(Vec3(0, 0, 0.455), Quat::Identity()), Vec3::Zero(),
                 Vec3::Zero());
  w.wake(box);
  w.step(kDt);
  EXPECT_TRUE(hasContact(w, box, plate));
}

// Pairs of sleeping shapes are carried over from the last step (WorldTuning::carry_sleeping_pairs)
// instead of found again: the world must step exactly as one that finds every pair. Four stacks
// of three boxes go to sleep while a box far away is kicked every 0.3 s (so the world never
// settles and collides every step). Then, while the stacks sleep: a pair inside stack 3 is
// disabled (its middle box then sinks through the bottom one once woken), the ground plane
// drops 5 cm under the sleepers (their plane pairs end) before stack 1 is woken, and stack 0 is
// knocked into stack 1. Every step both worlds have the same poses, bit for bit, the same
// awake bodies and the same contacts.
TEST(Sleeping, CarriedSleepingPairsStepAsIfFoundAgain) {
  struct Scene {
    std::unique_ptr<World> w;
    BodyId ground, kicked;
    std::vector<BodyId> boxes;  // stack k, level l: boxes[3 k + l]
    explicit Scene(bool carry) {
      w = std::make_unique<World>();
      WorldTuning tuning;
      tuning.carry_sleeping_pairs = carry;
      WorldInternals::setTuning(*w, tuning);
      ground = addGround(*w);
      const Vec3 half(0.2, 0.2, 0.2);
      for (int k = 0; k < 4; ++k)
        for (int l = 0; l < 3; ++l)
          boxes.push_back(addBox(*w, half, 1.0, Vec3(0.7 * k, 0.02 * l, 0.2 + 0.41 * l)));
      kicked = addBox(*w, half, 1.0, Vec3(10, 0, 0.2));
    }
    void step(int i) {
      if (i % 300 == 0) w->applyLinearImpulseToCenter(kicked, Vec3(0, 0, 3.0));
      if (i == 800) w->disableCollision(boxes[9], boxes[10]);
      if (i == 900) w->wake(boxes[11]);
      if (i == 1000)
        w->setBodyState(ground, Transform(Vec3(0, 0, -0.05), Quat::Identity()), Vec3::Zero(),
                        Vec3::Zero());
      if (i == 1100) w->wake(boxes[3]);
      if (i == 1500) w->applyLinearImpulseToCenter(boxes[2], Vec3(3.0, 0, 0));
      w->step(kDt);
    }
  };
  Scene carry(true), find(false);
  const int n = int(carry.boxes.size()) + 1;
  int mixed = 0;  // steps with sleeping and awake bodies (pairs carried over)
  bool ground_left = false;  // a sleeping stack lost its ground contact when the plane dropped
  for (int i = 0; i < 3000; ++i) {
    carry.step(i);
    find.step(i);
    const int awake = carry.w->awakeBodyCount();
    ASSERT_EQ(awake, find.w->awakeBodyCount()) << "step " << i;
    ASSERT_EQ(carry.w->contacts().size(), find.w->contacts().size()) << "step " << i;
    for (int k = 0; k < n; ++k) {
      const BodyId b{k + 1};  // after the ground
      const Transform x = carry.w->bodyPose(b), y = find.w->bodyPose(b);
      ASSERT_EQ(std::memcmp(x.p.data(), y.p.data(), sizeof(double) * 3), 0) << "step " << i;
      ASSERT_EQ(std::memcmp(x.q.coeffs().data(), y.q.coeffs().data(), sizeof(double) * 4), 0);
    }
    mixed += awake > 0 && awake < n;
    if (i == 1050)
      ground_left = !carry.w->isAwake(carry.boxes[0]) && !hasContact(*carry.w, carry.ground, carry.boxes[0]);
  }
  EXPECT_GT(mixed, 1000);
  EXPECT_TRUE(ground_left);
  EXPECT_FALSE(hasContact(*carry.w, carry.boxes[9], carry.boxes[10]));
  std::printf("[ sleep    ] sleeping pairs carried over: %d steps with sleepers beside awake "
              "bodies, same poses as finding every pair\n", mixed);
}

// Overlapping bodies are separated by impulses, so the correction splits by inverse mass
// (the light box moves 3x as far as the 3x heavier one), momentum stays zero, and the relax
// sweeps take the push-out velocity back: no kinetic energy is added.
TEST(Penetration, CorrectionSplitsByInverseMassWithoutEnergy) {
  WorldDef def;
  def.gravity.setZero();
  World w(def);
  const Vec3 half(0.1, 0.1, 0.1);
  const BodyId light = addBox(w, half, 1.0, Vec3(-0.09, 0, 0));
  const BodyId heavy = addBox(w, half, 3.0, Vec3(0.09, 0, 0));  // 2 cm overlap
  double max_ke = 0.0;
  for (int i = 0; i < 20; ++i) {
    w.step(kDt);
    max_ke = std::max(max_ke, w.kineticEnergy());
  }
  const double dl = -0.09 - w.comPosition(light).x(), dh = w.comPosition(heavy).x() - 0.09;
  EXPECT_NEAR(dl / dh, 3.0, 0.03);
  EXPECT_LT(w.linearMomentum().norm(), 1e-12);
  EXPECT_LT(max_ke, 1e-6);
  std::printf("[ split    ] moved light %.4f m, heavy %.4f m (ratio %.3f), max KE %.1e J\n", dl, dh,
              dl / dh, max_ke);
}

// World::setSleep changes the sleep settings in place: two stacked boxes asleep stay asleep
// (same poses, same contacts) when the thresholds change; sleep off wakes them and keeps them
// awake; sleep on again puts them to sleep time_to_sleep after the switch at the earliest (the
// slow times restart, even those counted before sleep went off); a bad value throws and changes
// nothing.
namespace {
SleepDef sleepDef(bool enabled, double time, double speed) {
  SleepDef d;
  d.enabled = enabled;
  d.time = time;
  d.speed = speed;
  return d;
}
}  // namespace

TEST(Sleeping, SettingsChangedInPlace) {
  World w;
  addGround(w);
  addBox(w, Vec3(0.2, 0.2, 0.2), 1.0, Vec3(0, 0, 0.2));
  const BodyId upper = addBox(w, Vec3(0.2, 0.2, 0.2), 1.0, Vec3(0.05, 0, 0.6));
  ASSERT_LT(stepUntilAsleep(w), 5000);
  const Transform pose = w.bodyPose(upper);
  const size_t contacts = w.contacts().size();

  w.setSleep(sleepDef(true, 2.0, 0.01));  // stricter: a sleeping island is not re-judged
  for (int i = 0; i < 100; ++i) w.step(kDt);
  EXPECT_EQ(w.awakeBodyCount(), 0);
  EXPECT_EQ((w.bodyPose(upper).p - pose.p).norm(), 0.0);
  EXPECT_EQ(w.contacts().size(), contacts);
  EXPECT_TRUE(w.def().sleep.enabled);
  EXPECT_EQ(w.def().sleep.time, 2.0);
  EXPECT_EQ(w.def().sleep.speed, 0.01);

  w.setSleep(sleepDef(false, 0.5, 0.05));
  EXPECT_EQ(w.awakeBodyCount(), 2) << "sleep off must wake the sleepers";
  for (int i = 0; i < 2000; ++i) w.step(kDt);
  EXPECT_EQ(w.awakeBodyCount(), 2) << "asleep with sleep off";
  EXPECT_LT((w.bodyPose(upper).p - pose.p).norm(), 1e-3) << "the stack moved once awake";

  // Slow for 0.5 s with sleep on (time_to_sleep 1 s), then off and on again with 0.3 s: the
  // 0.5 s already counted must not put the stack to sleep at the first step.
  w.setSleep(sleepDef(true, 1.0, 0.05));
  for (int i = 0; i < 500; ++i) w.step(kDt);
  EXPECT_EQ(w.awakeBodyCount(), 2);
  w.setSleep(sleepDef(false, 1.0, 0.05));
  const double t_on = 0.3;
  w.setSleep(sleepDef(true, t_on, 0.05));
  int steps = 0;
  while (w.awakeBodyCount() > 0 && steps < 5000) {
    w.step(kDt);
    ++steps;
  }
  EXPECT_EQ(w.awakeBodyCount(), 0);
  EXPECT_GE(steps * kDt, t_on - 1e-9) << "slept before time_to_sleep after the switch";
  EXPECT_LE(steps * kDt, t_on + 0.05) << "the stack was at rest: it sleeps right at t_on";

  const double nan = std::nan("");
  EXPECT_THROW(w.setSleep(sleepDef(true, -1.0, 0.05)), std::invalid_argument);
  EXPECT_THROW(w.setSleep(sleepDef(true, 0.5, nan)), std::invalid_argument);
  EXPECT_THROW(w.setSleep(sleepDef(false, std::numeric_limits<double>::infinity(), 0.05)),
               std::invalid_argument);
  SleepDef bad = sleepDef(true, 0.5, 0.05);
  bad.rest_time = nan;
  EXPECT_THROW(w.setSleep(bad), std::invalid_argument);
  bad.rest_time = 0.05;
  bad.rest_substeps = -1;
  EXPECT_THROW(w.setSleep(bad), std::invalid_argument);
  bad.rest_substeps = 2;
  bad.rest_relax_iterations = -1;
  EXPECT_THROW(w.setSleep(bad), std::invalid_argument);
  EXPECT_TRUE(w.def().sleep.enabled);
  EXPECT_EQ(w.def().sleep.time, t_on);
  EXPECT_EQ(w.awakeBodyCount(), 0);
}
