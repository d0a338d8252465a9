#include "point_lanes.hpp"

#include <algorithm>
#include <cmath>

#include "joint.hpp"
#include "joint_angles.hpp"
#include "softness.hpp"

namespace ragdoll_sim {

namespace {
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
void putFrame(double (&field)[3][kRowBlock], int i, const Vec3& v) {
  for (int k = 0; k < 3; ++k) field[k][i] = v[k];
}
Vec3 frameAt(const double (&field)[3][kRowBlock], int i) {
  return {field[0][i], field[1][i], field[2][i]};
}
HingeAxisPart* hingeAxis(Joint& j) {
  HingeJoint* h = std::get_if<HingeJoint>(&j.kind);
  return h ? &h->hinge_axis : nullptr;
}

// f(axes) for the joint's angle axes (a ball's Euler angles, a hinge's angle), if it has them.
template <class F>
void withAngleAxes(Joint& j, F&& f) {
  if (BallJoint* b = std::get_if<BallJoint>(&j.kind)) f(b->axes);
  else if (HingeJoint* h = std::get_if<HingeJoint>(&j.kind)) f(h->axes);
}

// Marks the axes in the lanes when they have rows to solve (limits, a motor or damping) and
// returns how many angle rows they bring (0: none).
template <int N>
int takeAngles(AngleAxes<N>& ax) {
  ax.in_lanes = ax.rowsNeeded();
  return ax.in_lanes ? N : 0;
}

// Whether a lane's joint leaves nothing to the sweeps: a ball or hinge brings every angle row
// it has (takeAngles); a swing-twist limit and a fixed joint's rotation lock stay scalar.
bool sweepsInLanes(const Joint& j) {
  if (const BallJoint* b = std::get_if<BallJoint>(&j.kind)) return !b->swing_twist_limits;
  return std::holds_alternative<HingeJoint>(j.kind);
}

// What moves with the angles, rows [0, rows) of lane i: the limits' C and a position motor's
// bias. An angle without a row this substep (count < N: a ball near gimbal lock), or without a
// limit or a drive, gets an open range and no drive.
template <int N>
void putAngleErrors(PointRowBlock& blk, int i, const AngleAxes<N>& ax, int rows, double h) {
  for (int r = 0; r < rows; ++r) {
    const bool used = r < ax.count;
    const bool limit = used && ax.limits_enabled;
    const double lower = limit ? ax.angles[r] - ax.lower[r] : 1.0;
    const double upper = limit ? ax.upper[r] - ax.angles[r] : 1.0;
    blk.limit_c[r][0][i] = float(std::min(lower, kFarOpen));
    blk.limit_c[r][1][i] = float(std::min(upper, kFarOpen));
    if (!blk.motor_rows) continue;
    const JointMotor* m = used ? &ax.motors[r] : nullptr;
    double bias = 0.0, mass_scale = 0.0, impulse_scale = 0.0;
    if (m && m->enabled && m->hertz > 0.0) {
      const Softness soft = Softness::make(m->hertz, m->damping_ratio, h);
      bias = soft.bias_rate * (ax.angles[r] - m->target);
      mass_scale = soft.mass_scale;
      impulse_scale = soft.impulse_scale;
    } else if (m && m->enabled) {
      bias = -m->target_velocity;
      mass_scale = 1.0;
    }
    blk.motor_bias[r][i] = float(bias);
    blk.motor_mass_scale[r][i] = float(mass_scale);
    blk.motor_impulse_scale[r][i] = float(impulse_scale);
    blk.motor_max[r][i] = m && m->enabled ? float(m->max_torque * h) : 0.0f;
    blk.motor_hc[r][i] = m && m->damping > 0.0 ? float(h * m->damping) : 0.0f;
  }
}

// Rows [0, rows) of lane i at the current position state: the above, j and the impulses.
template <int N>
void putAngles(PointRowBlock& blk, int i, const AngleAxes<N>& ax, int rows, double h) {
  putAngleErrors(blk, i, ax, rows, h);
  for (int r = 0; r < rows; ++r) {
    const bool used = r < ax.count;
    putVec(blk.angle_j[r], i, used ? ax.rows[r] : Vec3::Zero());
    blk.limit_impulse[r][0][i] = used ? float(ax.limits[r].lower_impulse) : 0.0f;
    blk.limit_impulse[r][1][i] = used ? float(ax.limits[r].upper_impulse) : 0.0f;
    if (blk.motor_rows) blk.motor_impulse[r][i] = used ? float(ax.motor_parts[r].impulse) : 0.0f;
  }
}

// Rows [0, rows) of lane i's frame: the rate rows, angles and which rows have a limit as the
// warm start left them (count < N: the rows past it are open and still).
template <int N>
void putFrameAngles(PointFrameBlock& frame, int i, const AngleAxes<N>& ax, int rows) {
  for (int r = 0; r < rows; ++r) {
    const bool used = r < ax.count;
    const Vec3 j = used ? ax.rows[r] : Vec3::Zero();
    for (int k = 0; k < 3; ++k) frame.angle_j[r][k][i] = j[k];
    frame.angles[r][i] = used ? ax.angles[r] : 0.0;
    frame.limited[r][i] = used && ax.limits_enabled ? 1.0 : 0.0;
  }
}

template <int N>
void takeAngleImpulses(const PointRowBlock& blk, int i, AngleAxes<N>& ax) {
  for (int r = 0; r < ax.count; ++r) {
    ax.limits[r].lower_impulse = double(blk.limit_impulse[r][0][i]);
    ax.limits[r].upper_impulse = double(blk.limit_impulse[r][1][i]);
    if (blk.motor_rows) ax.motor_parts[r].impulse = double(blk.motor_impulse[r][i]);
  }
}
}  // namespace

void PointLanes::reserve(int joints) {
  if (int(ranges_.size()) < joints) ranges_.resize(joints);
}

PointLanes::Range* PointLanes::rangeOf(const IslandRange& p) const {
  return p.joint_end > p.joint_begin ? ranges_[p.joint_begin].get() : nullptr;
}

namespace {
bool sameEdges(const std::vector<GraphEdge>& x, const std::vector<GraphEdge>& y) {
  if (x.size() != y.size()) return false;
  for (size_t k = 0; k < x.size(); ++k)
    if (x[k].body_a != y[k].body_a || x[k].body_b != y[k].body_b ||
        x[k].dynamic_a != y[k].dynamic_a || x[k].dynamic_b != y[k].dynamic_b)
      return false;
  return true;
}
}  // namespace

void PointLanes::addLaneFill(const IslandRange& p, int& rows, int& lanes) const {
  if (p.joint_end <= p.joint_begin || !ranges_[p.joint_begin]) return;
  const Range& r = *ranges_[p.joint_begin];
  rows += int(r.lanes.size());
  lanes += int(r.blocks.size()) * kRowBlock;
}

void PointLanes::build(const IslandRange& p, Joint* const* js,
                       const std::vector<SolverBody>& bodies) {
  if (p.joint_end <= p.joint_begin) return;
  std::unique_ptr<Range>& slot = ranges_[p.joint_begin];
  if (!slot) slot = std::make_unique<Range>();  // on this thread, in its own memory
  Range* R = slot.get();
  // The colouring's scratch is this thread's: ranges are built on different threads, and a
  // range's result is copied into its own blocks before the next one is built.
  thread_local ConstraintGraph graph;
  thread_local LanePacking packing;
  thread_local std::vector<GraphEdge> edges;
  thread_local std::vector<AnchorPart*> members;
  thread_local std::vector<HingeAxisPart*> axes;
  thread_local std::vector<Joint*> joints;
  thread_local std::vector<int> kinds;
  edges.clear();
  members.clear();
  axes.clear();
  joints.clear();
  for (int k = p.joint_begin; k < p.joint_end; ++k) {
    Joint& j = *js[k];
    AnchorPart* anchor = j.anchor();
    if (!anchor || !wideAnchor(j)) continue;
    const bool da = movable(bodies[j.a]), db = movable(bodies[j.b]);
    if (!da && !db) continue;
    members.push_back(anchor);
    axes.push_back(hingeAxis(j));
    joints.push_back(&j);
    // written in place: a temporary's flag bytes read back as one word stall the store buffer
    GraphEdge& e = edges.emplace_back();
    e.body_a = j.a;
    e.body_b = j.b;
    e.dynamic_a = da;
    e.dynamic_b = db;
  }
  if (members != R->anchors || !sameEdges(edges, R->edges)) {
    R->anchors = members;
    R->edges = edges;
    R->angle_jobs.valid = false;
    R->lanes.clear();
    R->blocks.clear();
    if (members.empty()) return;
    graph.colour(edges, int(bodies.size()));
    // A record solves the angle rows and axis rows any of its lanes has, for all of them: its
    // lanes grouped by joint kind (within a colour the order changes no bit).
    kinds.clear();
    for (const Joint* j : joints) kinds.push_back(int(j->kind.index()));
    packing.pack(graph, kRowBlock, &kinds);
    const int count = packing.recordCount();
    R->blocks.assign(count, PointRowBlock{});
    R->frames.assign(count, PointFrameBlock{});
    for (int c = 0; c < graph.colourCount(); ++c)
      for (int r = packing.recordBegin(c); r < packing.recordBegin(c + 1); ++r)
        R->blocks[r].colour = c;
    for (int r = 0; r < count; ++r) {
      PointRowBlock& blk = R->blocks[r];
      PointFrameBlock& frame = R->frames[r];
      for (int i = 0; i < kRowBlock; ++i) {
        const int c = packing.lane(r, i);
        blk.body_a[i] = blk.body_b[i] = -1;
        // a padding lane's frame is all zeros on the block's first bodies: its results are 0
        const GraphEdge& e = edges[c < 0 ? packing.lane(r, 0) : c];
        frame.body_a[i] = e.body_a;
        frame.body_b[i] = e.body_b;
        if (c < 0) continue;
        R->lanes.push_back({joints[c], members[c], axes[c], e.body_a, e.body_b, r, i, 0, false});
        if (axes[c]) blk.axis_rows = 1;
        // a body the rows must not write stays -1, with inertia 0 in its lane
        if (e.dynamic_a) blk.body_a[i] = e.body_a;
        if (e.dynamic_b) blk.body_b[i] = e.body_b;
      }
    }
  }
  // The joints' flags, their limit rows, and the bodies' world inverse inertias and inverse
  // masses (new every step; a body the rows do not move counts as 0, as in pointMass).
  for (PointRowBlock& blk : R->blocks) blk.angle_rows = blk.motor_rows = 0;
  for (Lane& l : R->lanes) {
    PointRowBlock& blk = R->blocks[l.block];
    const int i = l.lane;
    l.anchor->in_lanes = true;  // and a hinge's axis with it (HingeJoint)
    withAngleAxes(*l.joint, [&](auto& ax) {
      l.angle_rows = takeAngles(ax);
      if (ax.motorsActive()) blk.motor_rows = 1;
    });
    l.joint->sweeps_in_lanes = sweepsInLanes(*l.joint);
    const bool exact = l.angle_rows && l.joint->sweeps_in_lanes;
    if (exact != l.exact) R->angle_jobs.valid = false;
    l.exact = exact;
    blk.angle_rows = std::max(blk.angle_rows, l.angle_rows);
    double inv_mass = 0.0;
    if (blk.body_a[i] >= 0) {
      putSymmetric(blk.ii_a, i, bodies[l.a].inv_inertia);
      inv_mass += bodies[l.a].inv_mass;
    }
    if (blk.body_b[i] >= 0) {
      putSymmetric(blk.ii_b, i, bodies[l.b].inv_inertia);
      inv_mass += bodies[l.b].inv_mass;
    }
    blk.inv_mass[i] = float(inv_mass);
    PointFrameBlock& frame = R->frames[l.block];
    const PointPart& pt = l.anchor->point;
    putFrame(frame.r_a0, i, pt.rA0);
    putFrame(frame.r_b0, i, pt.rB0);
    putFrame(frame.center, i, pt.delta_center);
    withAngleAxes(*l.joint, [&](auto& ax) {
      for (int r = 0; r < l.angle_rows; ++r) {
        frame.lower[r][i] = ax.lower[r];
        frame.upper[r][i] = ax.upper[r];
      }
    });
    if (!l.axis) continue;
    putFrame(frame.a1, i, l.axis->a1_0);
    putFrame(frame.b2, i, l.axis->b2_0);
    putFrame(frame.c2, i, l.axis->c2_0);
  }
}

void PointLanes::refreshFrames(Range& R, std::vector<SolverBody>& bodies, bool advance_angles,
                               double h) {
  refreshPointFrames(R.frames.data(), R.blocks.data(), int(R.blocks.size()),
                     laneBodies(bodies.data()), advance_angles, h);
  for (const Lane& l : R.lanes) {
    const PointFrameBlock& frame = R.frames[l.block];
    const int i = l.lane;
    l.anchor->point.rA = frameAt(frame.r_a, i);
    l.anchor->point.rB = frameAt(frame.r_b, i);
    // a joint with swing-twist limits recomputed its angles exactly (BallJoint::advance)
    if (advance_angles && l.angle_rows && l.joint->sweeps_in_lanes)
      withAngleAxes(*l.joint, [&](auto& ax) {
        for (int r = 0; r < ax.count; ++r) ax.angles[r] = frame.angles[r][i];
      });
    if (!l.axis) continue;
    l.axis->u1 = frameAt(frame.u1, i);
    l.axis->u2 = frameAt(frame.u2, i);
    l.axis->C = {frame.axis_c[0][i], frame.axis_c[1][i]};
  }
}

void PointLanes::exactAngles(const IslandRange& p, std::vector<SolverBody>& bodies,
                             const StepContext& ctx, bool first_substep) {
  Range* R = rangeOf(p);
  if (!R || R->blocks.empty()) return;
  AngleJobs& J = R->angle_jobs;
  // after the kernel: the row count (a ball's 0 at gimbal lock), marked recomputed
  const auto take = [](auto& ax, bool rows) {
    ax.count = rows ? int(ax.angles.size()) : 0;
    ax.fresh = true;
  };
  if (first_substep) {
    const std::vector<BodyMotion>& m = *ctx.motions;
    if (!J.valid || J.bodies != bodies.data() || J.motions != m.data()) {
      J.hinges.clear();
      J.balls.clear();
      J.hinge_of.clear();
      J.ball_of.clear();
      J.ok.resize(R->lanes.size());
      for (const Lane& l : R->lanes) {
        if (!l.exact) continue;
        const JointFrameInputs in = currentFrames(*l.joint, bodies[l.a], bodies[l.b], m);
        if (HingeJoint* h = std::get_if<HingeJoint>(&l.joint->kind)) {
          J.hinges.push_back(h->angleJob(in));
          J.hinge_of.push_back({&h->axes, l.a, l.b});
        } else if (BallJoint* b = std::get_if<BallJoint>(&l.joint->kind)) {
          J.balls.push_back(b->angleJob(in, &J.ok[J.balls.size()]));
          J.ball_of.push_back({&b->axes, l.a, l.b});
        }
      }
      J.valid = true;
      J.bodies = bodies.data();
      J.motions = m.data();
    }
    // the joints' prepare cleared the marks
    for (const auto& of : J.hinge_of) of.axes->exact_in_lanes = true;
    for (const auto& of : J.ball_of) of.axes->exact_in_lanes = true;
    hingeAngles(J.hinges.data(), int(J.hinges.size()));
    eulerAngles(J.balls.data(), int(J.balls.size()));
    for (const auto& of : J.hinge_of) take(*of.axes, true);
    for (size_t k = 0; k < J.balls.size(); ++k) take(*J.ball_of[k].axes, J.ok[k] != 0.0);
    return;
  }
  // Later substeps: the jobs of the joints that recompute (their limits not open).
  thread_local std::vector<HingeAngleJob> hinges;
  thread_local std::vector<EulerAngleJob> balls;
  thread_local std::vector<int> hinge_at, ball_at;
  const auto choose = [&](const auto& jobs, const auto& of, auto& chosen, std::vector<int>& at) {
    chosen.clear();
    at.clear();
    for (size_t k = 0; k < jobs.size(); ++k) {
      if (!of[k].axes->recomputes(bodies[of[k].a], bodies[of[k].b], ctx.h, false)) continue;
      chosen.push_back(jobs[k]);
      at.push_back(int(k));
    }
  };
  choose(J.hinges, J.hinge_of, hinges, hinge_at);
  choose(J.balls, J.ball_of, balls, ball_at);
  hingeAngles(hinges.data(), int(hinges.size()));
  eulerAngles(balls.data(), int(balls.size()));
  for (const int k : hinge_at) take(*J.hinge_of[k].axes, true);
  for (const int k : ball_at) take(*J.ball_of[k].axes, J.ok[k] != 0.0);
}

void PointLanes::load(const IslandRange& p, std::vector<SolverBody>& bodies,
                      const StepContext& ctx, bool anchors_moved, bool all_angles) {
  Range* R = rangeOf(p);
  if (!R || R->blocks.empty()) return;
  if (anchors_moved) refreshFrames(*R, bodies, false, ctx.h);
  for (const Lane& l : R->lanes) {
    const PointPart& pt = l.anchor->point;
    PointRowBlock& blk = R->blocks[l.block];
    const int i = l.lane;
    putVec(blk.impulse, i, pt.impulse);  // the joint trees add to it between the substeps
    // every lane of a block with angle rows writes them: a lane without any has j = 0
    if (l.angle_rows) {
      withAngleAxes(*l.joint, [&](auto& ax) {
        if (all_angles || ax.fresh || !l.joint->sweeps_in_lanes) {
          putAngles(blk, i, ax, blk.angle_rows, ctx.h);
          putFrameAngles(R->frames[l.block], i, ax, blk.angle_rows);
        }
        ax.fresh = false;
      });
    } else if (blk.angle_rows && all_angles) {
      static const AngleAxes<1> kNone;
      putAngles(blk, i, kNone, blk.angle_rows, ctx.h);
      putFrameAngles(R->frames[l.block], i, kNone, blk.angle_rows);
    }
    if (!l.axis) continue;
    blk.axis_impulse[0][i] = float(l.axis->impulse.x());
    blk.axis_impulse[1][i] = float(l.axis->impulse.y());
  }
  const LaneBodies view = laneBodies(bodies.data());
  warmStartPointRows(ctx.lanes, R->blocks.data(), int(R->blocks.size()), view);
}

void PointLanes::refreshAnchors(const IslandRange& p, std::vector<SolverBody>& bodies,
                                const StepContext& ctx) {
  Range* R = rangeOf(p);
  if (!R || R->blocks.empty()) return;
  // the angles advance with the positions (the rows are kept), and the limits' errors with them
  refreshFrames(*R, bodies, true, ctx.h);
  // a position motor's bias moves with its angle too, and the errors of angles recomputed
  // exactly (swing-twist limits) follow those
  for (const Lane& l : R->lanes) {
    PointRowBlock& blk = R->blocks[l.block];
    if (l.angle_rows && (blk.motor_rows || !l.joint->sweeps_in_lanes))
      withAngleAxes(*l.joint,
                    [&](auto& ax) { putAngleErrors(blk, l.lane, ax, blk.angle_rows, ctx.h); });
  }
}

void PointLanes::solve(const IslandRange& p, std::vector<SolverBody>& bodies,
                       const StepContext& ctx, bool use_bias, bool sync) {
  Range* R = rangeOf(p);
  if (!R || R->blocks.empty()) return;
  const Softness s = ctx.joint_softness.orRigid(use_bias);
  PointRowParams params;
  params.bias_rate = float(s.bias_rate);
  params.mass_scale = float(s.mass_scale);
  params.impulse_scale = float(s.impulse_scale);
  params.inv_h = float(ctx.inv_h);
  params.use_bias = use_bias;
  const LaneBodies view = laneBodies(bodies.data());
  solvePointRows(ctx.lanes, R->blocks.data(), int(R->blocks.size()), view, params);
  if (!sync) return;
  for (const Lane& l : R->lanes) {
    const PointRowBlock& blk = R->blocks[l.block];
    const int i = l.lane;
    for (int k = 0; k < 3; ++k) l.anchor->point.impulse[k] = double(blk.impulse[k][i]);
    if (l.angle_rows) withAngleAxes(*l.joint, [&](auto& ax) { takeAngleImpulses(blk, i, ax); });
    if (l.axis)
      l.axis->impulse = {double(blk.axis_impulse[0][i]), double(blk.axis_impulse[1][i])};
  }
}

}  // namespace ragdoll_sim
