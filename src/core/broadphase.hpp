// Broadphase: sweep and prune on one axis, the one the boxes spread most along (variance of
// their centres). The proxies' order is kept between steps and re-sorted by insertion sort,
// which is near linear when bodies move little per step; the sweep then tests the other two
// axes only for proxies overlapping on the sweep axis. Unbounded shapes (planes) are
// tested against every bounded AABB (O(n) per plane).
#pragma once

#include <utility>
#include <vector>

#include "narrowphase.hpp"

namespace ragdoll_sim {

struct PlaneProxy {
  int shape;
  Vec3 normal;   // world
  double offset; // world: n . x = offset
};

class Broadphase {
 public:
  // aabbs[i] is shape i's box (ignored when unbounded[i]); pairs get (i, j) with i < j.
  void findPairs(const std::vector<Aabb>& aabbs, const std::vector<char>& unbounded,
                 const std::vector<PlaneProxy>& planes, double margin,
                 std::vector<std::pair<int, int>>& pairs);

 private:
  static constexpr double kSwitchRatio = 1.5;  // another axis must spread this much more
  std::vector<int> order_;
  int axis_ = 0;
  std::vector<char> seen_;  // scratch, kept to avoid a per-step allocation
};

}  // namespace ragdoll_sim
