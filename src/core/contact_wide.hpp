// The contact constraints of one prepared range in float lanes (SolverSettings::lanes != 1):
// the eligible manifolds coloured and packed one per lane into ContactBlocks, the rest left to
// the scalar double rows (docs/physics.md, the wide solver).
#pragma once

#include <vector>

#include "constraint_graph.hpp"
#include "contact_rows_wide.hpp"
#include "contact_geometry.hpp"

namespace ragdoll_sim {

struct ContactConstraint;
struct StepContext;

// Built by prepare for the range [begin, end), from the pool of the thread that prepares it
// (ContactSolver), so ranges prepared on different threads share nothing.
class ContactBatch {
 public:
  // The wide blocks of constraints cs[begin, end) (prepared in double, the rows of eligible
  // ones excepted): the eligible ones (wideEligible, contact_solver.hpp) in colours of the
  // graph of their dynamic bodies, their rows prepared in the lanes (and each normal row's
  // mass set in its constraint); the others and the colouring's overflow go to scalar().
  void build(std::vector<ContactConstraint>& cs, const StepContext& ctx, int begin, int end);
  // True when this holds the batch of [begin, end) (built this step with lanes != 1).
  bool holds(int begin, int end) const { return begin == begin_ && end == end_; }
  void clear() { end_ = -1; }
  // The slots the scalar rows solve after the blocks, in slot order.
  const std::vector<int>& scalar() const { return scalar_; }
  // The colours of the blocks (0 without any).
  int colourCount() const { return wide_.empty() ? 0 : graph_.colourCount(); }
  // The constraints in the blocks, and the blocks' lanes.
  int laneRows() const { return int(wide_.size()); }
  int lanes() const { return block_count_ * kRowBlock; }

  // Once per substep, first. positions_moved: the double separations are recomputed (in the
  // blocks' geometry; the constraints keep prepare's) and rounded into the lanes first.
  void warmStart(const StepContext& ctx, bool positions_moved);
  // The biased sweep takes the colours forward and backward in turn, substep by substep
  // (counted by warmStart) and step by step (StepContext::odd_step): solved always in one
  // order, the contacts of the colour solved last take the push-out, and down a stack every
  // other contact sinks to the linear slop while its neighbours stay shallow; turned only by
  // substep, the last substep of every step is a forward one, and its impulses (what the
  // contact reports show) lean the same way step after step.
  void solve(const StepContext& ctx, bool use_bias, bool positions_moved);
  // The lanes' impulses (normal, tangents, largest normal increment) into the double
  // constraints, which stay the source for everything after the substeps.
  void syncImpulses(std::vector<ContactConstraint>& cs) const;
  // Whether every point of the constraint in slot `slot` (in the blocks) lies at least
  // `separation` apart at the separations of the last update, when that update came after the
  // last position change: a relax sweep's, and no biased sweep (after which the positions
  // advance) since. False for a slot the blocks do not hold.
  bool apartAtLastUpdate(int slot, double separation) const;
  // Where slot `slot` sits in the blocks: block * kRowBlock + lane, -1 for a scalar one.
  int laneOf(int slot) const { return lane_of_slot_[slot - begin_]; }

 private:
  void updateSeparations(const StepContext& ctx);
  // The next block, zeroed for manifolds of up to `points` points; the blocks are kept from
  // step to step.
  void newBlock(int points, int colour);
  void fillLane(const ContactConstraint& cc, const std::vector<SolverBody>& bodies, int lane_slot);

  int begin_ = 0, end_ = -1;
  int substep_ = 0;  // the warm starts since build: the substep, from 1
  bool separations_settled_ = false;  // the last update follows the last position change
  std::vector<int> scalar_;
  std::vector<int> wide_;  // the slots in blocks
  std::vector<int> lane_of_slot_;  // of slot begin_ + i: block * kRowBlock + lane, -1: scalar
  std::vector<ContactBlock> blocks_;  // [0, block_count_) this step's
  std::vector<ContactGeometryBlock> geometry_;  // of blocks_[k]
  int block_count_ = 0;
  std::vector<GraphEdge> edges_;
  std::vector<int> candidates_;    // the eligible slots, in slot order
  std::vector<int> colour_slots_;  // one colour's slots, by point count and carried impulse
  ConstraintGraph graph_;
};

}  // namespace ragdoll_sim
