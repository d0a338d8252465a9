// The core builds with scalar Eigen (CMakeLists.txt: EIGEN_DONT_VECTORIZE, with 16-byte
// alignment bounds). A package that includes the core headers with Eigen's defaults must see
// the same layout of every public struct, or passing a BodyDef across would read garbage.
#include <gtest/gtest.h>

#include "layout_probe.hpp"

namespace ragdoll_sim::test {
namespace {

TEST(PublicLayout, SameAsWithDefaultEigen) {
#ifndef EIGEN_DONT_VECTORIZE
  GTEST_SKIP() << "the core is built with vectorized Eigen: nothing to compare";
#endif
  const std::vector<LayoutEntry> core = RAGDOLL_SIM_LAYOUT_ENTRIES;
  const std::vector<LayoutEntry> outside = layoutWithDefaultEigen();
  ASSERT_EQ(core.size(), outside.size());
  EXPECT_EQ(alignof(Quat), 16u);
  for (std::size_t i = 0; i < core.size(); ++i) {
    EXPECT_EQ(core[i].size, outside[i].size) << core[i].name;
    EXPECT_EQ(core[i].align, outside[i].align) << core[i].name;
  }
}

}  // namespace
}  // namespace ragdoll_sim::test
