// Resting islands on fewer substeps (SleepDef::rest_substeps): when an island takes them, that
// it leaves them as soon as something in it moves, and that what rests on them stays put and
// sleeps as it does on the full count.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "ragdoll_sim/world.hpp"
#include "scene_util.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::test;

namespace {
constexpr double kDt = 1e-3;

WorldDef withRest(bool on) {
  WorldDef d;
  if (!on) d.sleep.rest_substeps = 0;
  return d;
}

// Steps until everything sleeps (at most max_steps); returns the step count, -1 if never.
int stepsToSleep(World& w, int max_steps) {
  for (int i = 1; i <= max_steps; ++i) {
    w.step(kDt);
    if (w.awakeBodyCount() == 0) return i;
  }
  return -1;
}
}  // namespace

// A box dropped 1 cm onto the ground: its island takes the rest substeps once it has been slow
// for rest_time, not before, stays awake on them until time_to_sleep, and leaves them on the
// step after an impulse (which wakes it and restarts its sleep timer).
TEST(RestSubsteps, TakenAfterRestTimeAndLeftOnImpulse) {
  const WorldDef def;
  ASSERT_GT(def.sleep.rest_substeps, 0);
  ASSERT_LT(def.sleep.rest_substeps, def.solver.substeps);
  World w(def);
  addGround(w);
  const Vec3 half(0.2, 0.2, 0.1);
  const BodyId box = addBox(w, half, 2.0, Vec3(0, 0, 0.11));
  int slow_from = -1, resting_from = -1;
  for (int i = 1; i <= 400 && resting_from < 0; ++i) {
    w.step(kDt);
    const BodyState s = w.bodyState(box);
    // the sleep test: max(|v|, extent |w|), extent = the box's farthest point from its centre
    const bool slow = std::max(s.linear_velocity.norm(), half.norm() * s.angular_velocity.norm()) <
                      def.sleep.speed;
    if (!slow) slow_from = -1;
    else if (slow_from < 0) slow_from = i;
    if (w.islandCounters().resting_bodies > 0) resting_from = i;
  }
  ASSERT_GT(resting_from, 0) << "never took the rest substeps";
  ASSERT_GT(slow_from, 0);
  // The step that finds the island slow for rest_time is solved after that many slow steps.
  EXPECT_GE(resting_from - slow_from, int(def.sleep.rest_time / kDt) - 1);
  EXPECT_EQ(w.islandCounters().resting_islands, 1);
  EXPECT_TRUE(w.isAwake(box));

  w.applyLinearImpulse(box, Vec3(1.0, 0, 0), w.comPosition(box));
  w.step(kDt);
  EXPECT_EQ(w.islandCounters().resting_bodies, 0);
  EXPECT_EQ(w.islandCounters().bodies, 1);
  std::printf("[ rest     ] slow from step %d, rest substeps from step %d\n", slow_from, resting_from);
}

// The rest settings changed in place (World::setSleep) apply from the next step: a box resting
// on the rest substeps leaves them when rest_substeps goes to 0 or rest_time grows past the time
// it has been slow, and takes them again when they come back, without waking or moving.
TEST(RestSubsteps, SettingsChangedInPlace) {
  World w;
  addGround(w);
  const BodyId box = addBox(w, Vec3(0.2, 0.2, 0.1), 2.0, Vec3(0, 0, 0.11));
  SleepDef sleep = w.def().sleep;
  sleep.time = 10.0;  // stays awake through the test
  w.setSleep(sleep);
  for (int i = 0; i < 300; ++i) w.step(kDt);
  ASSERT_EQ(w.islandCounters().resting_islands, 1);
  const Vec3 p0 = w.bodyPose(box).p;

  SleepDef off = sleep;
  off.rest_substeps = 0;
  w.setSleep(off);
  w.step(kDt);
  EXPECT_EQ(w.islandCounters().resting_islands, 0) << "rest_substeps 0 must turn them off";
  EXPECT_EQ(w.def().sleep.rest_substeps, 0);
  w.setSleep(sleep);
  w.step(kDt);
  EXPECT_EQ(w.islandCounters().resting_islands, 1) << "back on: the box has been slow long";

  // Slow for ~0.3 s: a rest_time of 1 s is not reached yet, and is 0.7 s later.
  SleepDef later = sleep;
  later.rest_time = 1.0;
  w.setSleep(later);
  int steps = 0;
  do {
    w.step(kDt);
    ++steps;
  } while (w.islandCounters().resting_islands == 0 && steps < 2000);
  EXPECT_GT(steps, 600) << "rest_time 1 s taken too early";
  EXPECT_LT(steps, 800) << "rest_time 1 s not taken about 0.7 s later";
  EXPECT_TRUE(w.isAwake(box));
  EXPECT_LT((w.bodyPose(box).p - p0).norm(), 1e-4) << "the box moved at the switches";
}

