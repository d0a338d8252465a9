// Exact joint anchors: a direct solve of the point rows of each island's joint tree (Baraff
// 1996, "Linear-time dynamics using Lagrange multipliers"), after the Gauss-Seidel sweeps.
//
// Why: Gauss-Seidel over the joints converges slowly where masses differ a lot along a limb
// (a heavy torso and gram fingers) or where many links hang on one body (a hub with hundreds of
// children): the anchors drift apart however many sweeps run. A tree of joints, though, has a
// sparse factorisation without fill-in, so the rows can be solved exactly in linear time.
//
// The rows: a rigid anchor (ball, hinge, fixed; not a spring) between bodies A and B,
//   C = (xB + rB) - (xA + rA),  J_B = P(rB), J_A = -P(rA),  P(r) = [I  -skew(r)]  (3 x 6)
// on a body's generalised velocity u = (v, w), W = M^-1 = diag(1/m I, I^-1) (world).
// Velocity projection: find the impulses lambda with (J W J^T + E) lambda = -(J u), E a tiny
// regularisation (keeps redundant rows, a body pinned twice, definite), then u += W J^T lambda.
//
// The tree: bodies that move are nodes, joints between two of them edges; a spanning forest
// over them in joint order (a joint that closes a loop stays with the sweeps alone), rooted at
// each component's first body. A joint to a body that does not move (static, asleep) hangs on
// its one moving body as a leaf. Each body p, in an order that puts children first, takes its
// child joints k one at a time (Woodbury form of Baraff's block elimination, so that W is
// never inverted):
//   Jp = s P(r_p), Jc = -s P(r_c)  (s = +1 when p is the joint's B, else -1; c the child body)
//   K_k   = E + Jc W_c Jc^T + Jp W Jp^T              (W: p's so far; W_c, z_c: c's final)
//   G_k   = Jp W
//   W    <- W - G_k^T K_k^-1 G_k                      (p's response with child k attached)
// and with a right-hand side b (solve):
//   y_k   = b_k - Jc z_c - Jp z,   z <- z + G_k^T K_k^-1 y_k   (z starts at 0)
// W, z: p's generalised velocity change is W f + z for an impulse f from the joints not yet
// taken (later children, its own parent joint). Back from the roots, f = e (the parent
// joint's impulse Jc^T lambda on p, 0 at a root), children in reverse order:
//   lambda_k = K_k^-1 (y_k - G_k e),   e <- e + Jp^T lambda_k,   the child's e = Jc^T lambda_k.
// Every K_k is E plus positive semidefinite terms: the elimination is stable in any order.
// Cost: a few 3x6 and 6x6 products per joint, no allocation (the buffers grow with the world).
//
// Position projection: the same factorisation at the current poses with b = -C (beyond a
// slop), applied as position impulses (a Newton step on the anchors, no velocity added); two
// steps leave the anchors exact to second order.
//
// The tree of an island part lies in its slices of the island's body and joint arrays, so the
// halves of a split island (whole limbs, island_split.hpp) are solved at once on two threads.
// The forest depends only on the part's bodies (and whether each moves) and its joints (their
// bodies, and whether each is an unbroken rigid anchor): a part that finds those as its slices'
// last build left them keeps that build's forest (most steps change no island).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "island_schedule.hpp"
#include "joint.hpp"

namespace ragdoll_sim {

class JointTree {
 public:
  // Before the islands are solved (one thread): the buffers cover every body and joint.
  void reserve(int world_bodies, int island_bodies, int joints);
  // The forest of part p (a whole island, or a half of a split one, or an island attached to
  // one): joints [p.joint_begin, p.joint_end) of js, bodies of island_bodies.
  void build(const IslandRange& p, const std::vector<int>& island_bodies, Joint* const* js,
             const std::vector<SolverBody>& solver);
  // The point rows' velocities made exact at the anchors of the last refresh; the impulses
  // are added to the joints' accumulated ones (warm start, reports, breaks).
  // A tree is left as it is when none of its anchors' relative velocities exceeds tolerance
  // (m/s): its sweeps converged. A breakable anchor that would pass break_force h is left out
  // and breaks.
  void projectVelocities(const IslandRange& p, std::vector<SolverBody>& solver,
                         const std::vector<int>& island_bodies, double h, double tolerance);
  // Newton steps on the anchors at the current deltas, tree by tree until a tree's anchors are
  // within slop: the error beyond slop is removed (at most max_correction of it per joint and
  // step).
  void projectPositions(const IslandRange& p, std::vector<SolverBody>& solver,
                        const std::vector<int>& island_bodies, double slop,
                        double max_correction);

