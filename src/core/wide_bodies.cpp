#include "wide_bodies.hpp"

#include <algorithm>

#include "solver_context.hpp"

namespace ragdoll_sim {

void WideBodies::build(const std::vector<SolverBody>& bodies, const int* indices, int n) {
  bodies_.clear();
  for (int k = 0; k < n; ++k)
    if (indices[k] >= 0 && movable(bodies[indices[k]])) bodies_.push_back(indices[k]);
  std::sort(bodies_.begin(), bodies_.end());
  bodies_.erase(std::unique(bodies_.begin(), bodies_.end()), bodies_.end());
  records_.resize(bodies_.size());
  before_.resize(bodies_.size());
}

int WideBodies::record(int body) const {
  const auto it = std::lower_bound(bodies_.begin(), bodies_.end(), body);
  return it != bodies_.end() && *it == body ? int(it - bodies_.begin()) : -1;
}

void WideBodies::gather(const std::vector<SolverBody>& bodies) {
  for (size_t k = 0; k < bodies_.size(); ++k) {
    const SolverBody& b = bodies[bodies_[k]];
    BodyVelocityF& r = before_[k];
    for (int i = 0; i < 3; ++i) {
      r.v[i] = float(b.v[i]);
      r.w[i] = float(b.w[i]);
    }
    r.pad[0] = r.pad[1] = 0.0f;
    records_[k] = r;
  }
}

void WideBodies::scatter(std::vector<SolverBody>& bodies) const {
  for (size_t k = 0; k < bodies_.size(); ++k) {
    const BodyVelocityF &r = records_[k], &o = before_[k];
    SolverBody& b = bodies[bodies_[k]];
    for (int i = 0; i < 3; ++i) {
      // Equal floats leave the double alone (x - x would be +0, and -0 + 0 is +0).
      if (r.v[i] != o.v[i]) b.v[i] += double(r.v[i]) - double(o.v[i]);
      if (r.w[i] != o.w[i]) b.w[i] += double(r.w[i]) - double(o.w[i]);
    }
  }
}

}  // namespace ragdoll_sim
