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
