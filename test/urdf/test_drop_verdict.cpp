// judgeDrop (drop_check.hpp): each rule of the drop verdict fails on a report that breaks it,
// with a reason that names the rule and the numbers, and a clean report passes.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

#include "ragdoll_sim/drop_check.hpp"

using namespace ragdoll_sim;

namespace {
// A humanoid's drop that held together: root spawned 1 m up, on the ground and still at the end.
DropReport clean() {
  DropReport d;
  d.spawn_z = 1.0;
  d.max_penetration = 0.002;
  d.max_anchor_error = 0.0004;
  d.final_anchor_error = 0.0001;
  d.rest_height = 0.1;
  d.lowest_point = -0.001;
  d.min_lowest_point = -0.003;
  d.final_speed = 0.3;  // a hand swinging in the air
  d.final_contact_speed = 0.01;
  d.max_speed = 4.0;
  d.seconds = 3.0;
  return d;
}

// The verdict fails with exactly one reason, which starts with `rule`.
void expectOnly(const DropReport& d, const std::string& rule, const VerdictRules& rules = VerdictRules()) {
  const DropVerdict v = judgeDrop(d, rules);
  EXPECT_FALSE(v.pass);
  ASSERT_EQ(v.reasons.size(), 1u);
  EXPECT_EQ(v.reasons[0].rfind(rule, 0), 0u) << v.reasons[0];
}
}  // namespace

TEST(DropVerdict, CleanDropPasses) {
  const DropVerdict v = judgeDrop(clean());
  EXPECT_TRUE(v.pass);
  EXPECT_TRUE(v.reasons.empty());
}

TEST(DropVerdict, SankBelowFiveCentimetres) {
  DropReport d = clean();
  d.min_lowest_point = -0.049;
  EXPECT_TRUE(judgeDrop(d).pass);
  d.min_lowest_point = -44.0;
  expectOnly(d, "fell through the ground");
  EXPECT_NE(judgeDrop(d).reasons[0].find("-44000.0 mm < -50.0 mm"), std::string::npos)
      << judgeDrop(d).reasons[0];
  // Measured from the ground the rules name (a world whose floor is 2 m up).
  VerdictRules raised;
  raised.ground_z = 2.0;
  d = clean();
  d.spawn_z = 3.0;
  d.min_lowest_point = 1.9;
  expectOnly(d, "fell through the ground", raised);
}

TEST(DropVerdict, StretchedJoints) {
  DropReport d = clean();
  d.max_anchor_error = 0.0114;
  expectOnly(d, "joints stretched");
  EXPECT_EQ(judgeDrop(d).reasons[0], "joints stretched: anchor error 11.4 mm > 5.0 mm");
}

TEST(DropVerdict, ExplodedFasterThanFreeFall) {
  DropReport d = clean();
  const double limit = std::sqrt(2 * 9.81 * 1.0) + 1.0;  // 5.43 m/s
  d.max_speed = limit - 0.01;
  EXPECT_TRUE(judgeDrop(d).pass);
  d.max_speed = limit + 0.01;
  expectOnly(d, "exploded");
  d.max_speed = 1e4;
  expectOnly(d, "exploded");
}

TEST(DropVerdict, NaN) {
  DropReport d = clean();
  d.finite = false;
  d.seconds = 0.25;
  expectOnly(d, "NaN");
  // A measurement that is itself NaN breaks its rule rather than passing it.
  d = clean();
  d.max_anchor_error = std::numeric_limits<double>::quiet_NaN();
  expectOnly(d, "joints stretched");
}

TEST(DropVerdict, NotAtRestWhenItShouldBe) {
  DropReport d = clean();
  d.final_contact_speed = 0.5;
  expectOnly(d, "not at rest");
  VerdictRules short_run;
  short_run.expect_rest = false;
  EXPECT_TRUE(judgeDrop(d, short_run).pass);
}

TEST(DropVerdict, EveryBrokenRuleHasItsReason) {
  DropReport d = clean();
  d.min_lowest_point = -1.0;
  d.max_anchor_error = 0.1;
  d.max_speed = 100.0;
  d.final_contact_speed = 1.0;
  const DropVerdict v = judgeDrop(d);
  EXPECT_FALSE(v.pass);
  EXPECT_EQ(v.reasons.size(), 4u);
}
