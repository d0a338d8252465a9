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

  // Sweep along the axis the box centres spread most on (a row of ragdolls along y overlaps
  // in x), switching only when another axis spreads clearly more, so that the kept order stays
  // nearly sorted from step to step.
  Vec3 sum = Vec3::Zero(), sum2 = Vec3::Zero();
  for (int id : order_) {
    const Vec3 c = 0.5 * (aabbs[id].lo + aabbs[id].hi);
    sum += c;
    sum2 += c.cwiseProduct(c);
  }
  if (!order_.empty()) {
    const double inv = 1.0 / double(order_.size());
    const Vec3 var = sum2 * inv - (sum * inv).cwiseProduct(sum * inv);
    int best;
    var.maxCoeff(&best);
    if (best != axis_ && var[best] > kSwitchRatio * var[axis_]) axis_ = best;
  }
  const int ax = axis_;
  for (size_t i = 1; i < order_.size(); ++i) {
    const int id = order_[i];
    const double key = aabbs[id].lo[ax];
    size_t j = i;
    while (j > 0 && aabbs[order_[j - 1]].lo[ax] > key) {
      order_[j] = order_[j - 1];
      --j;
    }
    order_[j] = id;
  }

  for (size_t i = 0; i < order_.size(); ++i) {
    const Aabb& a = aabbs[order_[i]];
    for (size_t j = i + 1; j < order_.size(); ++j) {
      const Aabb& b = aabbs[order_[j]];
      if (b.lo[ax] > a.hi[ax]) break;
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