// Off (rest_substeps 0) no island ever takes them.
TEST(RestSubsteps, OffNeverTaken) {
  World w(withRest(false));
  addGround(w);
  addBox(w, Vec3(0.2, 0.2, 0.1), 2.0, Vec3(0, 0, 0.11));
  for (int i = 0; i < 600; ++i) {
    w.step(kDt);
    ASSERT_EQ(w.islandCounters().resting_islands, 0) << "step " << i;
  }
}

// Ten stacked boxes (Gauss-Seidel's slowest case: the load goes down the stack one contact per
// sweep) rest and sleep on the rest substeps as on the full count: no contact deeper than the
// linear slop, each box within 2 mm of the full count's rest pose, asleep no more than 0.1 s
// later.
TEST(RestSubsteps, TenBoxStackRestsAndSleepsAsOnFullCount) {
  const Vec3 half(0.25, 0.25, 0.25);
  std::vector<Vec3> rest[2];
  int slept[2];
  for (const bool on : {false, true}) {
    World w(withRest(on));
    addGround(w);
    std::vector<BodyId> boxes;
    for (int i = 0; i < 10; ++i) boxes.push_back(addBox(w, half, 1.0, Vec3(0, 0, 0.25 + 0.5 * i)));
    int resting_steps = 0;
    slept[on] = -1;
    for (int i = 1; i <= 3000 && slept[on] < 0; ++i) {
      w.step(kDt);
      resting_steps += w.islandCounters().resting_islands;
      if (w.awakeBodyCount() == 0) slept[on] = i;
    }
    EXPECT_EQ(resting_steps > 0, on);
    for (const BodyId b : boxes) rest[on].push_back(w.comPosition(b));
  }
  ASSERT_GT(slept[0], 0);
  ASSERT_GT(slept[1], 0) << "the stack never slept on the rest substeps";
  EXPECT_LE(slept[1], slept[0] + 100);
  double moved = 0.0;
  double deepest = 0.0;  // on the rest substeps, of the ground and the nine box-box contacts
  for (int i = 0; i < 10; ++i) {
    moved = std::max(moved, (rest[1][i] - rest[0][i]).norm());
    const double below = i == 0 ? 0.0 : rest[1][i - 1].z() + half.z();
    deepest = std::max(deepest, below - (rest[1][i].z() - half.z()));
  }
  // The stack settles 0.08 mm lower per contact than on the full count, within the slop.
  EXPECT_LT(moved, 2e-3);
  EXPECT_LT(deepest, SolverSettings().linear_slop);
  std::printf("[ rest     ] 10-box stack asleep after %d steps (full count %d), poses within %.2e m, "
              "deepest contact %.2e m\n", slept[1], slept[0], moved, deepest);
}

