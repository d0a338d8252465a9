// Islands: dynamic bodies connected through joints or touching contacts (union-find, rebuilt
// every step in O(bodies + constraints)). An island sleeps as a whole once every body in it
// has been slow for SleepDef::time, and wakes as a whole when any body in it wakes
// (a command, or a contact with an awake body).
#pragma once

#include <numeric>
#include <vector>

namespace ragdoll_sim {

class Islands {
 public:
  void reset(int n) {
    parent_.resize(n);
    std::iota(parent_.begin(), parent_.end(), 0);
  }
  // Every entry of `ids` its own island (the others, never united, stay so): a reset that
  // costs nothing per static body.
  void reset(int n, const std::vector<int>& ids) {
    const int old = int(parent_.size());
    if (n > old) {
      parent_.resize(n);
      std::iota(parent_.begin() + old, parent_.end(), old);
    }
    for (int i : ids) parent_[i] = i;
  }
  int find(int i) {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];
      i = parent_[i];
    }
    return i;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<int> parent_;
};

}  // namespace ragdoll_sim
