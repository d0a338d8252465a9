// The wide contact batches of ContactSolver (contact_solver.hpp): whatever ranges a step cuts at
// its islands' boundaries, each range finds its own batch and the bits do not depend on the cut;
// the batches are reused step after step, one per range a thread prepares, not one per contact;
// static bodies join no colour; within a colour the manifolds without a carried impulse go last;
// the rows prepared straight into the lanes are the double rows rounded.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

#include "contact_solver.hpp"

namespace ragdoll_sim {
namespace {

constexpr int kIslands = 6;  // pairs of boxes
constexpr double kHalf = 0.1;

// Body 0 the ground; boxes 2i+1 and 2i+2 side by side touch each other and the ground: island i
// is its ground contacts and the contact between them, consecutive in the contact array.
struct Pile {
  std::vector<BodyMotion> motions;
  std::vector<SolverBody> bodies;
  std::vector<Contact> contacts;
};

// Box b's four bottom corners (kHalf below its centre, `origin`) against body a, along +z.
Contact squareContact(int a, int b, const Vec3& origin, double separation) {
  Contact c;
  c.body_a = a;
  c.body_b = b;
  c.origin = origin;
  c.manifold.normal = Vec3::UnitZ();
  c.manifold.count = 4;
  for (int k = 0; k < 4; ++k) {
    c.manifold.points[k].point = Vec3(k & 1 ? kHalf : -kHalf, k & 2 ? kHalf : -kHalf, -kHalf);
    c.manifold.points[k].separation = separation;
  }
  c.static_friction = 0.6;
  c.kinetic_friction = 0.5;
  return c;
}

Contact groundContact(const Pile& p, int b) {
  Contact c = squareContact(0, b, p.motions[b].x, 0.0);
  for (int k = 0; k < 4; ++k) c.manifold.points[k].separation = -0.001 * (1 + (b + k) % 3);
  // last step's impulses, so that the warm start and the friction rows carry something
  for (int k = 0; k < 4; ++k) {
    c.normal_impulse[k] = 0.002 * (1 + k);
    c.friction_impulse[k] = Vec3(0.0004 * (k - 1), 0.0003, 0.0);
  }
  c.impulse_h = 1e-3;
  return c;
}

Contact sideContact(const Pile& p, int a, int b) {
  Contact c;
  c.body_a = a;
  c.body_b = b;
  c.origin = p.motions[a].x;
  c.manifold.normal = Vec3::UnitX();
  c.manifold.count = 2;
  c.manifold.points[0].point = Vec3(kHalf, 0.0, 0.05);
  c.manifold.points[1].point = Vec3(kHalf, 0.0, -0.05);
  c.manifold.points[0].separation = c.manifold.points[1].separation = -0.002;
  c.static_friction = c.kinetic_friction = 0.4;
  return c;
}

// sides false: no contact between the boxes, so each box has one contact and the order the
// contacts are solved in (slot order in double, colour order in lanes) changes nothing.
Pile makePile(bool sides) {
  Pile p;
  const int n = 1 + 2 * kIslands;
  p.motions.resize(n);
  p.bodies.resize(n);  // body 0: the identity solver body of the ground
  for (int b = 1; b < n; ++b) {
    BodyMotion& m = p.motions[b];
    m.awake = true;
    m.x = Vec3(0.21 * ((b - 1) % 2) + 1.0 * ((b - 1) / 2), 0.0, kHalf);
    SolverBody& s = p.bodies[b];
    s.inv_mass = 1.0 / (1.0 + 0.1 * b);
    s.inv_inertia = (150.0 + b) * Mat3::Identity();
    s.v = Vec3(0.05 * b, -0.02 * b, -0.3 - 0.01 * b);
    s.w = Vec3(0.1, -0.2 * (b % 3), 0.05 * b);
  }
  for (int i = 0; i < kIslands; ++i) {
    const int a = 1 + 2 * i, b = a + 1;
    p.contacts.push_back(groundContact(p, a));
    if (sides) p.contacts.push_back(sideContact(p, a, b));
    p.contacts.push_back(groundContact(p, b));
  }
  return p;
}

// One substep of 1 ms with one relax sweep, the contacts in `lanes` (1: double rows).
StepContext contactContext(int lanes, const SolverSettings& settings,
                           std::vector<SolverBody>& bodies, const std::vector<BodyMotion>& motions) {
  StepContext ctx;
  ctx.dt = ctx.h = 1e-3;
  ctx.inv_h = 1.0 / ctx.h;
  ctx.substeps = ctx.relax = 1;
  ctx.lanes = lanes;
  ctx.contact_softness = Softness::make(30.0, 10.0, ctx.h);
  ctx.settings = &settings;
  ctx.bodies = &bodies;
  ctx.motions = &motions;
  return ctx;
}

struct Result {
  std::vector<SolverBody> bodies;
  std::vector<Contact> contacts;
};

// One step of the pile's contacts (warm start, biased and relax sweeps, restitution, stored
// impulses), the islands grouped into the ranges that start at cuts (in island numbers).
Result step(ContactSolver& solver, const std::vector<int>& cuts, int lanes, bool sides = true) {
  Pile p = makePile(sides);
  const int per = sides ? 3 : 2;  // contacts per island
  SolverSettings settings;
  const StepContext ctx = contactContext(lanes, settings, p.bodies, p.motions);
  solver.selectActive(p.contacts, p.motions);
  solver.resize(1);
  std::vector<std::pair<int, int>> ranges;
  for (size_t k = 0; k < cuts.size(); ++k)
    ranges.emplace_back(per * cuts[k], k + 1 < cuts.size() ? per * cuts[k + 1] : per * kIslands);
  for (const auto& [b, e] : ranges) solver.prepare(p.contacts, ctx, b, e);
  for (const auto& [b, e] : ranges) {
    solver.warmStart(ctx, b, e, true);
    solver.solve(ctx, true, b, e, false);
    solver.solve(ctx, false, b, e, true);
    solver.applyRestitution(ctx, b, e);
    solver.storeImpulses(p.contacts, ctx.h, b, e);
  }
  return {p.bodies, p.contacts};
}

void expectSameBits(const Result& x, const Result& y, const char* what) {
  for (size_t b = 0; b < x.bodies.size(); ++b)
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(x.bodies[b].v[k], y.bodies[b].v[k]) << what << " body " << b;
      EXPECT_EQ(x.bodies[b].w[k], y.bodies[b].w[k]) << what << " body " << b;
    }
  for (size_t c = 0; c < x.contacts.size(); ++c)
    for (int i = 0; i < x.contacts[c].manifold.count; ++i)
      EXPECT_EQ(x.contacts[c].normal_impulse[i], y.contacts[c].normal_impulse[i])
          << what << " contact " << c << " point " << i;
}

TEST(ContactBatches, EachRangeFindsItsBatchWhateverTheCut) {
  for (int lanes : {4, 8}) {
    ContactSolver solver;
    const Result whole = step(solver, {0}, lanes);
    bool pushed = false;  // the step did something: a normal impulse somewhere
    for (const Contact& c : whole.contacts) pushed |= c.normal_impulse[0] > 0.0;
    EXPECT_TRUE(pushed);
    // Cuts that move from step to step: a range's first slot holds another range's batch of an
    // earlier step, or none.
    const std::vector<std::vector<int>> cuts = {{0, 1}, {0, 2, 5}, {0, 3}, {0, 1, 2, 3, 4, 5}, {0}};
    for (const auto& c : cuts) expectSameBits(whole, step(solver, c, lanes), "cut");
    EXPECT_LE(solver.batchCount(), kIslands);  // the most ranges of one step
  }
}

// Static bodies join no colour (ContactBatch::build counts only the movable ones): the pile's
// twelve ground contacts share the ground, yet with the boxes' side contacts the six islands in
// one range take two colours, and every contact is in the lanes.
TEST(ContactBatches, TheGroundJoinsNoColour) {
  ContactSolver solver;
  step(solver, {0}, 4);
  const ContactBatch* batch = solver.batchAt(0);
  ASSERT_NE(batch, nullptr);
  EXPECT_EQ(batch->colourCount(), 2);
  EXPECT_TRUE(batch->scalar().empty());
}

// Within a colour the manifolds that carry no normal impulse go after those that do, so that
// the speculative ones share blocks the sweeps skip as idle: with every other island's ground
// contacts cleared, the twelve contacts (one colour, four points each) take the lanes carried
// first, whatever their slot order.
TEST(ContactBatches, TheManifoldsWithoutImpulseGoLastInTheirColour) {
  Pile p = makePile(false);
  for (size_t c = 0; c < p.contacts.size(); ++c)
    if ((c / 2) % 2 == 1)
      for (int k = 0; k < 4; ++k) p.contacts[c].normal_impulse[k] = 0.0;
  SolverSettings settings;
  const StepContext ctx = contactContext(8, settings, p.bodies, p.motions);
  ContactSolver solver;
  solver.selectActive(p.contacts, p.motions);
  solver.resize(1);
  const int n = int(p.contacts.size());
  solver.prepare(p.contacts, ctx, 0, n);
  const ContactBatch* batch = solver.batchAt(0);
  ASSERT_NE(batch, nullptr);
  ASSERT_EQ(batch->colourCount(), 1);
  int last_carried = -1, first_clear = n;
  for (int c = 0; c < n; ++c) {
    ASSERT_GE(batch->laneOf(c), 0);
    if ((c / 2) % 2 == 1) first_clear = std::min(first_clear, batch->laneOf(c));
    else last_carried = std::max(last_carried, batch->laneOf(c));
  }
  EXPECT_LT(last_carried, first_clear);
}

// The wide path solves something: its bits differ from the double rows' (else the batches
// would not be found at all and the comparison above would hold trivially).
TEST(ContactBatches, TheLanesSolveTheRanges) {
  ContactSolver scalar, wide;
  const Result d = step(scalar, {0, 2}, 1);
  const Result f = step(wide, {0, 2}, 4);
  EXPECT_EQ(scalar.batchCount(), 0);
  EXPECT_EQ(wide.batchCount(), 2);
  bool differs = false;
  for (size_t b = 1; b < d.bodies.size(); ++b) differs |= d.bodies[b].v != f.bodies[b].v;
  EXPECT_TRUE(differs);
}

// The rows that prepare writes straight into the lanes are the double rows rounded: a step in
// lanes ends within float rounding of the same step in double (a row in the wrong place, a
// missing tangent or impulse would be off by the size of the impulses).
TEST(ContactBatches, TheLanesAgreeWithTheDoubleRows) {
  for (int lanes : {4, 8}) {
    ContactSolver scalar, wide;
    const Result d = step(scalar, {0, 2}, 1, false);
    const Result f = step(wide, {0, 2}, lanes, false);
    double worst = 0.0, largest = 0.0;
    for (size_t b = 1; b < d.bodies.size(); ++b) {
      worst = std::max(worst, (d.bodies[b].v - f.bodies[b].v).norm());
      worst = std::max(worst, 0.1 * (d.bodies[b].w - f.bodies[b].w).norm());  // 0.1 m lever
      largest = std::max(largest, d.bodies[b].v.norm());
    }
    EXPECT_LT(worst, 1e-5 * largest) << "lanes " << lanes;
    double impulse_error = 0.0, impulse_scale = 0.0;
    for (size_t c = 0; c < d.contacts.size(); ++c)
      for (int i = 0; i < d.contacts[c].manifold.count; ++i) {
        impulse_error = std::max(impulse_error, std::abs(d.contacts[c].normal_impulse[i] -
                                                         f.contacts[c].normal_impulse[i]));
        impulse_error = std::max(impulse_error, (d.contacts[c].friction_impulse[i] -
                                                 f.contacts[c].friction_impulse[i]).norm());
        impulse_scale = std::max(impulse_scale, d.contacts[c].normal_impulse[i]);
      }
    EXPECT_GT(impulse_scale, 0.0);
    EXPECT_LT(impulse_error, 1e-5 * impulse_scale) << "lanes " << lanes;
  }
}

// Boxes 1 and 2 stacked on the ground (body 0) as contacts {stack, ground} or {ground}: the
// stack's points `stack_depth` deep, box 1's ground points apart by 0.1 mm.
struct Stack {
  std::vector<BodyMotion> motions{3};
  std::vector<SolverBody> bodies{3};
  std::vector<Contact> contacts;
};
Stack makeStack(double stack_depth) {
  Stack p;
  for (int b = 1; b <= 2; ++b) {
    p.motions[b].awake = true;
    p.motions[b].x = Vec3(0.0, 0.0, kHalf * (2 * b - 1));
    p.bodies[b].inv_mass = 1.0;
    p.bodies[b].inv_inertia = 150.0 * Mat3::Identity();
  }
  if (stack_depth > 0.0) p.contacts.push_back(squareContact(1, 2, p.motions[2].x, -stack_depth));
  p.contacts.push_back(squareContact(0, 1, p.motions[1].x, 0.0001));
  return p;
}

// Box 1 after the first position sweep (relaxed: a relax sweep updated the separations after
// the positions moved by `sink`), with the contacts in lanes or in double.
SolverBody firstSweep(int lanes, double stack_depth, double sink, bool relaxed) {
  Stack p = makeStack(stack_depth);
  SolverSettings settings;
  const StepContext ctx = contactContext(lanes, settings, p.bodies, p.motions);
  ContactSolver solver;
  const int n = int(solver.selectActive(p.contacts, p.motions).size());
  solver.resize(1);
  solver.prepare(p.contacts, ctx, 0, n);
  solver.warmStart(ctx, 0, n, true);
  solver.solve(ctx, true, 0, n, false);
  p.bodies[1].dp = Vec3(0.0, 0.0, -sink);  // the positions advance
  p.bodies[2].dp = Vec3(0.0, 0.0, -sink);
  if (relaxed) solver.solve(ctx, false, 0, n, true);
  solver.project(ctx, 0, n, 1);
  return p.bodies[1];
}

// The first position sweep passes over the wide constraints whose points the lanes' last
// relax sweep found apart beyond -linear_slop (ContactBatch::apartAtLastUpdate). It must move
// the bodies exactly as the double rows' sweep, which looks at every point: box 1's ground
// contact, apart at the last update, is pushed into the ground by the stack's projection
// before the sweep reaches it; and alone, it sank after the last update (no relax sweep since).
TEST(ContactBatches, TheFirstPositionSweepMovesAsTheDoubleRows) {
  struct Case {
    double stack_depth, sink;
    bool relaxed, moves;  // moves: the ground contact moves box 1
  };
  for (const Case& c : {Case{0.006, 0.0, true, true}, Case{0.0, 0.002, false, true},
                        Case{0.0, 0.0, true, false}}) {
    const SolverBody d = firstSweep(1, c.stack_depth, c.sink, c.relaxed);
    EXPECT_EQ(d.dp.z() != -c.sink, c.moves) << c.stack_depth;
    for (int lanes : {4, 8}) {
      const SolverBody f = firstSweep(lanes, c.stack_depth, c.sink, c.relaxed);
      for (int i = 0; i < 3; ++i) EXPECT_EQ(d.dp[i], f.dp[i]) << c.stack_depth << " " << lanes;
      for (int i = 0; i < 4; ++i)
        EXPECT_EQ(d.dq.coeffs()[i], f.dq.coeffs()[i]) << c.stack_depth << " " << lanes;
    }
  }
}

}  // namespace
}  // namespace ragdoll_sim