// A 1 kg box on a 10 g plate (100 : 1) rests on the full substeps but, in the float rows, slips
// on the rest substeps' one relax sweep. The island that sped up on them takes the full count
// until it sleeps: it leaves the rest substeps once and sleeps within a second (taking them
// again each time it was slow for rest_time, it stayed awake past 5 s, switching back some 24
// times). Asleep, it may take them again: woken by a nudge, it does the same once more.
TEST(RestSubsteps, AnIslandThatSlipsOnThemTakesTheFullCountUntilItSleeps) {
  WorldDef def;
  def.solver.lanes = 8;  // forced: two bodies take the double rows (World::kLanesMinBodies)
  World w(def);
  addGround(w);
  addBox(w, Vec3(0.1, 0.1, 0.02), 0.01, Vec3(0, 0, 0.0205));
  const BodyId box = addBox(w, Vec3(0.2, 0.2, 0.1), 1.0, Vec3(0, 0, 0.1415));
  for (const char* episode : {"dropped", "nudged"}) {
    int slept = -1, rest_steps = 0, left = 0;
    bool resting = false;
    for (int i = 1; i <= 5000 && slept < 0; ++i) {
      w.step(kDt);
      const bool now = w.islandCounters().resting_islands > 0;
      rest_steps += now;
      if (resting && !now && w.awakeBodyCount() > 0) ++left;
      resting = now;
      if (w.awakeBodyCount() == 0) slept = i;
    }
    EXPECT_GT(rest_steps, 0) << episode;
    EXPECT_EQ(left, 1) << episode;
    ASSERT_GT(slept, 0) << episode << ": awake after 5 s";
    EXPECT_LT(slept, 1000) << episode;
    std::printf("[ rest     ] box on a plate 100 : 1, %s: %d steps on the rest substeps, left them "
                "%d time(s), asleep after %d steps\n", episode, rest_steps, left, slept);
    w.applyLinearImpulse(box, Vec3(0.0, 0.0, -1e-3), w.comPosition(box));
  }
}

// A box on a 20 degree slope (mu 0.8 > tan 20 deg): static friction holds it on the rest
// substeps; from the step it first takes them to the step it sleeps it creeps less than 0.1 mm.
TEST(RestSubsteps, StaticFrictionHoldsOnSlope) {
  Material m;
  m.static_friction = m.kinetic_friction = 0.8;
  const double slope = 20.0 * M_PI / 180.0;
  const Quat tilt(Eigen::AngleAxisd(slope, Vec3::UnitY()));
  World w;
  addGround(w, m, tilt);
  const Vec3 half(0.1, 0.1, 0.05);
  const BodyId box = addBody(w, Geometry::box(half), 1.0, boxInertia(half, 1.0),
                             Transform(tilt * Vec3(0, 0, 0.0505), tilt), m);
  Vec3 at_rest = Vec3::Constant(NAN);
  int slept = -1;
  for (int i = 1; i <= 2000 && slept < 0; ++i) {
    w.step(kDt);
    if (!at_rest.allFinite() && w.islandCounters().resting_bodies > 0) at_rest = w.comPosition(box);
    if (!w.isAwake(box)) slept = i;
  }
  ASSERT_TRUE(at_rest.allFinite()) << "never took the rest substeps";
  ASSERT_GT(slept, 0) << "never slept";
  const double creep = (w.comPosition(box) - at_rest).norm();
  EXPECT_LT(creep, 1e-4);
  std::printf("[ rest     ] box on 20 deg slope: creep %.2e m on the rest substeps, asleep at step %d\n",
              creep, slept);
}

// A sphere dropped onto a box that rests on the rest substeps: the step whose island holds both
// (a contact, speculative first, joins them) takes the full count, and the box is not left
// asleep under it.
TEST(RestSubsteps, ArrivingBodyBringsFullCount) {
  World w;
  addGround(w);
  const BodyId box = addBox(w, Vec3(0.2, 0.2, 0.1), 2.0, Vec3(0, 0, 0.1));
  int resting = 0;
  for (int i = 0; i < 300; ++i) {  // within time_to_sleep: awake, resting from ~0.05 s
    w.step(kDt);
    resting += w.islandCounters().resting_bodies;
  }
  ASSERT_GT(resting, 0) << "the box never took the rest substeps";
  const BodyId ball = addSphere(w, 0.05, 0.5, Vec3(0, 0, 0.45));
  int joined = 0;
  for (int i = 0; i < 400; ++i) {
    w.step(kDt);
    const IslandCounters c = w.islandCounters();
    if (c.largest_island == 2 && w.bodyState(ball).linear_velocity.norm() > 0.1) {
      ++joined;
      EXPECT_EQ(c.resting_bodies, 0) << "step " << i;
    }
  }
  EXPECT_GT(joined, 0) << "the sphere never joined the box's island while moving";
  EXPECT_NEAR(w.comPosition(ball).z(), 0.25, 2e-3);  // on the box (top at 0.2)
  EXPECT_GT(stepsToSleep(w, 2000), 0);
  EXPECT_NEAR(w.comPosition(box).z(), 0.1, 2e-3);
  std::printf("[ rest     ] sphere onto a resting box: %d steps in one island while it moved\n", joined);
}

