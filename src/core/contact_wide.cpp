// The wide contact path of a prepared range (contact_wide.hpp); the kernels are in
// contact_rows_wide.inc.
#include "contact_wide.hpp"

#include <algorithm>
#include <cstddef>
#include <cstring>

#include "contact_solver.hpp"
#include "lane_bodies.hpp"
#include "lane_width.hpp"
#include "solver_context.hpp"

namespace ragdoll_sim {

static_assert(kBlockPoints == Manifold::kMaxPoints, "a block holds a whole manifold");

namespace {
void setVec(float (&field)[3][kRowBlock], int lane, const Vec3& x) {
  for (int k = 0; k < 3; ++k) field[k][lane] = float(x[k]);
}

bool wide8(int width) { return width == 8 && cpuHasAvx2(); }
// The kernels of the width: with AVX-512F, the 8-lane one solves two blocks at once (the same
// bits).
void warmStartBlocks(int width, ContactBlock* blocks, int count, const LaneBodies& bodies) {
  if (wide8(width) && cpuHasAvx512())
    return kernel_w16::warmStartContactBlocks(blocks, count, bodies);
  if (wide8(width)) kernel_w8::warmStartContactBlocks(blocks, count, bodies);
  else kernel_w4::warmStartContactBlocks(blocks, count, bodies);
}
void solveBlocks(int width, ContactBlock* blocks, int count, const LaneBodies& bodies,
                 const NormalRowParams& params) {
  if (wide8(width) && cpuHasAvx512())
    return kernel_w16::solveContactBlocks(blocks, count, bodies, params);
  if (wide8(width)) kernel_w8::solveContactBlocks(blocks, count, bodies, params);
  else kernel_w4::solveContactBlocks(blocks, count, bodies, params);
}
// The kernels write a movable body only (a static or sleeping one is shared between ranges).
int writable(const std::vector<SolverBody>& bodies, int b) { return movable(bodies[b]) ? b : -1; }
}  // namespace

void ContactBatch::build(std::vector<ContactConstraint>& cs, const StepContext& ctx, int begin,
                         int end) {
  const auto& bodies = *ctx.bodies;
  begin_ = begin;
  end_ = end;
  substep_ = 0;
  separations_settled_ = false;
  lane_of_slot_.assign(end - begin, -1);
  scalar_.clear();
  wide_.clear();
  block_count_ = 0;
  std::vector<int>& candidates = candidates_;
  candidates.clear();
  for (int k = begin; k < end; ++k) {
    if (!wideEligible(cs[k])) {
      scalar_.push_back(k);
      continue;
    }
    candidates.push_back(k);
  }
  if (candidates.empty()) return;
  edges_.resize(candidates.size());
  for (size_t i = 0; i < candidates.size(); ++i) {
    const ContactConstraint& cc = cs[candidates[i]];
    GraphEdge& e = edges_[i];
    e.body_a = cc.a;
    e.body_b = cc.b;
    e.dynamic_a = movable(bodies[cc.a]);
    e.dynamic_b = movable(bodies[cc.b]);
  }
  graph_.colour(edges_.data(), int(edges_.size()), int(bodies.size()));
  for (int c = 0; c < graph_.colourCount(); ++c) {
    // A block loops over the points of its largest manifold: by point count, most first, the
    // manifolds of a colour fill the blocks' points better. Within a count, those that carry
    // no normal impulse (mostly speculative ones, which stay apart) go last, so that they fill
    // blocks of their own, which the sweeps skip as idle. The constraints of a colour share no
    // body, so their order within it changes no bit.
    const int* order = graph_.order().data() + graph_.colourBegin(c);
    const int size = graph_.colourSize(c);
    // A counting sort: bucket 2 (kMax - count), then + 1 without a carried impulse, in order.
    constexpr int kMax = Manifold::kMaxPoints;
    const auto bucket = [&](const ContactConstraint& cc) {
      bool carried = false;
      for (int i = 0; i < cc.count; ++i) carried |= cc.points[i].normal_impulse != 0.0;
      return 2 * (kMax - cc.count) + (carried ? 0 : 1);
    };
    int first[2 * kMax + 1] = {};  // where each bucket begins
    for (int j = 0; j < size; ++j) ++first[bucket(cs[candidates[order[j]]]) + 1];
    for (int k = 1; k <= 2 * kMax; ++k) first[k] += first[k - 1];
    colour_slots_.resize(size);
    for (int j = 0; j < size; ++j) {
      const int slot = candidates[order[j]];
      colour_slots_[first[bucket(cs[slot])]++] = slot;
    }
    for (int j = 0; j < int(colour_slots_.size()); ++j) {
      const int slot = colour_slots_[j];
      if (j % kRowBlock == 0) newBlock(cs[slot].count, c);
      const int lane_slot = (block_count_ - 1) * kRowBlock + j % kRowBlock;
      wide_.push_back(slot);
      lane_of_slot_[slot - begin] = lane_slot;
      fillLane(cs[slot], bodies, lane_slot);
    }
  }
  const int overflow = graph_.colourBegin(graph_.colourCount());
  for (int j = overflow; j < graph_.size(); ++j) scalar_.push_back(candidates[graph_.order()[j]]);
  std::sort(scalar_.begin(), scalar_.end());
  prepareBlockRows(geometry_.data(), blocks_.data(), block_count_, laneBodies(ctx.bodies->data()));
  for (size_t i = 0; i < wide_.size(); ++i) {  // for the position projection
    ContactConstraint& cc = cs[wide_[i]];
    const int lane_slot = lane_of_slot_[wide_[i] - begin_];
    const ContactGeometryBlock& g = geometry_[lane_slot / kRowBlock];
    const int l = lane_slot % kRowBlock;
    for (int p = 0; p < cc.count; ++p) cc.points[p].normal_mass = g.normal_mass[p][l];
  }
}

void ContactBatch::newBlock(int points, int colour) {
  if (block_count_ == int(blocks_.size())) {
    blocks_.emplace_back();
    geometry_.emplace_back();
  }
  // A lane's points past its count are computed from whatever they hold, and not stored.
  std::memset(static_cast<void*>(&geometry_[block_count_]), 0,
              offsetof(ContactGeometryBlock, r_a));
  ContactBlock& b = blocks_[block_count_++];
  // Padding is zero rows and mass 0; the kernels read no point past the block's first lane's
  // count, the most of its lanes. The rows are all written by prepareBlockRows.
  std::memset(static_cast<void*>(&b), 0, offsetof(ContactBlock, point));
  constexpr size_t kRows = offsetof(ContactPointLanes, separation);
  for (int p = 0; p < points; ++p)
    std::memset(reinterpret_cast<char*>(&b.point[p]) + kRows, 0, sizeof(ContactPointLanes) - kRows);
  for (int l = 0; l < kRowBlock; ++l) b.body_a[l] = b.body_b[l] = -1;
  b.colour = colour;
}

void ContactBatch::fillLane(const ContactConstraint& cc, const std::vector<SolverBody>& bodies,
                            int lane_slot) {
  ContactBlock& b = blocks_[lane_slot / kRowBlock];
  const int l = lane_slot % kRowBlock;
  b.body_a[l] = writable(bodies, cc.a);
  b.body_b[l] = writable(bodies, cc.b);
  b.inv_mass_a[l] = float(bodies[cc.a].inv_mass);
  b.inv_mass_b[l] = float(bodies[cc.b].inv_mass);
  setVec(b.n, l, cc.normal);
  setVec(b.t0, l, cc.tangent[0]);
  setVec(b.t1, l, cc.tangent[1]);
  b.friction[l] = float(cc.friction);
  b.points = std::max(b.points, int32_t(cc.count));
  ContactGeometryBlock& g = geometry_[lane_slot / kRowBlock];
  g.body_a[l] = cc.a;
  g.body_b[l] = cc.b;
  g.count[l] = cc.count;
  for (int k = 0; k < 3; ++k) {
    g.n[k][l] = cc.normal[k];
    g.t[0][k][l] = cc.tangent[0][k];
    g.t[1][k][l] = cc.tangent[1][k];
  }
  for (int i = 0; i < cc.count; ++i) {
    const ContactConstraintPoint& p = cc.points[i];
    ContactPointLanes& q = b.point[i];
    for (int k = 0; k < 3; ++k) {
      g.r_a[i][k][l] = p.rA[k];
      g.r_b[i][k][l] = p.rB[k];
    }
    g.base[i][l] = p.base_separation;
    // The separation comes with the first warm start (positions_moved), the largest increment
    // starts at the zero newBlock left.
    q.impulse[0][l] = float(p.normal_impulse);
    q.impulse[1][l] = float(p.tangent_impulse[0]);
    q.impulse[2][l] = float(p.tangent_impulse[1]);
  }
}

bool ContactBatch::apartAtLastUpdate(int slot, double separation) const {
  if (!separations_settled_) return false;
  const int lane_slot = lane_of_slot_[slot - begin_];
  if (lane_slot < 0) return false;
  const ContactGeometryBlock& g = geometry_[lane_slot / kRowBlock];
  const int l = lane_slot % kRowBlock;
  for (int p = 0; p < g.count[l]; ++p)
    if (!(g.separation[p][l] >= separation)) return false;
  return true;
}

void ContactBatch::updateSeparations(const StepContext& ctx) {
  updateBlockSeparations(geometry_.data(), blocks_.data(), block_count_,
                         laneBodies(ctx.bodies->data()));
}

void ContactBatch::warmStart(const StepContext& ctx, bool positions_moved) {
  ++substep_;
  if (block_count_ == 0) return;
  if (positions_moved) updateSeparations(ctx);
  const LaneBodies view = laneBodies(ctx.bodies->data());
  const int n = block_count_;
  warmStartBlocks(ctx.lanes, blocks_.data(), n, view);
}

void ContactBatch::solve(const StepContext& ctx, bool use_bias, bool positions_moved) {
  // The positions advance after the biased sweep; a relax sweep's update is at the new ones.
  if (use_bias) separations_settled_ = false;
  else if (positions_moved) separations_settled_ = true;
  if (block_count_ == 0) return;
  if (positions_moved) updateSeparations(ctx);
  const SolverSettings& s = *ctx.settings;
  NormalRowParams p;
  p.inv_h = float(ctx.inv_h);
  p.bias_rate = float(ctx.contact_softness.bias_rate);
  p.mass_scale = float(ctx.contact_softness.mass_scale);
  p.impulse_scale = float(ctx.contact_softness.impulse_scale);
  p.linear_slop = float(s.linear_slop);
  p.max_push_velocity = float(s.max_push_velocity);
  p.use_bias = use_bias;
  const LaneBodies view = laneBodies(ctx.bodies->data());
  const int n = block_count_;
  const auto sweep = [&](ContactBlock* first, int count) {
    solveBlocks(ctx.lanes, first, count, view, p);
  };
  // The colours in reverse order, each colour's blocks in order (they share no body: the same
  // bits in any order).
  if (use_bias && (substep_ + int(ctx.odd_step)) % 2 == 0) {
    for (int last = n - 1, first; last >= 0; last = first - 1) {
      for (first = last; first > 0 && blocks_[first - 1].colour == blocks_[last].colour;) --first;
      sweep(&blocks_[first], last - first + 1);
    }
    return;
  }
  sweep(blocks_.data(), n);
}

void ContactBatch::syncImpulses(std::vector<ContactConstraint>& cs) const {
  for (size_t i = 0; i < wide_.size(); ++i) {
    ContactConstraint& cc = cs[wide_[i]];
    const int lane_slot = lane_of_slot_[wide_[i] - begin_];
    const ContactBlock& b = blocks_[lane_slot / kRowBlock];
    const int l = lane_slot % kRowBlock;
    for (int p = 0; p < cc.count; ++p) {
      const ContactPointLanes& q = b.point[p];
      cc.points[p].normal_impulse = q.impulse[0][l];
      cc.points[p].tangent_impulse[0] = q.impulse[1][l];
      cc.points[p].tangent_impulse[1] = q.impulse[2][l];
      cc.points[p].max_normal_impulse = q.max_impulse[l];
    }
  }
}

}  // namespace ragdoll_sim
