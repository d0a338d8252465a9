// Anatomy extensions of the URDF (read by the pre-pass, anatomy_xml.hpp) onto the RagdollDef.
#include "loader.hpp"

namespace ragdoll_sim {
namespace urdf_load {

void Loader::sphericalLimits(const std::string& joint, RagdollJointDef* jd) {
  const auto it = extras_.spherical_limits.find(joint);
  if (it == extras_.spherical_limits.end()) {
    def_.notes.push_back("joint " + quote(joint) + ": spherical, a ball joint without limits");
    return;
  }
  const SwingTwistLimits& l = it->second;
  jd->swing_twist = l;
  def_.notes.push_back("joint " + quote(joint) + ": spherical, a ball joint with swing-twist limits (cone " +
                       num(l.cone_1) + " about y, " + num(l.cone_2) + " about z; twist about x " +
                       num(l.twist_lower) + ".." + num(l.twist_upper) + " rad)");
}

void Loader::linkDamping(LinkDef* link) {
  const auto it = extras_.link_damping_factor.find(link->name);
  if (it == extras_.link_damping_factor.end()) return;
  link->linear_damping = link->angular_damping = dampingFactorRate(it->second);
  def_.notes.push_back("link " + quote(link->name) + ": <gazebo> dampingFactor " + num(it->second) +
                       " -> velocity damping " + num(link->linear_damping) +
                       " 1/s (Gazebo's decay per second at its 1 ms step)");
}

}  // namespace urdf_load
}  // namespace ragdoll_sim
