// Contact reports of two worlds compared bit for bit (the same scene on different thread counts).
#pragma once

#include <gtest/gtest.h>

#include <cstring>
#include <string>
#include <vector>

#include "ragdoll_sim/world.hpp"

namespace ragdoll_sim {
namespace test {

inline void expectSameBits(const Vec3& a, const Vec3& b, const std::string& what) {
  EXPECT_EQ(std::memcmp(a.data(), b.data(), sizeof(double) * 3), 0) << what;
}

// The reports of one and two after the same step (labelled `at`); reported and moving count
// the reports and their points that separate or approach.
inline void expectSameContactReports(const World& one, const World& two, const std::string& at,
                                     int& reported, int& moving) {
  std::vector<ContactReport> r1, r2;
  one.contactReports(r1);
  two.contactReports(r2);
  ASSERT_EQ(r1.size(), r2.size()) << at;
  for (size_t k = 0; k < r1.size(); ++k) {
    const ContactReport &a = r1[k], &b = r2[k];
    const std::string where = at + ", report " + std::to_string(k);
    ASSERT_EQ(a.body_a.index, b.body_a.index) << where;
    ASSERT_EQ(a.body_b.index, b.body_b.index) << where;
    ASSERT_EQ(a.count, b.count) << where;
    // the lever arms come from the step's displacement dp, the points' speeds from its dq
    expectSameBits(a.torque_a, b.torque_a, where + " torque_a");
    expectSameBits(a.torque_b, b.torque_b, where + " torque_b");
    for (int p = 0; p < a.count; ++p) {
      EXPECT_EQ(a.points[p].separating_speed, b.points[p].separating_speed) << where;
      moving += a.points[p].separating_speed != 0.0;
    }
    ++reported;
  }
}

}  // namespace test
}  // namespace ragdoll_sim
