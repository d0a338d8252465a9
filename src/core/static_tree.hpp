// The shapes of static bodies in their own bounding-volume tree (Box2D v3 keeps a tree per body
// type for the same reason): built once from their boxes, rebuilt only when a static shape is
// added, removed or moved, and queried with the boxes of the other shapes, so that a step costs
// nothing per static shape. A top-down build (median split on the longest axis of the box
// centres) into a flat array; a query reports exactly the boxes that Aabb::overlaps the query
// box. Boxes with a NaN bound (which overlap nothing) stay out of the tree and are tested one
// by one, so the answer stays exact for any input.
#pragma once

#include <cstdint>
#include <vector>

#include "narrowphase.hpp"

namespace ragdoll_sim {

class StaticTree {
 public:
  // The tree over the shapes `ids` whose boxes are aabbs[id]; the old tree is dropped.
  void build(const std::vector<int>& ids, const std::vector<Aabb>& aabbs);

  // f(id) for every shape of the last build whose box overlaps `box` (Aabb::overlaps), in no
  // particular order.
  template <class F>
  void query(const Aabb& box, F&& f) const {
    for (int k : loose_)
      if (boxes_[k].overlaps(box)) f(ids_[k]);
    if (nodes_.empty()) return;
    int stack[kMaxDepth];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& node = nodes_[stack[--top]];
      if (!node.box.overlaps(box)) continue;
      if (node.count > 0) {
        for (int k = node.first; k < node.first + node.count; ++k)
          if (boxes_[k].overlaps(box)) f(ids_[k]);
        continue;
      }
      // children: the next node and node.first
      stack[top++] = node.first;
      stack[top++] = int(&node - nodes_.data()) + 1;
    }
  }

  bool empty() const { return ids_.empty(); }
  int size() const { return int(ids_.size()); }
  // Number of build calls so far (the world's tests check that stepping does not rebuild).
  int64_t builds() const { return builds_; }

 private:
  static constexpr int kLeafSize = 4;  // boxes per leaf
  // Depth bound of the median split (each level halves the boxes): twice a 32-bit count's bits.
  static constexpr int kMaxDepth = 64;
  struct Node {
    Aabb box;   // of everything below
    int first;  // leaf: first box in boxes_; inner: the second child (the first is this + 1)
    int count;  // leaf: its boxes (> 0); inner: 0
  };
  int buildNode(int begin, int end);

  std::vector<Node> nodes_;
  std::vector<Aabb> boxes_;  // in tree order (leaves hold ranges of it); loose ones first
  std::vector<int> ids_;     // shape id of boxes_[k]
  std::vector<int> loose_;   // indices into boxes_ of the boxes with a NaN bound
  std::vector<Vec3> centres_;  // build scratch
  int64_t builds_ = 0;
};

}  // namespace ragdoll_sim
