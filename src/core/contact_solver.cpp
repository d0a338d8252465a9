// Sequential-impulse contact solver with soft contacts (Box2D v3 soft step, in 3D).
//
// Normal row per point:  Cdot = (vB + wB x rB - vA - wA x rA) . n,  lambda_n >= 0,
//   m_n = 1 / (1/mA + 1/mB + (rA x n).IA^-1(rA x n) + (rB x n).IB^-1(rB x n)).
// The separation is tracked through the substeps from the bodies' deltas:
//   s = (dpB - dpA + dqB rB - dqA rA) . n + base_separation.
//   s > 0 (speculative): bias = s / h, the gap may close in this substep but not overlap;
//   s <= 0: soft push-out bias = max(bias_rate (s + slop), -max_push_velocity) with the
//   contact softness, so penetration is removed as a damped spring, not by a velocity kick;
//   the relax pass (no bias, rigid, WorldDef::contact_relax_iterations sweeps) then takes the
//   push-out velocity back. Penetration is thus corrected by impulses (a soft Baumgarte push
//   whose velocity is removed again: the effect of split impulses, without a second set of
//   velocities), so the correction splits between the bodies by their inverse masses and
//   inertias and adds no kinetic energy: two boxes created 2 cm apart-in-overlap in free
//   space separate and stop (KE 1.5e-8 J after 4 relax sweeps; 6.8e-3 J with one sweep).
// Friction: two tangent rows, impulse clamped to the Coulomb disc |lambda_t| <= mu lambda_n,
//   mu = static coefficient when the pair was sliding slower than static_friction_speed at the
//   start of the step, kinetic otherwise.
// Restitution: after the substeps, points that approached faster than the threshold get
//   lambda = -m_n (vn + e vn_before), accumulated and clamped like the normal row.
#include "contact_solver.hpp"

#include <algorithm>
#include <cmath>

