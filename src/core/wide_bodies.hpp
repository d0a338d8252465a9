// The float copies of one constraint batch's bodies for the wide solver (docs/physics.md).
// The velocities of the dynamic bodies that a batch's rows touch are gathered from the double
// solver bodies into 8-float records (BodyVelocityF) before the rows are solved in lanes, and
// written back after as exact double differences: v += double(v_after) - double(v_before) in
// float, so the rows' changes are kept to float precision while a body they leave alone keeps
// every bit of its double velocity (a falling body near a speculative contact stays on v = g t).
#pragma once

#include <vector>

#include "body.hpp"
#include "normal_row_wide.hpp"

namespace ragdoll_sim {

class WideBodies {
 public:
  // The batch's bodies from body indices (any order, repeats and identity bodies allowed: a
  // static or sleeping body is never written, so it gets no record).
  void build(const std::vector<SolverBody>& bodies, const int* indices, int n);
  // The record of body b, or -1 for a body the rows must not write (not movable, or not
  // among build's indices).
  int record(int body) const;
  int size() const { return int(bodies_.size()); }

  // Records <- the solver bodies' velocities, rounded to float.
  void gather(const std::vector<SolverBody>& bodies);
  // Solver bodies += what the rows changed since gather (in double, from the float values).
  void scatter(std::vector<SolverBody>& bodies) const;
  BodyVelocityF* records() { return records_.data(); }

 private:
  std::vector<int> bodies_;  // sorted body indices, record k is bodies_[k]
  std::vector<BodyVelocityF> records_, before_;
};

}  // namespace ragdoll_sim
