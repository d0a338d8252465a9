// Lumping: a link and everything below it by fixed joints (or by moving joints that lead only to
// massless links) become one body: exact, and cheaper than a weld the solver must hold.
#include "loader.hpp"

#include <cmath>

namespace ragdoll_sim {
namespace urdf_load {

// ---- mass and massless links --------------------------------------------------------
// The link's own mass (<inertial>, tiny placeholder masses read as 0) or, without an
// <inertial>, whether it has collision geometry to take a volume mass from.
double Loader::ownMass(const urdf::Link& l) {
  if (l.inertial) return std::isfinite(l.inertial->mass) && l.inertial->mass >= kTinyMass ? l.inertial->mass : 0.0;
  return l.collision_array.empty() ? 0.0 : 1.0;  // volume mass follows
}
bool Loader::massless(const urdf::Link& l) { return !(ownMass(l) > 0); }
// No mass anywhere in the subtree of `l` (a sensor frame, a tool tip, an empty gripper link).
bool Loader::subtreeMassless(const urdf::Link& l) const {
  if (!massless(l)) return false;
  for (const auto& j : l.child_joints)
    if (!subtreeMassless(*model_.getLink(j->child_link_name))) return false;
  return true;
}

// ---- links and fixed-joint lumping ---------------------------------------------------
void Loader::addGroup(const urdf::LinkConstSharedPtr& link) {
  groups_.emplace_back();
  groups_.back().top = link;
  addLink(int(groups_.size()) - 1, link, Transform());
}

// Adds `link` (frame T in the group's frame) and its fixed descendants to group g.
void Loader::addLink(int g, const urdf::LinkConstSharedPtr& link, const Transform& T) {
  placement_[link->name] = {g, T};
  addMassAndShapes(g, *link, T);
  const auto color = extras_.link_color.find(link->name);
  if (!groups_[g].has_color && color != extras_.link_color.end()) {
    groups_[g].has_color = true;
    groups_[g].color = color->second;
  }
  for (const auto& j : link->child_joints) {
    const urdf::LinkConstSharedPtr child = model_.getLink(j->child_link_name);
    const std::string jn = "joint " + quote(j->name);
    const bool spherical = extras_.spherical_joints.count(j->name) > 0;
    const bool keep_fixed = extras_.preserved_fixed.count(j->name) > 0;
    if (j->type == urdf::Joint::PLANAR)
      throw LoadError(jn + ": planar joints are not supported (use a prismatic pair)");
    if (j->type == urdf::Joint::FLOATING && !spherical)
      throw LoadError(jn + ": floating joints are supported only from a massless root link");
    if (j->type == urdf::Joint::UNKNOWN) throw LoadError(jn + ": unknown joint type");
    const bool moving = j->type != urdf::Joint::FIXED || keep_fixed;
    if (moving && subtreeMassless(*child)) {
      def_.notes.push_back(jn + ": leads only to massless links, lumped like a fixed joint (" +
                           quote(child->name) + " into " + quote(groups_[g].top->name) + ")");
    } else if (moving) {
      if (j->mimic)
        def_.warnings.push_back(jn + ": <mimic> of " + quote(j->mimic->joint_name) +
                                " not enforced (the joint moves freely)");
      groups_[g].child_joints.push_back(j);
      addGroup(child);
      continue;
    } else {
      def_.notes.push_back(jn + ": link " + quote(child->name) + " lumped into " +
                           quote(groups_[g].top->name));
    }
    addLink(g, child, T * toTransform(j->parent_to_joint_origin_transform, jn));
  }
}

}  // namespace urdf_load
}  // namespace ragdoll_sim