namespace ragdoll_sim {

namespace {
double rowMass(const SolverBody& A, const SolverBody& B, const Vec3& rA, const Vec3& rB,
               const Vec3& d) {
  const Vec3 ra = rA.cross(d), rb = rB.cross(d);
  const double k = A.inv_mass + B.inv_mass + ra.dot(A.inv_inertia * ra) + rb.dot(B.inv_inertia * rb);
  return k > 0.0 ? 1.0 / k : 0.0;
}
Vec3 relativeVelocity(const SolverBody& A, const SolverBody& B, const Vec3& rA, const Vec3& rB) {
  return B.v + B.w.cross(rB) - A.v - A.w.cross(rA);
}
}  // namespace

void ContactSolver::prepare(const std::vector<Contact>& contacts, const StepContext& ctx) {
  const auto& motions = *ctx.motions;
  const auto& bodies = *ctx.bodies;
  const WorldDef& def = *ctx.def;
  constraints_.clear();
  for (int ci = 0; ci < int(contacts.size()); ++ci) {
    const Contact& c = contacts[ci];
    if (c.manifold.count == 0 || (!motions[c.body_a].awake && !motions[c.body_b].awake)) continue;
    ContactConstraint cc;
    cc.a = c.body_a;
    cc.b = c.body_b;
    cc.contact = ci;
    cc.normal = c.manifold.normal;
    cc.count = c.manifold.count;
    cc.restitution = c.restitution;
    const SolverBody &A = bodies[cc.a], &B = bodies[cc.b];
    const Vec3 xA = motions[cc.a].x, xB = motions[cc.b].x;

    // Tangent basis along the sliding direction of the first point when it slides.
    const Vec3 v0 = relativeVelocity(A, B, c.manifold.points[0].point - xA,
                                     c.manifold.points[0].point - xB);
    Vec3 vt = v0 - v0.dot(cc.normal) * cc.normal;
    double max_slip = 0.0;
    cc.tangent[0] = vt.norm() > 1e-9 ? Vec3(vt.normalized()) : anyPerpendicular(cc.normal);
    cc.tangent[1] = cc.normal.cross(cc.tangent[0]);

    for (int i = 0; i < cc.count; ++i) {
      const ManifoldPoint& mp = c.manifold.points[i];
      ContactConstraintPoint& p = cc.points[i];
      p.rA = mp.point - xA;
      p.rB = mp.point - xB;
      p.base_separation = mp.separation - (p.rB - p.rA).dot(cc.normal);
      p.normal_mass = rowMass(A, B, p.rA, p.rB, cc.normal);
      const Vec3 dv = relativeVelocity(A, B, p.rA, p.rB);
      p.relative_velocity = dv.dot(cc.normal);
      max_slip = std::max(max_slip, (dv - p.relative_velocity * cc.normal).norm());
      p.normal_impulse = c.normal_impulse[i];
      p.max_normal_impulse = 0.0;
      for (int k = 0; k < 2; ++k) {
        p.tangent_mass[k] = rowMass(A, B, p.rA, p.rB, cc.tangent[k]);
        p.tangent_impulse[k] = c.friction_impulse[i].dot(cc.tangent[k]);
      }
    }
    cc.friction = max_slip < def.static_friction_speed ? c.static_friction : c.kinetic_friction;
    constraints_.push_back(cc);
  }
}

void ContactSolver::warmStart(const StepContext& ctx) {
  auto& bodies = *ctx.bodies;
  for (ContactConstraint& cc : constraints_) {
    SolverBody &A = bodies[cc.a], &B = bodies[cc.b];
    for (int i = 0; i < cc.count; ++i) {
      const ContactConstraintPoint& p = cc.points[i];
      const Vec3 P = p.normal_impulse * cc.normal + p.tangent_impulse[0] * cc.tangent[0] +
                     p.tangent_impulse[1] * cc.tangent[1];
      applyPairImpulse(A, B, P, p.rA, p.rB);
    }
  }
}

void ContactSolver::solve(const StepContext& ctx, bool use_bias) {
  auto& bodies = *ctx.bodies;
  const WorldDef& def = *ctx.def;
  const Softness& soft = ctx.contact_softness;
  for (ContactConstraint& cc : constraints_) {
    SolverBody &A = bodies[cc.a], &B = bodies[cc.b];
    const Vec3 dp = B.dp - A.dp;
    for (int i = 0; i < cc.count; ++i) {
      ContactConstraintPoint& p = cc.points[i];
      const double s = (dp + B.dq * p.rB - A.dq * p.rA).dot(cc.normal) + p.base_separation;
      double bias = 0.0, mass_scale = 1.0, impulse_scale = 0.0;
      if (s > 0.0) {
        bias = s * ctx.inv_h;
      } else if (use_bias) {
        bias = std::max(soft.bias_rate * std::min(s + def.linear_slop, 0.0), -def.max_push_velocity);
        mass_scale = soft.mass_scale;
        impulse_scale = soft.impulse_scale;
      }
      const double vn = relativeVelocity(A, B, p.rA, p.rB).dot(cc.normal);
      double lambda = -p.normal_mass * mass_scale * (vn + bias) - impulse_scale * p.normal_impulse;
      const double next = std::max(p.normal_impulse + lambda, 0.0);
      lambda = next - p.normal_impulse;
      p.normal_impulse = next;
      p.max_normal_impulse = std::max(p.max_normal_impulse, lambda);
      applyPairImpulse(A, B, lambda * cc.normal, p.rA, p.rB);
    }
    for (int i = 0; i < cc.count; ++i) {
      ContactConstraintPoint& p = cc.points[i];
      const Vec3 dv = relativeVelocity(A, B, p.rA, p.rB);
      const double old0 = p.tangent_impulse[0], old1 = p.tangent_impulse[1];
      double t0 = old0 - p.tangent_mass[0] * dv.dot(cc.tangent[0]);
      double t1 = old1 - p.tangent_mass[1] * dv.dot(cc.tangent[1]);
      const double limit = cc.friction * p.normal_impulse;
      const double mag = std::sqrt(t0 * t0 + t1 * t1);
      if (mag > limit) {
        const double scale = mag > 0.0 ? limit / mag : 0.0;
        t0 *= scale;
        t1 *= scale;
      }
      p.tangent_impulse[0] = t0;
      p.tangent_impulse[1] = t1;
      applyPairImpulse(A, B, (t0 - old0) * cc.tangent[0] + (t1 - old1) * cc.tangent[1], p.rA, p.rB);
    }
  }
}

void ContactSolver::applyRestitution(const StepContext& ctx) {
  auto& bodies = *ctx.bodies;
  const double threshold = ctx.def->restitution_threshold;
  for (ContactConstraint& cc : constraints_) {
    if (cc.restitution == 0.0) continue;
    SolverBody &A = bodies[cc.a], &B = bodies[cc.b];
    for (int i = 0; i < cc.count; ++i) {
      ContactConstraintPoint& p = cc.points[i];
      if (p.relative_velocity > -threshold || p.max_normal_impulse == 0.0) continue;
      const double vn = relativeVelocity(A, B, p.rA, p.rB).dot(cc.normal);
      double lambda = -p.normal_mass * (vn + cc.restitution * p.relative_velocity);
      const double next = std::max(p.normal_impulse + lambda, 0.0);
      lambda = next - p.normal_impulse;
      p.normal_impulse = next;
      applyPairImpulse(A, B, lambda * cc.normal, p.rA, p.rB);
    }
  }
}

void ContactSolver::storeImpulses(std::vector<Contact>& contacts) const {
  for (const ContactConstraint& cc : constraints_) {
    Contact& c = contacts[cc.contact];
    for (int i = 0; i < cc.count; ++i) {
      const ContactConstraintPoint& p = cc.points[i];
      c.normal_impulse[i] = p.normal_impulse;
      c.friction_impulse[i] = p.tangent_impulse[0] * cc.tangent[0] + p.tangent_impulse[1] * cc.tangent[1];
    }
  }
}

}  // namespace ragdoll_sim
