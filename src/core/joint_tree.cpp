// The joint tree's build, factorisation and solves (the derivation: joint_tree.hpp).
#include "joint_tree.hpp"

#include <algorithm>
#include <limits>

namespace ragdoll_sim {

namespace {

// Relative size of the regularisation E against the pair's inverse masses: far below any
// row's own weight, far above round-off in the Woodbury updates.
constexpr double kRegularisation = 1e-9;
// Newton steps of the position projection: the second takes the first's error of second order.
constexpr int kNewtonSteps = 2;

// The rigid point part of a joint (a spring anchor is meant to stretch; a slider has none).
PointPart* rigidAnchor(Joint& j) {
  AnchorPart* a = j.spring.stiffness > 0.0 ? nullptr : j.anchor();
  return a ? &a->point : nullptr;
}

using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Mat36 = Eigen::Matrix<double, 3, 6>;

// P(r) X for P(r) = [I  -skew(r)] (columns: x.head - r x x.tail).
Mat36 leverRows(const Vec3& r, const Mat6& X) {
  Mat36 out;
  for (int k = 0; k < 6; ++k)
    out.col(k) = X.col(k).head<3>() - r.cross(Vec3(X.col(k).tail<3>()));
  return out;
}
// P(r) u
Vec3 leverRate(const Vec3& r, const Vec6& u) { return u.head<3>() + Vec3(u.tail<3>()).cross(r); }
// P(r)^T f: the generalised impulse of force f at lever r.
Vec6 leverImpulse(const Vec3& r, const Vec3& f) {
  Vec6 out;
  out << f, r.cross(f);
  return out;
}
// X P(r)^T for a 3 x 6 X (row i: x_i.head + x_i.tail x r).
Mat3 timesLeverT(const Mat36& X, const Vec3& r) {
  Mat3 out;
  for (int i = 0; i < 3; ++i) {
    const Vec3 head = X.row(i).head<3>().transpose(), tail = X.row(i).tail<3>().transpose();
    out.row(i) = (head + tail.cross(r)).transpose();
  }
  return out;
}
Mat6 inverseMass(const SolverBody& b) {
  Mat6 w = Mat6::Zero();
  w.topLeftCorner<3, 3>().diagonal().setConstant(b.inv_mass);
  w.bottomRightCorner<3, 3>() = b.inv_inertia;
  return w;
}

}  // namespace

void JointTree::reserve(int world_bodies, int island_bodies, int joints) {
  if (int(slot_of_body_.size()) < world_bodies) slot_of_body_.resize(world_bodies, -1);
  if (int(nodes_.size()) < island_bodies) {
    nodes_.resize(island_bodies);
    order_.resize(island_bodies);
    edge_count_.resize(island_bodies);
    trees_.resize(island_bodies);
    tree_count_.resize(island_bodies);
    uf_.resize(island_bodies);
    degree_.resize(island_bodies);
    adj_start_.resize(island_bodies);
    parent_edge_.resize(island_bodies);
    body_key_.resize(island_bodies);
    part_key_.resize(island_bodies);
  }
  if (int(edges_.size()) < joints) {
    edges_.resize(joints);
    checks_.resize(joints);
    joint_key_.resize(joints);
    cand_.resize(joints);
    adj_.resize(2 * size_t(joints));
  }
}

// Every slot of p is compared (and rewritten when one differs): a slot another part's build
// wrote since has that part's owner, and a later build of a part with the same body_begin
// rewrote the bounds at body_begin.
bool JointTree::keepsForest(const IslandRange& p, const std::vector<int>& island_bodies,
                            Joint* const* js, const std::vector<SolverBody>& solver) {
  const int b0 = p.body_begin;
  PartKey& part = part_key_[b0];
  bool same = part.body_end == p.body_end && part.joint_begin == p.joint_begin &&
              part.joint_end == p.joint_end;
  part = {p.body_end, p.joint_begin, p.joint_end};
  for (int k = b0; k < p.body_end; ++k) {
    const int b = island_bodies[k];
    const bool moves = movable(solver[b]);
    BodyKey& key = body_key_[k];
    if (key.body == b && key.owner == b0 && key.moves == moves) continue;
    same = false;
    key = {b, b0, moves};
  }
  for (int k = p.joint_begin; k < p.joint_end; ++k) {
    Joint& j = *js[k];
    const bool edge = !j.broken && rigidAnchor(j);
    JointKey& key = joint_key_[k];
    if (key.joint == &j && key.a == j.a && key.b == j.b && key.owner == b0 && key.edge == edge)
      continue;
    same = false;
    key = {&j, j.a, j.b, b0, edge};
  }
  return same;
}

void JointTree::build(const IslandRange& p, const std::vector<int>& island_bodies,
                      Joint* const* js, const std::vector<SolverBody>& solver) {
  if (keepsForest(p, island_bodies, js, solver)) return;
  const int b0 = p.body_begin, b1 = p.body_end, j0 = p.joint_begin;
  edge_count_[b0] = 0;
  for (int k = b0; k < b1; ++k) {
    slot_of_body_[island_bodies[k]] = k;
    uf_[k] = k;
    degree_[k] = 0;
  }
  const auto slotOf = [&](int b) {
    if (b < 0 || !movable(solver[b])) return -1;
    const int k = slot_of_body_[b];
    return k >= b0 && k < b1 && island_bodies[k] == b ? k : -1;
  };
  const auto root = [&](int k) {
    while (uf_[k] != k) k = uf_[k] = uf_[uf_[k]];
    return k;
  };
  // Candidate edges in joint order: each side's slot, -1 for a body that does not move.
  int n = 0;
  for (int k = j0; k < p.joint_end; ++k) {
    Joint& j = *js[k];
    if (j.broken || !rigidAnchor(j)) continue;
    const int sa = slotOf(j.a), sb = slotOf(j.b);
    if (sa < 0 && sb < 0) continue;
    if (sa >= 0 && sb >= 0) {
      const int ra = root(sa), rb = root(sb);
      if (ra == rb) continue;  // closes a loop: left to the sweeps
      uf_[std::max(ra, rb)] = std::min(ra, rb);
    }
    cand_[j0 + n++] = {&j, sa, sb};
    if (sa >= 0) ++degree_[sa];
    if (sb >= 0) ++degree_[sb];
  }
  if (n == 0) return;
  int start = 2 * j0;
  for (int k = b0; k < b1; ++k) {
    adj_start_[k] = start;
    start += degree_[k];
    degree_[k] = 0;
  }
  for (int e = 0; e < n; ++e)
    for (const int s : {cand_[j0 + e].a, cand_[j0 + e].b})
      if (s >= 0) adj_[adj_start_[s] + degree_[s]++] = e;
  // Breadth first from each component's first body (uf_ now holds the visited marks): the
  // edges are written grouped by their parent, parents before children.
  for (int k = b0; k < b1; ++k) uf_[k] = 0, parent_edge_[k] = -1;
  int head = b0, tail = b0, out = 0;
  for (int r = b0; r < b1; ++r) {
    if (uf_[r]) continue;
    uf_[r] = 1;
    order_[tail++] = r;
    while (head < tail) {
      const int q = order_[head++];
      nodes_[q].first = j0 + out;
      for (int a = adj_start_[q]; a < adj_start_[q] + degree_[q]; ++a) {
        const int c = adj_[a];
        if (c == parent_edge_[q]) continue;
        const Candidate& cd = cand_[j0 + c];
        const int other = cd.a == q ? cd.b : cd.a;
        checks_[j0 + out] = {rigidAnchor(*cd.joint), cd.joint->a, cd.joint->b};
        Edge& e = edges_[j0 + out++];
        e.joint = cd.joint;
        e.parent = q;
        e.child = other;
        e.s = cd.b == q ? 1.0 : -1.0;
        if (other >= 0) {
          parent_edge_[other] = c;
          uf_[other] = 1;
          order_[tail++] = other;
        }
      }
      nodes_[q].end = j0 + out;
    }
  }
  edge_count_[b0] = out;
  recordTrees(p);
}

void JointTree::factor(const Tree& t, const std::vector<SolverBody>& solver,
                       const std::vector<int>& island_bodies) {
  for (int idx = t.last - 1; idx >= t.first; --idx) {
    const int q = order_[idx];
    Node& node = nodes_[q];
    const SolverBody& body = solver[island_bodies[q]];
    node.w = inverseMass(body);
    for (int k = node.first; k < node.end; ++k) {
      Edge& e = edges_[k];
      if (e.joint->broken || e.joint->overloaded) {  // breaks after this substep: left out
        e.k_inv.setZero();
        e.g.setZero();
        continue;
      }
      const Mat36 x = leverRows(e.r_parent, node.w);  // P W, G = s P W
      Mat3 K = timesLeverT(x, e.r_parent);
      double inv_masses = body.inv_mass;
      if (e.child >= 0) {
        const Node& c = nodes_[e.child];
        K += timesLeverT(leverRows(e.r_child, c.w), e.r_child);
        inv_masses += solver[island_bodies[e.child]].inv_mass;
      }
      K.diagonal().array() += kRegularisation * inv_masses;
      K = 0.5 * (K + K.transpose());
      e.k_inv = K.inverse();
      e.g = e.s * x;
      node.w.noalias() -= x.transpose() * (e.k_inv * x);
    }
  }
}

void JointTree::solve(const Tree& t) {
  for (int idx = t.last - 1; idx >= t.first; --idx) {
    Node& node = nodes_[order_[idx]];
    node.z.setZero();
    node.e.setZero();
    for (int k = node.first; k < node.end; ++k) {
      Edge& e = edges_[k];
      e.y = e.b - e.s * leverRate(e.r_parent, node.z);
      if (e.child >= 0) e.y += e.s * leverRate(e.r_child, nodes_[e.child].z);
      node.z.noalias() += e.g.transpose() * (e.k_inv * e.y);
    }
  }
  for (int idx = t.first; idx < t.last; ++idx) {
    Node& node = nodes_[order_[idx]];
    Vec6 f = node.e;
    for (int k = node.end - 1; k >= node.first; --k) {
      Edge& e = edges_[k];
      e.lambda = e.k_inv * (e.y - e.g * f);
      f += e.s * leverImpulse(e.r_parent, e.lambda);
      if (e.child >= 0) nodes_[e.child].e = -e.s * leverImpulse(e.r_child, e.lambda);
    }
  }
}

// Build writes each tree's bodies (its root, then the rest breadth first) as one run of order_
// and its edges as one run of edges_, so a tree ends where every body its edges reach has been
// counted; the trees with an edge are kept at the part's slots for the projections.
void JointTree::recordTrees(const IslandRange& p) {
  int count = 0;
  for (int first = p.body_begin; first < p.body_end;) {
    Tree t{first, first + 1, 0, 0};
    for (int idx = first; idx < t.last; ++idx) {
      const Node& node = nodes_[order_[idx]];
      for (int k = node.first; k < node.end; ++k) t.last += edges_[k].child >= 0;
    }
    t.edge_begin = nodes_[order_[first]].first;
    t.edge_end = nodes_[order_[t.last - 1]].end;
    if (t.edge_end > t.edge_begin) trees_[p.body_begin + count++] = t;
    first = t.last;
  }
  tree_count_[p.body_begin] = count;
}

template <class F>
void JointTree::forTrees(const IslandRange& p, F&& f) {
  const int b0 = p.body_begin;
  for (int k = 0; k < tree_count_[b0]; ++k) f(trees_[b0 + k]);
}

// Each body's total generalised impulse from its edges' lambda (node e, reused after solve).
void JointTree::gatherImpulses(const Tree& t) {
  for (int idx = t.first; idx < t.last; ++idx) nodes_[order_[idx]].e.setZero();
  for (int k = t.edge_begin; k < t.edge_end; ++k) {
    const Edge& e = edges_[k];
    nodes_[e.parent].e += e.s * leverImpulse(e.r_parent, e.lambda);
    if (e.child >= 0) nodes_[e.child].e -= e.s * leverImpulse(e.r_child, e.lambda);
  }
}

// Each tree stops on its own error, so a tree's bits do not depend on the other trees of its
// part (nor on the islands that share its range).
void JointTree::projectVelocities(const IslandRange& p, std::vector<SolverBody>& solver,
                                  const std::vector<int>& island_bodies, double h,
                                  double tolerance) {
  if (edgeCount(p) == 0) return;
  forTrees(p, [&](const Tree& t) { projectTreeVelocities(t, solver, island_bodies, h, tolerance); });
}

void JointTree::projectTreeVelocities(const Tree& t, std::vector<SolverBody>& solver,
                                      const std::vector<int>& island_bodies, double h,
                                      double tolerance) {
  Edge* const edges = &edges_[t.edge_begin];
  const int n = t.edge_end - t.edge_begin;
  const auto anchorVelocity = [&](const Check& c) {  // -(J u): the anchors' relative velocity
    const SolverBody &A = solver[c.a], &B = solver[c.b];
    return Vec3(-(B.v + B.w.cross(c.anchor->rB) - A.v - A.w.cross(c.anchor->rA)));
  };
  double worst = 0.0;
  for (int k = 0; k < n; ++k)
    worst = std::max(worst, anchorVelocity(checks_[t.edge_begin + k]).squaredNorm());
  if (!(worst > tolerance * tolerance)) return;  // the sweeps converged
  for (int k = 0; k < n; ++k) {
    Edge& e = edges[k];
    const PointPart& pt = *checks_[t.edge_begin + k].anchor;
    e.r_parent = e.s > 0.0 ? pt.rB : pt.rA;
    e.r_child = e.s > 0.0 ? pt.rA : pt.rB;
    e.b = anchorVelocity(checks_[t.edge_begin + k]);
  }
  // A breakable anchor transmits at most its strength: one whose exact impulse would pass
  // break_force h is left out (it breaks after the substep, with what the sweeps gave it) and
  // the others are solved again without it.
  for (bool again = true; again;) {
    factor(t, solver, island_bodies);
    solve(t);
    again = false;
    for (int k = 0; k < n; ++k) {
      Joint& j = *edges[k].joint;
      const double cap = j.spring.break_force * h;
      if (j.overloaded || !(cap < std::numeric_limits<double>::infinity())) continue;
      if ((rigidAnchor(j)->impulse + edges[k].lambda).squaredNorm() > cap * cap)
        j.overloaded = again = true;
    }
  }
  for (int k = 0; k < n; ++k) rigidAnchor(*edges[k].joint)->impulse += edges[k].lambda;
  gatherImpulses(t);
  for (int idx = t.first; idx < t.last; ++idx) {
    const int q = order_[idx];
    SolverBody& b = solver[island_bodies[q]];
    const Vec6& f = nodes_[q].e;
    b.v += b.inv_mass * f.head<3>();
    b.w += b.inv_inertia * f.tail<3>();
  }
}

void JointTree::projectPositions(const IslandRange& p, std::vector<SolverBody>& solver,
                                 const std::vector<int>& island_bodies, double slop,
                                 double max_correction) {
  if (edgeCount(p) == 0) return;
  forTrees(p, [&](const Tree& t) {
    projectTreePositions(t, solver, island_bodies, slop, max_correction);
  });
}

// The bodies move by their summed position impulses at once: applied joint by joint, the
// rotations of a body with many children would compose to second order in their sizes.
void JointTree::projectTreePositions(const Tree& t, std::vector<SolverBody>& solver,
                                     const std::vector<int>& island_bodies, double slop,
                                     double max_correction) {
  for (int step = 0; step < kNewtonSteps; ++step) {
    bool any = false;
    for (int k = t.edge_begin; k < t.edge_end; ++k) {
      Edge& e = edges_[k];
      const Joint& j = *e.joint;
      const PointPart& pt = *rigidAnchor(*e.joint);
      const SolverBody &A = solver[j.a], &B = solver[j.b];
      const Vec3 rA = A.dq * pt.rA0, rB = B.dq * pt.rB0;
      e.r_parent = e.s > 0.0 ? rB : rA;
      e.r_child = e.s > 0.0 ? rA : rB;
      Vec3 C = pt.errorAt(A, B, rA, rB);
      if (trimToSlop(C, slop, max_correction)) any = true;
      else C.setZero();
      e.b = -C;
    }
    if (!any) return;
    factor(t, solver, island_bodies);
    solve(t);
    gatherImpulses(t);
    for (int idx = t.first; idx < t.last; ++idx) {
      const int q = order_[idx];
      SolverBody& b = solver[island_bodies[q]];
      const Vec6& f = nodes_[q].e;
      b.dp += b.inv_mass * f.head<3>();
      const Vec3 turn = b.inv_inertia * f.tail<3>();
      const double angle = turn.norm();
      if (angle > 0.0) b.dq = (Quat(Eigen::AngleAxisd(angle, turn / angle)) * b.dq).normalized();
    }
  }
}

}  // namespace ragdoll_sim
