#include "point_lanes.hpp"

#include <cmath>

#include "joint.hpp"

namespace ragdoll_sim {

namespace {
// The anchor of a ball, hinge or fixed joint (a slider has none).
AnchorPart* anchorOf(Joint& j) {
  switch (j.kind.index()) {
    case 0: return &std::get_if<0>(&j.kind)->anchor;
    case 1: return &std::get_if<1>(&j.kind)->anchor;
    case 2: return &std::get_if<2>(&j.kind)->anchor;
    default: return nullptr;
  }
}

// Rigid and unbreakable: a breakable anchor keeps its capped scalar solve, and only those can
// break within the step.
bool wideAnchor(const Joint& j) {
  return !j.broken && !(j.spring.stiffness > 0.0) && !std::isfinite(j.spring.break_force) &&
         !std::isfinite(j.spring.break_torque);
}

// Symmetric matrix m into lane i of a six-entry field (xx, yy, zz, xy, xz, yz).
void putSymmetric(float (&field)[6][kRowBlock], int i, const Mat3& m) {
  field[0][i] = float(m(0, 0));
  field[1][i] = float(m(1, 1));
  field[2][i] = float(m(2, 2));
  field[3][i] = float(m(0, 1));
  field[4][i] = float(m(0, 2));
  field[5][i] = float(m(1, 2));
}
void putVec(float (&field)[3][kRowBlock], int i, const Vec3& v) {
  for (int k = 0; k < 3; ++k) field[k][i] = float(v[k]);
}
}  // namespace

void PointLanes::reserve(int joints) {
  if (int(ranges_.size()) < joints) ranges_.resize(joints);
}

PointLanes::Range* PointLanes::rangeOf(const IslandRange& p) {
  return p.joint_end > p.joint_begin ? &ranges_[p.joint_begin] : nullptr;
}

void PointLanes::build(const IslandRange& p, Joint* const* js,
                       const std::vector<SolverBody>& bodies) {
  Range* R = rangeOf(p);
  if (!R) return;
  R->members.clear();
  R->body_index.clear();
  for (int k = p.joint_begin; k < p.joint_end; ++k) {
    const Joint& j = *js[k];
    if (!anchorOf(*js[k]) || !wideAnchor(j)) continue;
    R->members.push_back(k);
    R->body_index.push_back(j.a);
    R->body_index.push_back(j.b);
  }
  R->bodies.build(bodies, R->body_index.data(), int(R->body_index.size()));
  R->edges.clear();
  for (const int k : R->members) {
    const int a = R->bodies.record(js[k]->a), b = R->bodies.record(js[k]->b);
    R->edges.push_back({a, b, a >= 0, b >= 0});
  }
  R->graph.colour(R->edges, R->bodies.size());
  R->packing.pack(R->graph, kRowBlock);
  const int count = R->packing.recordCount();
  R->blocks.assign(count, PointRowBlock{});
  R->lane_joint.assign(size_t(count) * kRowBlock, -1);
  for (int r = 0; r < count; ++r) {
    PointRowBlock& blk = R->blocks[r];
    for (int i = 0; i < kRowBlock; ++i) {
      const int c = R->packing.lane(r, i);
      blk.body_a[i] = blk.body_b[i] = -1;
      if (c < 0) continue;
      Joint& j = *js[R->members[c]];
      anchorOf(j)->in_lanes = true;
      R->lane_joint[r * kRowBlock + i] = R->members[c];
      blk.body_a[i] = R->edges[c].body_a;
      blk.body_b[i] = R->edges[c].body_b;
      // a body the rows must not write keeps mass and inertia 0 in its lane
      if (blk.body_a[i] >= 0) {
        blk.inv_mass_a[i] = float(bodies[j.a].inv_mass);
        putSymmetric(blk.ii_a, i, bodies[j.a].inv_inertia);
      }
      if (blk.body_b[i] >= 0) {
        blk.inv_mass_b[i] = float(bodies[j.b].inv_mass);
        putSymmetric(blk.ii_b, i, bodies[j.b].inv_inertia);
      }
    }
  }
}

void PointLanes::load(const IslandRange& p, Joint* const* js,
                      const std::vector<SolverBody>& bodies) {
  Range* R = rangeOf(p);
  if (!R) return;
  for (size_t l = 0; l < R->lane_joint.size(); ++l) {
    if (R->lane_joint[l] < 0) continue;
    const Joint& j = *js[R->lane_joint[l]];
    const PointPart& pt = anchorOf(*js[R->lane_joint[l]])->point;
    PointRowBlock& blk = R->blocks[l / kRowBlock];
    const int i = int(l % kRowBlock);
    putSymmetric(blk.k_inv, i, pt.k_inv);
    putVec(blk.r_a, i, pt.rA);
    putVec(blk.r_b, i, pt.rB);
    putVec(blk.error, i, pt.error(bodies[j.a], bodies[j.b]));
    putVec(blk.impulse, i, pt.impulse);
  }
}

void PointLanes::refreshAnchors(const IslandRange& p, Joint* const* js) {
  Range* R = rangeOf(p);
  if (!R) return;
  for (size_t l = 0; l < R->lane_joint.size(); ++l) {
    if (R->lane_joint[l] < 0) continue;
    const PointPart& pt = anchorOf(*js[R->lane_joint[l]])->point;
    PointRowBlock& blk = R->blocks[l / kRowBlock];
    const int i = int(l % kRowBlock);
    putVec(blk.r_a, i, pt.rA);
    putVec(blk.r_b, i, pt.rB);
  }
}

void PointLanes::solve(const IslandRange& p, Joint* const* js, std::vector<SolverBody>& bodies,
                       const StepContext& ctx, bool use_bias) {
  Range* R = rangeOf(p);
  if (!R || R->blocks.empty()) return;
  const Softness s = ctx.joint_softness.orRigid(use_bias);
  PointRowParams params;
  params.bias_rate = float(s.bias_rate);
  params.mass_scale = float(s.mass_scale);
  params.impulse_scale = float(s.impulse_scale);
  params.use_bias = use_bias;
  R->bodies.gather(bodies);
  solvePointRows(ctx.lanes, R->blocks.data(), int(R->blocks.size()), R->bodies.records(), params);
  R->bodies.scatter(bodies);
  for (size_t l = 0; l < R->lane_joint.size(); ++l) {
    if (R->lane_joint[l] < 0) continue;
    const PointRowBlock& blk = R->blocks[l / kRowBlock];
    const int i = int(l % kRowBlock);
    Vec3& impulse = anchorOf(*js[R->lane_joint[l]])->point.impulse;
    for (int k = 0; k < 3; ++k) impulse[k] = double(blk.impulse[k][i]);
  }
}

}  // namespace ragdoll_sim
