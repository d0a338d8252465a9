#include "broadphase.hpp"

#include <algorithm>

namespace ragdoll_sim {

void Broadphase::findPairs(const std::vector<Aabb>& aabbs, const std::vector<char>& unbounded,
                           const std::vector<PlaneProxy>& planes, double margin,
                           std::vector<std::pair<int, int>>& pairs) {
  pairs.clear();
  const int n = int(aabbs.size());
  // Keep the previous order, drop stale or unbounded ids, append new ones.
  std::vector<char>& seen = seen_;
  seen.assign(n, 0);
  int w = 0;
  for (int id : order_)
    if (id < n && !unbounded[id]) {
      order_[w++] = id;
      seen[id] = 1;
    }
  order_.resize(w);
  for (int i = 0; i < n; ++i)
    if (!unbounded[i] && !seen[i]) order_.push_back(i);

  for (size_t i = 1; i < order_.size(); ++i) {
    const int id = order_[i];
    const double key = aabbs[id].lo.x();
    size_t j = i;
    while (j > 0 && aabbs[order_[j - 1]].lo.x() > key) {
      order_[j] = order_[j - 1];
      --j;
    }
    order_[j] = id;
  }

  for (size_t i = 0; i < order_.size(); ++i) {
    const Aabb& a = aabbs[order_[i]];
    for (size_t j = i + 1; j < order_.size(); ++j) {
      const Aabb& b = aabbs[order_[j]];
      if (b.lo.x() > a.hi.x()) break;
      if (a.overlaps(b)) pairs.emplace_back(std::min(order_[i], order_[j]), std::max(order_[i], order_[j]));
    }
  }

  for (const PlaneProxy& p : planes) {
    for (int id : order_) {
      const Aabb& b = aabbs[id];
      const Vec3 c = 0.5 * (b.lo + b.hi), e = 0.5 * (b.hi - b.lo);
      if (p.normal.dot(c) - p.normal.cwiseAbs().dot(e) <= p.offset + margin)
        pairs.emplace_back(std::min(p.shape, id), std::max(p.shape, id));
    }
  }
}

}  // namespace ragdoll_sim
