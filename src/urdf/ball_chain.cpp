// Ball chains: 2-3 revolute joints through massless links fold into one ball joint when their
// inner origins coincide and their axes are orthogonal.
//
// Ball chain frames. URDF gives child-in-parent = O1 R(x1,t1) O2 R(x2,t2) O3 R(x3,t3) with joint
// origins Ok and axes xk in each joint's child frame. When O2 = Q2 and O3 = Q3 are pure rotations,
// moving them to the right (Q R(x,t) = R(Q x,t) Q) gives
//   O1 R(a0,t1) R(a1,t2) R(a2,t3) Q2 Q3,  a0 = x1, a1 = Q2 x2, a2 = Q2 Q3 x3  (in O1's frame),
// i.e. frame_parent = O1 and frame_child = (Q2 Q3)^-1, matching RagdollJointDef's convention.
// A chain that cannot fold (offset or skew axes, > 3 joints) keeps its hinges; its massless
// links then get a small nominal mass (a body cannot be massless).
#include "loader.hpp"

#include <cmath>

namespace ragdoll_sim {
namespace urdf_load {

bool Loader::isChainLink(const Group& g, double parent_mass) const {
  return g.shapes.empty() && g.child_joints.size() == 1 && movesAsChain(*g.child_joints[0]) &&
         !extras_.preserved_fixed.count(g.child_joints[0]->name) &&
         g.mass.mass < kDummyFraction * parent_mass;
}

// A chain of joints through massless links, or why it cannot be one ball joint.
std::string Loader::foldProblem(const std::vector<urdf::JointConstSharedPtr>& chain,
                                const std::vector<std::string>& dummies, int child) const {
  if (chain.size() > 3) return "more than 3 joints through massless links";
  for (const auto& d : dummies)
    if (!(groups_[groupOf(d)].mass.mass < kDummyFraction * groups_[child].mass.mass))
      return "link " + quote(d) + " is not negligible next to " + quote(groups_[child].top->name);
  std::vector<Vec3> axes;
  Quat Q = Quat::Identity();
  for (size_t k = 0; k < chain.size(); ++k) {
    if (k > 0) {
      const Transform O = origin(*chain[k]);
      if (O.p.norm() > kCoincident)
        return "joint " + quote(chain[k]->name) + " has a translated origin (" + num(O.p.norm()) + " m)";
      Q = Q * O.q;
    }
    axes.push_back(Q * unitAxis(*chain[k]));
  }
  for (size_t a = 0; a < axes.size(); ++a)
    for (size_t b = a + 1; b < axes.size(); ++b)
      if (std::abs(axes[a].dot(axes[b])) > kOrthogonal) return "axes are not orthogonal";
  return "";
}

}  // namespace urdf_load
}  // namespace ragdoll_sim