// 64 boxes in 8 jointed chains lying side by side on the ground: one island, which World
// splits in two halves. At rest it takes the rest substeps as a whole. A box dropped beside it
// is an island of its own, solved along with the halves in their substep loop: while it falls
// the raft keeps the full count, whatever its own state. The same poses on 1 and 2 threads.
TEST(RestSubsteps, SplitIslandRestsTogetherWithItsAttachedIslands) {
  std::vector<Transform> end[2];
  for (const int threads : {1, 2}) {
    WorldDef def;
    def.threads = threads;
    World w(def);
    addGround(w);
    const double h = 0.1;
    std::vector<BodyId> boxes;
    for (int c = 0; c < 8; ++c)
      for (int k = 0; k < 8; ++k) {
        const BodyId b = addBox(w, Vec3(h, h, h), 1.0, Vec3(2 * h * k, 2 * h * c, h));
        if (k > 0) chainLink(w, boxes.back(), b, h);
        boxes.push_back(b);
      }
    int split_resting = 0;
    for (int i = 0; i < 100; ++i) {
      w.step(kDt);
      const IslandCounters n = w.islandCounters();
      ASSERT_EQ(n.split_islands, 1) << "step " << i;
      split_resting += n.resting_islands;
    }
    EXPECT_GT(split_resting, 0) << "the split raft never took the rest substeps";
    ASSERT_EQ(w.islandCounters().resting_bodies, 64);
    const BodyId ball = addSphere(w, 0.05, 0.5, Vec3(5, 5, 0.4));
    int falling = 0;
    for (int i = 0; i < 300; ++i) {
      w.step(kDt);
      const IslandCounters n = w.islandCounters();
      if (w.bodyState(ball).linear_velocity.norm() > 0.1) {
        ++falling;
        EXPECT_EQ(n.islands, 2) << "step " << i;
        EXPECT_EQ(n.split_islands, 1) << "step " << i;
        EXPECT_EQ(n.resting_islands, 0) << "step " << i;
      }
    }
    EXPECT_GT(falling, 100);
    EXPECT_NEAR(w.comPosition(ball).z(), 0.05, 2e-3);
    for (const BodyId b : boxes) end[threads - 1].push_back(w.bodyPose(b));
  }
  for (size_t k = 0; k < end[0].size(); ++k) {
    ASSERT_EQ(std::memcmp(end[0][k].p.data(), end[1][k].p.data(), sizeof(double) * 3), 0) << k;
    ASSERT_EQ(std::memcmp(end[0][k].q.coeffs().data(), end[1][k].q.coeffs().data(), sizeof(double) * 4), 0);
  }
}

// A chain of five 1 kg links (addChain) hanging at rest from a static frame: its top anchor
// carries the chain's weight. Joint and contact impulses are per substep, so when the island
// goes onto the rest substeps (h from dt/3 to dt/2) the warm start carries them over as the
// same force (warmStartScale): the anchor's force stays within 15 % of the weight through the
// switch (88 % on the first rest step; the rest of the dip is the softer joints of the shorter
// substep). Without the rescale it dips to 80 %.
TEST(RestSubsteps, WarmStartKeepsTheForceAcrossTheSwitch) {
  World w;
  std::vector<JointId> joints;
  const double mass = 1.0;
  addChain(w, Vec3(0, 0, 2.0), std::vector<double>(5, mass), -Vec3::UnitZ(), &joints);
  const JointId anchor = joints.front();
  const double weight = 5 * mass * 9.81;
  int switched = -1;
  double at_switch = 0.0, worst = 0.0;
  for (int i = 1; i <= 300; ++i) {
    w.step(kDt);
    const double force = w.jointForce(anchor) / weight;
    if (switched < 0 && w.islandCounters().resting_bodies > 0) {
      switched = i;
      at_switch = force;
    }
    if (switched > 0 && i < switched + 10) worst = std::max(worst, std::abs(force - 1.0));
  }
  ASSERT_GT(switched, 0) << "the chain never took the rest substeps";
  EXPECT_GT(at_switch, 0.85);
  EXPECT_LT(worst, 0.15);
  std::printf("[ rest     ] hanging chain: rest substeps from step %d, anchor force %.3f of the "
              "weight there, within %.3f over 10 steps\n", switched, at_switch, worst);
}
