// Contact constraints for one step; see contact_solver.cpp for the math.
#pragma once

#include <limits>
#include <memory>
#include <vector>

#include "contact.hpp"
#include "contact_wide.hpp"
#include "solver_context.hpp"

namespace ragdoll_sim {

// One Jacobian row along a unit direction d: J = [-d, -(rA x d), d, rB x d], with the
// angular parts premultiplied by the inverse inertias (frozen for the step) so that the
// loops do no matrix work: Cdot = d.(vB - vA) + wB.angB - wA.angA.
struct ContactRow {
  Vec3 angA, angB;    // rA x d, rB x d
  Vec3 iangA, iangB;  // IA^-1 angA, IB^-1 angB
  double mass;        // 1 / (J M^-1 J^T)
};

struct ContactConstraintPoint {
  Vec3 rA, rB;                  // from the COMs at step start (world)
  double base_separation;       // separation - (rB - rA).n, so s = (d + rB' - rA').n + base
  // s at the current deltas (warm start, first sweep after a move); in the wide path the
  // block's geometry holds it after prepare (contact_geometry.hpp)
  double separation;
  double normal_impulse, tangent_impulse[2];
  double max_normal_impulse;
  double relative_velocity;     // normal approach speed before the step (for restitution)
  // A compliant point's spring bias of its biased sweep (> 0: apart, no push), which the relax
  // sweeps of the substep solve again.
  double spring_bias;
  // The normal row's mass, for the position projection (the rows themselves are in the
  // block's lanes, or in ContactRows for a constraint solved alone).
  double normal_mass;
  double step_impulse, peak_impulse;  // impulse tracking: sum and largest over the substeps
};

// The rows of a constraint solved alone (not in the wide blocks), apart from ContactConstraint
// so that the wide path, which keeps its rows in the lanes, never reads past the points.
struct ContactRows {
  ContactRow normal[Manifold::kMaxPoints], tangent[Manifold::kMaxPoints][2];
};

struct ContactConstraint {
  int a, b, contact;
  Vec3 normal, tangent[2];
  double friction, restitution;
  // Contact::contact_hertz > 0: the normal rows are this spring-damper in every sweep, whether
  // the bodies approach or part, and take neither restitution nor position projection.
  bool compliant;
  int count;
  int moved_sweep;  // the last position sweep of the step in which it moved a body
  // Rolling resistance (rolling > 0 only): angular rows J = [0, -t_k, 0, t_k] along the two
  // tangents, their impulses; IA^-1 t_k and IB^-1 t_k premultiplied and the 2x2 effective mass
  // at the end.
  double rolling;
  double rolling_impulse[2];
  ContactConstraintPoint points[Manifold::kMaxPoints];
  // Last: what only a compliant or rolling constraint reads, apart from the lines that prepare
  // writes for every constraint.
  Softness compliance;
  Vec3 roll_iA[2], roll_iB[2];
  Eigen::Matrix2d roll_mass;
};

// The friction clamp's shortcut (solveConstraint): whether sqrt(mag2) <= limit is certain
// without the square root, as for a sticking point (most of a resting pile's): mag2 is below
// limit^2 by far more than the roundings of limit^2 and of the root. Only a normal limit^2 is
// trusted (a subnormal one has few bits).
inline bool insideCone(double mag2, double limit) {
  const double limit2 = limit * limit;
  return limit2 >= std::numeric_limits<double>::min() && mag2 < limit2 * (1.0 - 0x1p-40);
}

// Whether cc may be solved in the wide blocks (contact_wide.hpp): rigid, without rolling
// resistance.
inline bool wideEligible(const ContactConstraint& cc) { return !cc.compliant && cc.rolling == 0.0; }

// s = (dpB - dpA + dqB rB - dqA rA).n + base_separation of every point of cc, in double.
void updateSeparations(const SolverBody& A, const SolverBody& B, ContactConstraint& cc);

// The row along d of a point with lever arms rA, rB. Inlined: prepare builds three rows per
// point and the call would cost as much as the row.
[[gnu::always_inline]] inline ContactRow contactRow(const SolverBody& A, const SolverBody& B,
                                                    const Vec3& rA, const Vec3& rB,
                                                    const Vec3& d) {
  ContactRow r;
  r.angA = rA.cross(d);
  r.angB = rB.cross(d);
  r.iangA = A.inv_inertia * r.angA;
  r.iangB = B.inv_inertia * r.angB;
  const double k = A.inv_mass + B.inv_mass + r.angA.dot(r.iangA) + r.angB.dot(r.iangB);
  r.mass = k > 0.0 ? 1.0 / k : 0.0;
  return r;
}

// Constraints are stored grouped by island (World groups the selected contacts, then each
// island's are prepared by the thread that solves it); the per-substep calls take the range
// [begin, end) of one island, so islands can be solved in parallel.
class ContactSolver {
 public:
  // The contacts that become constraints this step (touching, one body awake), in contact
  // order; the caller may reorder them (grouped by island) before prepare.
  std::vector<int>& selectActive(const std::vector<Contact>& contacts,
                                 const std::vector<BodyMotion>& motions);
  // One constraint slot per selected contact, in the selected order; then prepare fills the
  // slots [begin, end) (each on its own: ranges may be prepared on different threads).
  // threads: the most threads that prepare ranges this step (each draws wide batches from its
  // own pool).
  void resize(int threads = 1);
  const std::vector<int>& active() const { return active_; }  // selectActive's contacts
  // The wide batches held, all threads together: one per range that a thread prepared in a
  // step (the most over the steps), whatever the number of contacts.
  int batchCount() const;
  // This step's wide batch of the range that starts at slot begin, else nullptr.
  const ContactBatch* batchAt(int begin) const {
    return begin < int(batch_at_.size()) ? batch_at_[begin] : nullptr;
  }
  // The wide batch of [begin, end) when this step solves it in lanes, else nullptr.
  ContactBatch* batchOf(const StepContext& ctx, int begin, int end);
  // With ctx.lanes != 1 it also builds the range's wide batch (contact_wide.hpp), which the
  // calls with the same range then solve before the scalar rest.
  void prepare(const std::vector<Contact>& contacts, const StepContext& ctx, int begin, int end);
  // positions_moved: as for solve; false when a sweep already recomputed the separations at
  // the current deltas (the first relax sweep after the last position update).
  void warmStart(const StepContext& ctx, int begin, int end, bool positions_moved);
  // positions_moved: the deltas changed since the last warm start or sweep, so the
  // separations are recomputed (they stay fixed through the sweeps of one position state).
  void solve(const StepContext& ctx, bool use_bias, int begin, int end, bool positions_moved);
  // Position projection of penetrations deeper than the slop (after the substeps), sweep
  // number `sweep` of the step (from 1); true when it moved a body.
  bool project(const StepContext& ctx, int begin, int end, int sweep);
  // Restitution, then the impulses kept for the next step's warm start, of constraints
  // [begin, end) (after the island's substeps), accumulated over substeps of h.
  void applyRestitution(const StepContext& ctx, int begin, int end);
  void storeImpulses(std::vector<Contact>& contacts, double h, int begin, int end) const;

