// Sequential-impulse contact solver with soft contacts (Box2D v3 soft step, in 3D).
//
// Normal row per point:  Cdot = (vB + wB x rB - vA - wA x rA) . n,  lambda_n >= 0,
//   m_n = 1 / (1/mA + 1/mB + (rA x n).IA^-1(rA x n) + (rB x n).IB^-1(rB x n)).
// The separation is tracked through the substeps from the bodies' deltas:
//   s = (dpB - dpA + dqB rB - dqA rA) . n + base_separation.
//   s > 0 (speculative): bias = s / h, the gap may close in this substep but not overlap;
//   s <= 0: soft push-out bias = max(bias_rate (s + slop), -max_push_velocity) with the
//   contact softness, so penetration is removed as a damped spring, not by a velocity kick;
//   a point still approaching (Cdot < 0) is solved rigidly (mass_scale 1, no impulse
//   relaxation): softness shapes only the push-out, so a hard landing is stopped, not sunk in;
//   the relax pass (no bias, rigid, SolverSettings::contact_relax_iterations sweeps) then takes the
//   push-out velocity back. Penetration is thus corrected by impulses (a soft Baumgarte push
//   whose velocity is removed again: the effect of split impulses, without a second set of
//   velocities), so the correction splits between the bodies by their inverse masses and
//   inertias and adds no kinetic energy: two boxes created overlapping in free space separate
//   and stop.
// Compliant contacts (Contact::contact_hertz > 0, a padded surface): an overlapping point is
//   a spring-damper of that frequency and damping ratio (the soft step with bias_rate * s, no
//   slop, no push-out cap) in every sweep, approaching or not: the relax sweeps solve the
//   spring of the biased sweep again (the Gauss-Seidel of a manifold's points), so an impact is
//   stopped over about a quarter period instead of one substep; a point apart (s > 0) takes no
//   impulse, so a body enters the surface one substep late at most instead of being stopped
//   on it. The spring's damping ratio sets the rebound (restitution is not applied) and its
//   compression is the rest depth (no position projection).
// Friction: two tangent rows, impulse clamped to the Coulomb disc |lambda_t| <= mu lambda_n,
//   mu = static coefficient when the pair was sliding slower than static_friction_speed at the
//   start of the step, kinetic otherwise.
// Position projection (SolverSettings::position_iterations, after the substeps): a point deeper than
//   the slop is moved out by the position impulse m_n * min(s + slop, 0) * position_factor
//   along n (non-linear Gauss-Seidel, Box2D v2's solvePositionConstraints): it removes depth
//   left by a hard landing without giving the bodies any velocity.
// Rolling resistance (Contact::rolling = coefficient * radius > 0): the relative angular
//   velocity in the tangent plane, Cdot_k = t_k.(wB - wA), k = 0, 1, is driven to 0 by an
//   angular impulse L = sum_k lambda_k t_k with K_kl = t_k.(IA^-1 + IB^-1) t_l, clamped to the
//   disc |lambda| <= rolling * sum of the normal impulses (a torque <= c r N). A sphere rolling
//   on a plane then decelerates at 5/7 c g, like a disc of friction on the rotation.
// Restitution: after the substeps, points that approached faster than the threshold get
//   lambda = -m_n (vn + e vn_before), accumulated and clamped like the normal row.
// Warm start: the impulses kept from the last step were accumulated over its substep h0; an
//   island on another substep h (rest substeps, a new dt) starts from them times h / h0, the
//   same force (warmStartScale, solver_context.hpp).
#include "contact_solver.hpp"

#include <algorithm>
#include <cmath>

#include "thread_team.hpp"

