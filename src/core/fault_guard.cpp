// The fault guard around the step: inputs checked and clamped before it, bodies the solver left
// non-finite or out of range reset after it, and their warm starts cleared. Data: fault_guard.hpp.
#include "world_impl.hpp"

namespace ragdoll_sim {

namespace {
void clearContactWarmStart(Contact& c) {
  for (int i = 0; i < Manifold::kMaxPoints; ++i) {
    c.normal_impulse[i] = 0.0;
    c.friction_impulse[i].setZero();
  }
  c.rolling_impulse.setZero();
  c.sep_valid = false;
}
}  // namespace


// Before the step: what was set since the last one (impulses, forces, setBodyState) must be
// finite and in range, and velocities are clamped. A good pose is the body's last good one (it
// may come from setBodyState); a body with a bad velocity, force or torque keeps it.
// A static body that was not created or commanded since the last step is as it was then; so is
// a dynamic one the last step's finish checked and clamped (guard_clean), and the guard skips
// it: it would read every body's state on one thread, from lines the island threads wrote.
void World::Impl::guardInputs() {
  const auto clean = [this](int i) { return guard_clean[i] != 0; };
  forEachGuarded([this](int i) {
    BodyMotion& m = motions[i];
    if (inputsFinite(m)) {
      if (!withinWorldRange(m.x)) {
        resetBody(i, BodyFaultCause::OutOfRange);
        return;
      }
      clampNorm(m.v, def.solver.max_linear_speed);
      clampNorm(m.w, def.solver.max_angular_speed);
      last_finite[i] = {m.x, m.q};
      return;
    }
    if (m.x.allFinite() && m.q.coeffs().allFinite() && withinWorldRange(m.x))
      last_finite[i] = {m.x, m.q};
    resetBody(i, BodyFaultCause::Input);
  }, clean);
}

void World::Impl::resetBody(int b, BodyFaultCause cause) {
  guard_clean[b] = 0;
  settled = false;
  schedule_fresh = false;
  forgetBoxes(b);
  BodyMotion& m = motions[b];
  m.x = last_finite[b].x;
  m.x_carry.setZero();
  m.q = last_finite[b].q;
  m.v.setZero();
  m.w.setZero();
  m.force.setZero();
  m.torque.setZero();
  ++fault_count;
  if (faults.size() < World::kMaxPendingFaults) faults.push_back({BodyId{b}, cause, time});
}


// An awake body takes the step's deltas and velocities; forces are cleared. A body the
// solver left non-finite or out of range is only marked here (islands finish on their own
// threads): resetFaulted resets the marked ones, in body order.
void World::Impl::finishBody(int i) {
  BodyMotion& m = motions[i];
  if (m.awake) {
    const SolverBody& s = solver[i];
    const Vec3 d = s.dp + m.x_carry;
    const Vec3 on_grid = snapPosition(d);
    m.x_carry = d - on_grid;  // exact
    m.x += on_grid;           // exact: both on the grid
    m.q = (s.dq * m.q).normalized();
    finishMotion(i, s);
  }
  m.force.setZero();
  m.torque.setZero();
}

// An awake body after its pose: the velocities, the fault marks, the clamps.
void World::Impl::finishMotion(int i, const SolverBody& s) {
  BodyMotion& m = motions[i];
  m.v = s.v;
  m.w = s.w;
  if (!motionFinite(m)) {
    solver_fault[i] = kSolverFault;
  } else if (!withinWorldRange(m.x)) {
    solver_fault[i] = kRangeFault;
  } else {
    clampNorm(m.v, def.solver.max_linear_speed);
    clampNorm(m.w, def.solver.max_angular_speed);
    last_finite[i] = {m.x, m.q};
    guard_clean[i] = 1;
  }
}

// Only awake (dynamic) bodies are marked (finishBody).
void World::Impl::resetFaulted() {
  for (const int i : dynamic_bodies)
    if (solver_fault[i]) {
      const bool range = solver_fault[i] == kRangeFault;
      solver_fault[i] = 0;
      resetBody(i, range ? BodyFaultCause::OutOfRange : BodyFaultCause::Solver);
      solver_reset[i] = 1;
      any_solver_reset = true;
    }
}

void World::Impl::finishStep() {
  forEachGuarded([this](int i) { finishBody(i); });
  resetFaulted();
  clearTouched();
}

// The other static bodies have no forces to clear (they were cleared when last touched).
void World::Impl::finishOutsideBodies() {
  for (const int i : dynamic_bodies)
    if (island_of_body[i] < 0) finishBody(i);
  for (const int i : touched_static)
    if (bodies[i].alive) finishBody(i);
}

// After a solver or range fault the impulses accumulated by the reset bodies' joints and
// contacts are garbage (NaN, or the huge ones that flung it) and would poison the next warm start.
void World::Impl::clearWarmStart() {
  for (size_t k = 0; k < joints.size(); ++k) {
    Joint& j = joints[k];
    if (joint_alive[k] && (solver_reset[j.a] || solver_reset[j.b])) j.clearWarmStart();
  }
  for (Contact& c : contacts)
    if (solver_reset[c.body_a] || solver_reset[c.body_b]) clearContactWarmStart(c);
  std::fill(solver_reset.begin(), solver_reset.end(), 0);
  any_solver_reset = false;
}

std::vector<BodyFault> World::takeBodyFaults() {
  std::vector<BodyFault> out;
  out.swap(impl_->faults);
  return out;
}

int64_t World::bodyFaultCount() const { return impl_->fault_count; }

}  // namespace ragdoll_sim