 private:
  using Vec6 = Eigen::Matrix<double, 6, 1>;
  using Mat6 = Eigen::Matrix<double, 6, 6>;
  using Mat36 = Eigen::Matrix<double, 3, 6>;

  struct Edge {
    Joint* joint = nullptr;
    int parent = -1, child = -1;  // body slots (island_bodies); child -1: a fixed body
    double s = 1.0;               // +1: the parent is the joint's B
    Vec3 r_parent = Vec3::Zero(), r_child = Vec3::Zero();  // levers at the factorised poses
    Mat3 k_inv = Mat3::Zero();
    Mat36 g = Mat36::Zero();
    Vec3 b = Vec3::Zero(), y = Vec3::Zero(), lambda = Vec3::Zero();
  };
  struct Node {
    Mat6 w;
    Vec6 z, e;
    int first = 0, end = 0;  // its child edges
  };

  // One tree of a part: its bodies order_[first, last), its edges edges_[edge_begin, edge_end).
  struct Tree {
    int first, last, edge_begin, edge_end;
  };
  // After build: part p's trees with an edge into its slots of trees_.
  void recordTrees(const IslandRange& p);
  // f(tree) for each tree of part p with an edge.
  template <class F>
  void forTrees(const IslandRange& p, F&& f);
  void projectTreeVelocities(const Tree& t, std::vector<SolverBody>& solver,
                             const std::vector<int>& island_bodies, double h, double tolerance);
  void projectTreePositions(const Tree& t, std::vector<SolverBody>& solver,
                            const std::vector<int>& island_bodies, double slop,
                            double max_correction);
  // Factorises tree t at its edges' levers (set by the caller).
  void factor(const Tree& t, const std::vector<SolverBody>& solver,
              const std::vector<int>& island_bodies);
  // lambda for the edges' b.
  void solve(const Tree& t);
  void gatherImpulses(const Tree& t);
  int edgeCount(const IslandRange& p) const { return edge_count_[p.body_begin]; }

  std::vector<int> slot_of_body_;  // world body -> island_bodies slot (valid in its part)
  std::vector<Node> nodes_;        // by island_bodies slot
  std::vector<int> order_;         // per part slice: body slots, parents before children
  std::vector<int> edge_count_;    // at the part's body_begin
  std::vector<Tree> trees_;        // per part slice: its trees with an edge (recordTrees)
  std::vector<int> tree_count_;    // at the part's body_begin
  std::vector<Edge> edges_;        // per part slice of the joint range: grouped by parent
  // What the convergence test reads of edges_[k], packed (an Edge is ~350 bytes, and most
  // substeps read only these for every edge and solve no tree).
  struct Check {
    const PointPart* anchor;
    int a, b;  // the joint's bodies
  };
  std::vector<Check> checks_;
  // scratch for build: candidate edges (a moving body's slot per side, else -1) per joint
  // slot, union-find and visited marks, adjacency (per body slot: its start in adj_, count)
  struct Candidate {
    Joint* joint;
    int a, b;
  };
  std::vector<Candidate> cand_;
  std::vector<int> uf_, degree_, adj_start_, adj_, parent_edge_;

  // The inputs of the last build that wrote each slot, and its part (owner: its body_begin;
  // at the body_begin slot also its other bounds), to tell when a part may keep its forest.
  struct BodyKey {
    int body = -1, owner = -1;
    bool moves = false;
  };
  struct JointKey {
    const Joint* joint = nullptr;
    int a = -1, b = -1, owner = -1;
    bool edge = false;  // an unbroken rigid anchor
  };
  struct PartKey {
    int body_end = -1, joint_begin = -1, joint_end = -1;
  };
  // True when part p's slices hold the forest of its bodies and joints as they are now;
  // else records them as the inputs of the build that follows.
  bool keepsForest(const IslandRange& p, const std::vector<int>& island_bodies, Joint* const* js,
                   const std::vector<SolverBody>& solver);
  std::vector<BodyKey> body_key_;    // by island_bodies slot
  std::vector<JointKey> joint_key_;  // by joint slot
  std::vector<PartKey> part_key_;    // at a part's body_begin
};

}  // namespace ragdoll_sim
