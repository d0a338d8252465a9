// Contact constraints for one step; see contact_solver.cpp for the math.
#pragma once

#include <vector>

#include "contact.hpp"
#include "solver_context.hpp"

namespace ragdoll_sim {

struct ContactConstraintPoint {
  Vec3 rA, rB;                  // from the COMs at step start (world)
  double base_separation;       // separation - (rB - rA).n, so s = (d + rB' - rA').n + base
  double normal_mass, tangent_mass[2];
  double normal_impulse, tangent_impulse[2];
  double max_normal_impulse;
  double relative_velocity;     // normal approach speed before the step (for restitution)
};

struct ContactConstraint {
  int a, b, contact;
  Vec3 normal, tangent[2];
  double friction, restitution;
  int count;
  ContactConstraintPoint points[Manifold::kMaxPoints];
};

class ContactSolver {
 public:
  void prepare(const std::vector<Contact>& contacts, const StepContext& ctx);
  void warmStart(const StepContext& ctx);
  void solve(const StepContext& ctx, bool use_bias);
  void applyRestitution(const StepContext& ctx);
  void storeImpulses(std::vector<Contact>& contacts) const;

 private:
  std::vector<ContactConstraint> constraints_;
};

}  // namespace ragdoll_sim
