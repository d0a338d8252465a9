// Sleeping: islands fall asleep when slow and wake on an impulse, a settled world keeps its
// poses and contacts, static bodies moved beside sleepers, carried pairs, settings changed in
// place.
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

// A body at rest falls asleep after time_to_sleep and wakes on an impulse.
TEST(Sleep, RestingBoxSleepsAndWakesOnImpulse) {
  World w;
  addGround(w);
  const Vec3 half(0.2, 0.2, 0.1);
  const BodyId box = addBody(w, Geometry::box(half), 2.0, boxInertia(half, 2.0),
                             Transform(Vec3(0, 0, 0.2), Quat::Identity()), Material());
  int asleep_at = -1;
  for (int i = 0; i < 3000 && asleep_at < 0; ++i) {
    w.step(kDt);
    if (!w.isAwake(box)) asleep_at = i;
  }
  ASSERT_GT(asleep_at, 0) << "never slept";
  EXPECT_EQ(w.awakeBodyCount(), 0);
  const Vec3 rest = w.comPosition(box);
  for (int i = 0; i < 100; ++i) w.step(kDt);
  EXPECT_EQ((w.comPosition(box) - rest).norm(), 0.0);  // asleep: not integrated at all
  w.applyLinearImpulse(box, Vec3(2.0, 0, 0), w.comPosition(box));
  EXPECT_TRUE(w.isAwake(box));
  for (int i = 0; i < 100; ++i) w.step(kDt);
  EXPECT_GT(w.comPosition(box).x() - rest.x(), 0.01);
  std::printf("[ sleep    ] box asleep after %.3f s\n", (asleep_at + 1) * kDt);
}

// The sleep test is Box2D v3's: max(|v|, extent |w|) below sleep_speed for time_to_sleep. A
// sphere drifting at 0.8 sleep_speed and spinning at 0.8 sleep_speed / extent sleeps (a sum of
// the two would keep it awake); at 1.2 sleep_speed in either it stays awake.
TEST(Sleep, SlowestOfDriftAndSpinDecides) {
  for (const double f : {0.8, 1.2}) {
    WorldDef wd;
    wd.gravity.setZero();
    World w(wd);
    const double r = 0.1, m = 1.0;
    const BodyId b = addBody(w, Geometry::sphere(r), m, Mat3::Identity() * 0.4 * m * r * r,
                             Transform(), Material());
    w.setBodyState(b, Transform(), Vec3(f * wd.sleep.speed, 0, 0), Vec3(0, 0, f * wd.sleep.speed / r));
    for (int i = 0; i < 1000; ++i) w.step(kDt);
    EXPECT_EQ(w.isAwake(b), f > 1.0) << "speed factor " << f;
  }
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

// A resting box on the ground carries a light bar on a frictionless vertical hinge at the
// bar's end, turning at 1 rad/s: gravity has no torque about the axis and nothing dissipates
// the turn, so the bar's ends move at 0.3 m/s for ever and every per-body speed test keeps the
// island awake. Its kinetic energy is far below that of the island's mass at the sleep speed:
// the island sleeps within a second of sleep time, and wakes on an impulse.
TEST(Sleep, LimbTurningAboutAFrictionlessJointStillSleeps) {
  World w;
  addGround(w);
  const Vec3 half(0.3, 0.2, 0.1);
  const BodyId box = addBox(w, half, 20.0, Vec3(0, 0, 0.1));
  const BodyId bar = addBox(w, Vec3(0.15, 0.02, 0.02), 0.5, Vec3(0.45, 0, 0.35));
  HingeJointDef h;
  h.body_a = box;
  h.body_b = bar;
  h.frame_a = Transform(Vec3(0.3, 0, 0.25), Quat::Identity());  // a post above the box's edge
  h.frame_b = Transform(Vec3(-0.15, 0, 0), Quat::Identity());
  h.axis = Vec3::UnitZ();
  w.createHingeJoint(h);
  for (int i = 0; i < 300; ++i) w.step(kDt);  // the box settles
  const BodyState s = w.bodyState(bar);
  w.setBodyState(bar, s.pose, Vec3(0, 0.15, 0), Vec3(0, 0, 1.0));  // 1 rad/s about the hinge
  int steps = 0;
  double turned = 0.0;
  while (w.isAwake(bar) && steps < 5000) {
    w.step(kDt);
    turned += w.bodyState(bar).angular_velocity.z() * kDt;
    ++steps;
  }
  std::printf("[ spin     ] the bar turned %.2f rad and slept after %d steps\n", turned, steps);
  EXPECT_LT(steps, 1500) << "the island never sleeps";
  EXPECT_GT(turned, 0.3) << "it slept before the turn was seen";
  EXPECT_FALSE(w.isAwake(box));
  w.applyLinearImpulse(bar, Vec3(0, 0.1, 0), w.comPosition(bar));
  w.step(kDt);
  EXPECT_TRUE(w.isAwake(box));

  // The rule off (island_speed 0): the same turn keeps the island awake (what it fixes).
  SleepDef off = w.def().sleep;
  off.island_speed = 0.0;
  w.setSleep(off);
  w.setBodyState(bar, w.bodyPose(bar), w.bodyState(bar).linear_velocity, Vec3(0, 0, 1.0));
  for (int i = 0; i < 1500; ++i) w.step(kDt);
  EXPECT_TRUE(w.isAwake(bar));
}