  // Impulse tracking (StepContext::track_impulses): after each substep (first: the step's
  // first), each point's accumulated normal impulse is what the substep applied; it is summed
  // and its largest kept. After restitution, storeTracks files them by contact index.
  void trackSubstep(int begin, int end, bool first);
  void storeTracks(std::vector<ContactTrack>& tracks, const std::vector<Contact>& contacts,
                   double h, int begin, int end) const;

 private:
  // The lanes' impulses into the double constraints of [begin, end) (a no-op without a batch).
  void syncImpulses(int begin, int end);

  // The wide batches of one thread, reused step after step in the order that thread prepares
  // its ranges: a range's batch is then warm in the cache of the core that solves it, and no two
  // threads write the same cache line.
  struct alignas(64) BatchPool {
    std::vector<std::unique_ptr<ContactBatch>> batches;
    int used = 0;  // batches taken this step
  };
  ContactBatch& takeBatch();

  std::vector<ContactConstraint> constraints_;
  std::vector<ContactRows> rows_;           // per slot; set for the constraints solved alone
  std::vector<BatchPool> pools_;            // one per thread
  std::vector<ContactBatch*> batch_at_;     // this step's batch of the range at its first slot
  std::vector<int> active_;  // contact index of each constraint
};

}  // namespace ragdoll_sim