namespace ragdoll_sim {

namespace {
// The velocities of a manifold's two bodies, held in locals through its rows and written back
// once, and only for a movable() body: static bodies are shared by all islands, and writing the
// ground from both threads on every row would make the cores fight over its cache line.
// kLiveA = false: A is an identity body (static or asleep: v = w = 0, inverse mass 0); its
// terms are dropped instead of multiplied by zero, which gives the same numbers with half the
// row work. Most contacts of a ragdoll are with the ground, which is side A when it was created
// first (the lower shape index); a static side B takes the general path.
template <bool kLiveA>
struct PairVelocity {
  Vec3 vA, wA, vB, wB;
  double mA, mB;
  PairVelocity(const SolverBody& A, const SolverBody& B)
      : vA(A.v), wA(A.w), vB(B.v), wB(B.w), mA(A.inv_mass), mB(B.inv_mass) {}
  void store(SolverBody& A, SolverBody& B) const {
    if (kLiveA && movable(A)) {
      A.v = vA;
      A.w = wA;
    }
    if (movable(B)) {
      B.v = vB;
      B.w = wB;
    }
  }
  double rowVelocity(const ContactRow& r, const Vec3& d) const {
    if (!kLiveA) return d.dot(vB) + wB.dot(r.angB);
    return d.dot(vB - vA) + wB.dot(r.angB) - wA.dot(r.angA);
  }
  void applyRow(const ContactRow& r, const Vec3& d, double lambda) {
    if (kLiveA) {
      vA -= (mA * lambda) * d;
      wA -= lambda * r.iangA;
    }
    vB += (mB * lambda) * d;
    wB += lambda * r.iangB;
  }
};
template <bool kLiveA>
void applyRolling(PairVelocity<kLiveA>& u, const ContactConstraint& cc, double l0, double l1) {
  if (kLiveA) u.wA -= l0 * cc.roll_iA[0] + l1 * cc.roll_iA[1];
  u.wB += l0 * cc.roll_iB[0] + l1 * cc.roll_iB[1];
}
[[gnu::always_inline]] inline Vec3 relativeVelocity(const SolverBody& A, const SolverBody& B,
                                                    const Vec3& rA, const Vec3& rB) {
  return B.v + B.w.cross(rB) - A.v - A.w.cross(rA);
}
}  // namespace

// s = (dpB - dpA).n + (dqB rB).n - (dqA rA).n + base for every point of cc: n is rotated back
// once per manifold instead of rotating each lever arm.
void updateSeparations(const SolverBody& A, const SolverBody& B, ContactConstraint& cc) {
  const double dpn = (B.dp - A.dp).dot(cc.normal);
  const Vec3 nB = B.dq.conjugate() * cc.normal;
  const Vec3 nA = unturned(A) ? cc.normal : Vec3(A.dq.conjugate() * cc.normal);
  for (int i = 0; i < cc.count; ++i) {
    ContactConstraintPoint& p = cc.points[i];
    p.separation = dpn + p.rB.dot(nB) - p.rA.dot(nA) + p.base_separation;
  }
}

std::vector<int>& ContactSolver::selectActive(const std::vector<Contact>& contacts,
                                              const std::vector<BodyMotion>& motions) {
  active_.clear();
  for (int ci = 0; ci < int(contacts.size()); ++ci) {
    const Contact& c = contacts[ci];
    if (c.manifold.count > 0 && (motions[c.body_a].awake || motions[c.body_b].awake))
      active_.push_back(ci);
  }
  return active_;
}

namespace {
void prepareRows(ContactConstraint& cc, ContactRows& rows, const SolverBody& A,
                 const SolverBody& B) {
  for (int i = 0; i < cc.count; ++i) {
    ContactConstraintPoint& p = cc.points[i];
    rows.normal[i] = contactRow(A, B, p.rA, p.rB, cc.normal);
    p.normal_mass = rows.normal[i].mass;
    for (int k = 0; k < 2; ++k) rows.tangent[i][k] = contactRow(A, B, p.rA, p.rB, cc.tangent[k]);
  }
}
}  // namespace

void ContactSolver::prepare(const std::vector<Contact>& contacts, const StepContext& ctx,
                            int begin, int end) {
  const auto& motions = *ctx.motions;
  const auto& bodies = *ctx.bodies;
  const SolverSettings& settings = *ctx.settings;
  for (int slot = begin; slot < end; ++slot) {
    const int ci = active_[slot];
    const Contact& c = contacts[ci];
    ContactConstraint& cc = constraints_[slot];
    cc.a = c.body_a;
    cc.b = c.body_b;
    cc.contact = ci;
    cc.normal = c.manifold.normal;
    cc.count = c.manifold.count;
    cc.moved_sweep = 0;
    cc.restitution = c.restitution;
    cc.compliant = c.contact_hertz > 0.0;
    cc.rolling = c.rolling;
    // A wide constraint's rows are prepared in its block's lanes (ContactBatch::build).
    const bool scalar_rows = ctx.lanes == 1 || !wideEligible(cc);
    if (cc.compliant)
      cc.compliance = Softness::make(std::min(c.contact_hertz, 0.25 * ctx.inv_h),
                                     c.contact_damping_ratio, ctx.h);
    const SolverBody &A = bodies[cc.a], &B = bodies[cc.b];
    // The points are relative to c.origin, a centre on the grid: the lever arms come from
    // exact differences of centres, the same wherever the pair is (body.hpp).
    const Vec3 oA = c.origin - motions[cc.a].x, oB = c.origin - motions[cc.b].x;

    // Tangent basis along the sliding direction of the first point when it slides.
    const Vec3 v0 = relativeVelocity(A, B, c.manifold.points[0].point + oA,
                                     c.manifold.points[0].point + oB);
    Vec3 vt = v0 - v0.dot(cc.normal) * cc.normal;
    double max_slip = 0.0;
    const double scale = warmStartScale(c.impulse_h, ctx.h);
    cc.tangent[0] = vt.norm() > 1e-9 ? Vec3(vt.normalized()) : anyPerpendicular(cc.normal);
    cc.tangent[1] = cc.normal.cross(cc.tangent[0]);

    for (int i = 0; i < cc.count; ++i) {
      const ManifoldPoint& mp = c.manifold.points[i];
      ContactConstraintPoint& p = cc.points[i];
      p.rA = mp.point + oA;
      p.rB = mp.point + oB;
      p.base_separation = mp.separation - (p.rB - p.rA).dot(cc.normal);
      const Vec3 dv = relativeVelocity(A, B, p.rA, p.rB);
      p.relative_velocity = dv.dot(cc.normal);
      max_slip = std::max(max_slip, (dv - p.relative_velocity * cc.normal).norm());
      p.normal_impulse = scale * c.normal_impulse[i];
      p.max_normal_impulse = 0.0;
      for (int k = 0; k < 2; ++k)
        p.tangent_impulse[k] = scale * c.friction_impulse[i].dot(cc.tangent[k]);
    }
    if (scalar_rows) prepareRows(cc, rows_[slot], A, B);
    cc.friction =
        max_slip < settings.static_friction_speed ? c.static_friction : c.kinetic_friction;
    cc.rolling_impulse[0] = cc.rolling_impulse[1] = 0.0;
    if (cc.rolling > 0.0) {
      Eigen::Matrix2d K;
      for (int k = 0; k < 2; ++k) {
        cc.roll_iA[k] = A.inv_inertia * cc.tangent[k];
        cc.roll_iB[k] = B.inv_inertia * cc.tangent[k];
        cc.rolling_impulse[k] = scale * c.rolling_impulse.dot(cc.tangent[k]);
      }
      for (int k = 0; k < 2; ++k)
        for (int l = 0; l < 2; ++l) K(k, l) = cc.tangent[k].dot(cc.roll_iA[l] + cc.roll_iB[l]);
      cc.roll_mass = inverseOrZero(K);
    }
  }
  if (begin >= end || ctx.lanes == 1) return;
  ContactBatch& batch = takeBatch();
  batch.build(constraints_, ctx, begin, end);
  batch_at_[begin] = &batch;
  for (const int k : batch.scalar()) {  // the colouring's overflow
    ContactConstraint& cc = constraints_[k];
    if (wideEligible(cc)) prepareRows(cc, rows_[k], bodies[cc.a], bodies[cc.b]);
  }
}

void ContactSolver::resize(int threads) {
  constraints_.resize(active_.size());
  rows_.resize(active_.size());
  batch_at_.assign(active_.size(), nullptr);
  if (int(pools_.size()) < threads) pools_.resize(threads);
  for (BatchPool& p : pools_) p.used = 0;
}

int ContactSolver::batchCount() const {
  int n = 0;
  for (const BatchPool& p : pools_) n += int(p.batches.size());
  return n;
}

ContactBatch& ContactSolver::takeBatch() {
  BatchPool& pool = pools_.at(teamSlot().first);
  if (pool.used == int(pool.batches.size())) pool.batches.push_back(std::make_unique<ContactBatch>());
  return *pool.batches[pool.used++];
}

ContactBatch* ContactSolver::batchOf(const StepContext& ctx, int begin, int end) {
  if (ctx.lanes == 1 || begin >= end) return nullptr;
  ContactBatch* batch = batch_at_[begin];
  return batch && batch->holds(begin, end) ? batch : nullptr;
}

void ContactSolver::syncImpulses(int begin, int end) {
  if (begin >= end) return;
  const ContactBatch* batch = batch_at_[begin];
  if (batch && batch->holds(begin, end)) batch->syncImpulses(constraints_);
}

namespace {
// m: far above the rounding of a separation (1e-15 m for lever arms of metres), far below the
// slop.
constexpr double kSeparationMargin = 1e-9;

// No impulse carried on any point or on rolling: warm starting and the rows of an idle manifold
// (idleIn) would only add zeros.
bool noImpulse(const ContactConstraint& cc) {
  for (int i = 0; i < cc.count; ++i) {
    const ContactConstraintPoint& p = cc.points[i];
    if (p.normal_impulse != 0.0 || p.tangent_impulse[0] != 0.0 || p.tangent_impulse[1] != 0.0)
      return false;
  }
  return cc.rolling_impulse[0] == 0.0 && cc.rolling_impulse[1] == 0.0;
}

// A manifold is idle in a sweep when it carries no impulse and every point is apart (s > 0)
// and would stay apart at the current velocities through the substep (vn + s / h >= 0): each
// normal row then clamps to 0, so friction's limit is 0 too, and the sweep changes nothing.
// Most manifolds of a pile are such speculative ones, and this test costs one row velocity per
// point instead of three rows and stores.
template <bool kLiveA>
bool idleIn(const ContactConstraint& cc, const ContactRows& rows, const PairVelocity<kLiveA>& u,
            double inv_h) {
  for (int i = 0; i < cc.count; ++i) {
    const ContactConstraintPoint& p = cc.points[i];
    if (!(p.separation > 0.0) ||
        u.rowVelocity(rows.normal[i], cc.normal) + p.separation * inv_h < 0.0)
      return false;
  }
  return noImpulse(cc);
}

// The normal impulse of a compliant point (see the file comment): the biased sweep sets the
// spring's bias from the separation, the relax sweeps solve the same spring again.
template <bool kLiveA>
double compliantImpulse(ContactConstraintPoint& p, const ContactRow& row,
                        const ContactConstraint& cc, const PairVelocity<kLiveA>& u,
                        bool use_bias) {
  const Softness& k = cc.compliance;
  if (use_bias) p.spring_bias = p.separation > 0.0 ? 1.0 : k.bias_rate * p.separation;
  if (p.spring_bias > 0.0) return -p.normal_impulse;  // apart: let go
  const double vn = u.rowVelocity(row, cc.normal);
  return -row.mass * k.mass_scale * (vn + p.spring_bias) - k.impulse_scale * p.normal_impulse;
}

template <bool kLiveA>
void warmStartConstraint(ContactConstraint& cc, const ContactRows& rows, SolverBody& A,
                         SolverBody& B, bool positions_moved) {
  if (positions_moved) updateSeparations(A, B, cc);
  if (noImpulse(cc)) return;
  PairVelocity<kLiveA> u(A, B);
  for (int i = 0; i < cc.count; ++i) {
    const ContactConstraintPoint& p = cc.points[i];
    u.applyRow(rows.normal[i], cc.normal, p.normal_impulse);
    u.applyRow(rows.tangent[i][0], cc.tangent[0], p.tangent_impulse[0]);
    u.applyRow(rows.tangent[i][1], cc.tangent[1], p.tangent_impulse[1]);
  }
  if (cc.rolling > 0.0) applyRolling(u, cc, cc.rolling_impulse[0], cc.rolling_impulse[1]);
  u.store(A, B);
}

template <bool kLiveA>
void solveConstraint(ContactConstraint& cc, const ContactRows& rows, SolverBody& A, SolverBody& B,
                     const StepContext& ctx, bool use_bias, bool positions_moved) {
  const SolverSettings& settings = *ctx.settings;
  const Softness& soft = ctx.contact_softness;
  if (positions_moved) updateSeparations(A, B, cc);
  PairVelocity<kLiveA> u(A, B);
  if (idleIn(cc, rows, u, ctx.inv_h)) return;
  for (int i = 0; i < cc.count; ++i) {
    ContactConstraintPoint& p = cc.points[i];
    double lambda;
    if (cc.compliant) {
      lambda = compliantImpulse(p, rows.normal[i], cc, u, use_bias);
    } else {
      const double s = p.separation;
      double bias = 0.0, mass_scale = 1.0, impulse_scale = 0.0;
      if (s > 0.0) {
        bias = s * ctx.inv_h;
      } else if (use_bias) {
        bias = std::max(soft.bias_rate * std::min(s + settings.linear_slop, 0.0),
                        -settings.max_push_velocity);
        mass_scale = soft.mass_scale;
        impulse_scale = soft.impulse_scale;
      }
      const double vn = u.rowVelocity(rows.normal[i], cc.normal);
      if (vn < 0.0) mass_scale = 1.0, impulse_scale = 0.0;  // approaching: rigid
      lambda = -rows.normal[i].mass * mass_scale * (vn + bias) - impulse_scale * p.normal_impulse;
    }
    const double next = std::max(p.normal_impulse + lambda, 0.0);
    lambda = next - p.normal_impulse;
    p.normal_impulse = next;
    p.max_normal_impulse = std::max(p.max_normal_impulse, lambda);
    u.applyRow(rows.normal[i], cc.normal, lambda);
  }
  for (int i = 0; i < cc.count; ++i) {
    ContactConstraintPoint& p = cc.points[i];
    const double old0 = p.tangent_impulse[0], old1 = p.tangent_impulse[1];
    const double limit = cc.friction * p.normal_impulse;
    // No normal impulse (a speculative point) and no friction carried: the cone is a point and
    // the friction impulse stays zero.
    if (limit == 0.0 && old0 == 0.0 && old1 == 0.0) continue;
    const ContactRow(&t)[2] = rows.tangent[i];
    double t0 = old0 - t[0].mass * u.rowVelocity(t[0], cc.tangent[0]);
    double t1 = old1 - t[1].mass * u.rowVelocity(t[1], cc.tangent[1]);
    const double mag2 = t0 * t0 + t1 * t1;
    if (!insideCone(mag2, limit)) {
      const double mag = std::sqrt(mag2);
      if (mag > limit) {
        const double scale = mag > 0.0 ? limit / mag : 0.0;
        t0 *= scale;
        t1 *= scale;
      }
    }
    p.tangent_impulse[0] = t0;
    p.tangent_impulse[1] = t1;
    u.applyRow(t[0], cc.tangent[0], t0 - old0);
    u.applyRow(t[1], cc.tangent[1], t1 - old1);
  }
  if (cc.rolling > 0.0) {
    double total_normal = 0.0;
    for (int i = 0; i < cc.count; ++i) total_normal += cc.points[i].normal_impulse;
    const Eigen::Vector2d cdot((u.wB - u.wA).dot(cc.tangent[0]), (u.wB - u.wA).dot(cc.tangent[1]));
    const Eigen::Vector2d old(cc.rolling_impulse[0], cc.rolling_impulse[1]);
    Eigen::Vector2d next = old - cc.roll_mass * cdot;
    const double limit = cc.rolling * total_normal, mag = next.norm();
    if (mag > limit) next *= mag > 0.0 ? limit / mag : 0.0;
    cc.rolling_impulse[0] = next[0];
    cc.rolling_impulse[1] = next[1];
    applyRolling(u, cc, next[0] - old[0], next[1] - old[1]);
  }
  u.store(A, B);
}
}  // namespace

// With a wide batch: its blocks in lanes, then the scalar rest; else every slot scalar.
template <class Slot>
void forSlots(ContactBatch* batch, int begin, int end, Slot&& slot) {
  if (!batch) {
    for (int k = begin; k < end; ++k) slot(k);
    return;
  }
  for (const int k : batch->scalar()) slot(k);
}

void ContactSolver::warmStart(const StepContext& ctx, int begin, int end, bool positions_moved) {
  auto& bodies = *ctx.bodies;
  ContactBatch* batch = batchOf(ctx, begin, end);
  if (batch) batch->warmStart(ctx, positions_moved);
  forSlots(batch, begin, end, [&](int k) {
    ContactConstraint& cc = constraints_[k];
    SolverBody &A = bodies[cc.a], &B = bodies[cc.b];
    if (movable(A)) warmStartConstraint<true>(cc, rows_[k], A, B, positions_moved);
    else warmStartConstraint<false>(cc, rows_[k], A, B, positions_moved);
  });
}

void ContactSolver::solve(const StepContext& ctx, bool use_bias, int begin, int end,
                          bool positions_moved) {
  auto& bodies = *ctx.bodies;
  ContactBatch* batch = batchOf(ctx, begin, end);
  if (batch) batch->solve(ctx, use_bias, positions_moved);
  forSlots(batch, begin, end, [&](int k) {
    ContactConstraint& cc = constraints_[k];
    SolverBody &A = bodies[cc.a], &B = bodies[cc.b];
    if (movable(A)) solveConstraint<true>(cc, rows_[k], A, B, ctx, use_bias, positions_moved);
    else solveConstraint<false>(cc, rows_[k], A, B, ctx, use_bias, positions_moved);
  });
}

bool ContactSolver::project(const StepContext& ctx, int begin, int end, int sweep) {
  auto& bodies = *ctx.bodies;
  const SolverSettings& settings = *ctx.settings;
  bool moved = false;
  // The first sweep starts at the positions of the last relax sweep's separations in the lanes:
  // a constraint whose bodies no projection has moved yet, with every point apart by more than
  // -linear_slop there, would compute C = 0 below and is passed over. The margin covers the
  // last bits by which those separations (the normal turned into each body's frame) differ
  // from the ones below (the lever arms turned into the world).
  const ContactBatch* batch = sweep == 1 ? batchOf(ctx, begin, end) : nullptr;
  const double clear = -settings.linear_slop + kSeparationMargin;
  for (int k = begin; k < end; ++k) {
    ContactConstraint& cc = constraints_[k];
    SolverBody &A = bodies[cc.a], &B = bodies[cc.b];
    if (cc.compliant || unchangedSince(sweep, cc.moved_sweep, A, B)) continue;
    if (batch && A.moved_sweep != sweep && B.moved_sweep != sweep &&
        batch->apartAtLastUpdate(k, clear))
      continue;
    // the ground's lever arms need no turning (only its separation reads them: it is not moved)
    const bool fixed_a = !movable(A) && unturned(A);
    for (int i = 0; i < cc.count; ++i) {
      const ContactConstraintPoint& p = cc.points[i];
      const Vec3 rA = fixed_a ? p.rA : Vec3(A.dq * p.rA), rB = B.dq * p.rB;
      const double s = (B.dp - A.dp + rB - rA).dot(cc.normal) + p.base_separation;
      const double C = std::max(settings.position_factor * std::min(s + settings.linear_slop, 0.0),
                                -settings.max_position_correction);
      if (C < 0.0) {
        applyPairPositionImpulse(A, B, (-p.normal_mass * C) * cc.normal, rA, rB);
        markMoved(sweep, cc.moved_sweep, A, B);
        moved = true;
      }
    }
  }
  return moved;
}

void ContactSolver::applyRestitution(const StepContext& ctx, int begin, int end) {
  syncImpulses(begin, end);  // the double constraints are the source from here on
  auto& bodies = *ctx.bodies;
  const double threshold = ctx.settings->restitution_threshold;
  for (int k = begin; k < end; ++k) {
    ContactConstraint& cc = constraints_[k];
    if (cc.restitution == 0.0 || cc.compliant) continue;
    SolverBody &A = bodies[cc.a], &B = bodies[cc.b];
    for (int i = 0; i < cc.count; ++i) {
      ContactConstraintPoint& p = cc.points[i];
      if (p.relative_velocity > -threshold || p.max_normal_impulse == 0.0) continue;
      // Built again: a wide constraint keeps only its normal row's mass (contact_wide.hpp).
      const ContactRow row = contactRow(A, B, p.rA, p.rB, cc.normal);
      PairVelocity<true> u(A, B);
      const double vn = u.rowVelocity(row, cc.normal);
      double lambda = -row.mass * (vn + cc.restitution * p.relative_velocity);
      const double next = std::max(p.normal_impulse + lambda, 0.0);
      lambda = next - p.normal_impulse;
      p.normal_impulse = next;
      if (ctx.track_impulses) p.step_impulse += lambda;
      u.applyRow(row, cc.normal, lambda);
      u.store(A, B);
    }
  }
}

void ContactSolver::storeImpulses(std::vector<Contact>& contacts, double h, int begin,
                                  int end) const {
  for (int k = begin; k < end; ++k) {
    const ContactConstraint& cc = constraints_[k];
    Contact& c = contacts[cc.contact];
    c.impulse_h = h;
    for (int i = 0; i < cc.count; ++i) {
      const ContactConstraintPoint& p = cc.points[i];
      c.normal_impulse[i] = p.normal_impulse;
      c.friction_impulse[i] = p.tangent_impulse[0] * cc.tangent[0] + p.tangent_impulse[1] * cc.tangent[1];
    }
    c.rolling_impulse = cc.rolling_impulse[0] * cc.tangent[0] + cc.rolling_impulse[1] * cc.tangent[1];
  }
}

void ContactSolver::trackSubstep(int begin, int end, bool first) {
  syncImpulses(begin, end);
  for (int k = begin; k < end; ++k) {
    ContactConstraint& cc = constraints_[k];
    for (int i = 0; i < cc.count; ++i) {
      ContactConstraintPoint& p = cc.points[i];
      if (first) {
        p.step_impulse = p.peak_impulse = p.normal_impulse;
      } else {
        p.step_impulse += p.normal_impulse;
        p.peak_impulse = std::max(p.peak_impulse, p.normal_impulse);
      }
    }
  }
}

void ContactSolver::storeTracks(std::vector<ContactTrack>& tracks,
                                const std::vector<Contact>& contacts, double h, int begin,
                                int end) const {
  for (int k = begin; k < end; ++k) {
    const ContactConstraint& cc = constraints_[k];
    ContactTrack& t = tracks[cc.contact];
    t.key = contacts[cc.contact].key;
    for (int i = 0; i < cc.count; ++i) {
      const ContactConstraintPoint& p = cc.points[i];
      t.step_impulse[i] = p.step_impulse;
      t.peak_force[i] = p.peak_impulse / h;
      t.closing_speed[i] = -p.relative_velocity;
    }
  }
}

}  // namespace ragdoll_sim
