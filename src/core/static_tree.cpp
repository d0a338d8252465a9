#include "static_tree.hpp"

#include <algorithm>
#include <cmath>

namespace ragdoll_sim {

namespace {
bool hasNaN(const Aabb& b) { return b.lo.hasNaN() || b.hi.hasNaN(); }
}  // namespace

void StaticTree::build(const std::vector<int>& ids, const std::vector<Aabb>& aabbs) {
  ++builds_;
  nodes_.clear();
  loose_.clear();
  ids_.clear();
  boxes_.clear();
  // Loose boxes first, then the tree's in any order (buildNode sorts them into leaves).
  for (int id : ids)
    if (hasNaN(aabbs[id])) {
      loose_.push_back(int(ids_.size()));
      ids_.push_back(id);
      boxes_.push_back(aabbs[id]);
    }
  for (int id : ids)
    if (!hasNaN(aabbs[id])) {
      ids_.push_back(id);
      boxes_.push_back(aabbs[id]);
    }
  const int begin = int(loose_.size()), end = int(ids_.size());
  if (begin == end) return;
  centres_.resize(boxes_.size());
  for (int k = begin; k < end; ++k) {
    // An infinite box has a NaN centre: 0 keeps the split's order strict.
    centres_[k] = 0.5 * (boxes_[k].lo + boxes_[k].hi);
    for (int a = 0; a < 3; ++a)
      if (std::isnan(centres_[k][a])) centres_[k][a] = 0.0;
  }
  nodes_.reserve(size_t(2 * (end - begin) / kLeafSize + 1));
  buildNode(begin, end);
}

// The node over boxes_[begin, end): a leaf of up to kLeafSize boxes, else two children split at
// the median centre along the longest axis of the centres' spread (balanced: depth log2).
int StaticTree::buildNode(int begin, int end) {
  Aabb box{boxes_[begin].lo, boxes_[begin].hi};
  Vec3 clo = centres_[begin], chi = centres_[begin];
  for (int k = begin + 1; k < end; ++k) {
    box.lo = box.lo.cwiseMin(boxes_[k].lo);
    box.hi = box.hi.cwiseMax(boxes_[k].hi);
    clo = clo.cwiseMin(centres_[k]);
    chi = chi.cwiseMax(centres_[k]);
  }
  const int index = int(nodes_.size());
  nodes_.push_back({box, begin, end - begin});
  if (end - begin <= kLeafSize) return index;
  // Infinite bounds give an infinite or NaN spread: any axis still splits the count in half.
  const Vec3 spread = chi - clo;
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (spread[a] > spread[axis]) axis = a;
  const int mid = begin + (end - begin) / 2;
  // Sort the three parallel arrays by one permutation of [begin, end).
  std::vector<int> perm(size_t(end - begin));
  for (int k = begin; k < end; ++k) perm[size_t(k - begin)] = k;
  std::nth_element(perm.begin(), perm.begin() + (mid - begin), perm.end(), [&](int a, int b) {
    const double ca = centres_[a][axis], cb = centres_[b][axis];
    return ca < cb || (ca == cb && a < b);  // a total order (no NaN centres)
  });
  std::vector<Aabb> boxes(perm.size());
  std::vector<int> ids(perm.size());
  std::vector<Vec3> centres(perm.size());
  for (size_t k = 0; k < perm.size(); ++k) {
    boxes[k] = boxes_[perm[k]];
    ids[k] = ids_[perm[k]];
    centres[k] = centres_[perm[k]];
  }
  std::copy(boxes.begin(), boxes.end(), boxes_.begin() + begin);
  std::copy(ids.begin(), ids.end(), ids_.begin() + begin);
  std::copy(centres.begin(), centres.end(), centres_.begin() + begin);
  buildNode(begin, mid);
  const int second = buildNode(mid, end);
  nodes_[index].first = second;
  nodes_[index].count = 0;
  return index;
}

}  // namespace ragdoll_sim
