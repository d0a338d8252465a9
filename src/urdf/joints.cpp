// Moving joints -> RagdollJointDefs: hinges, sliders, free balls, welds and folded ball chains
// (ball_chain.cpp decides when a chain folds), with limits, dynamics and each body's rest pose.
#include "loader.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace ragdoll_sim {
namespace urdf_load {

// Joint origin in the frame of the group holding its parent link.
Transform Loader::origin(const urdf::Joint& j) const {
  return placement_.at(j.parent_link_name).second *
         toTransform(j.parent_to_joint_origin_transform, "joint " + quote(j.name));
}

Vec3 Loader::unitAxis(const urdf::Joint& j) {
  const Vec3 a = toVec(j.axis);
  if (!a.allFinite() || a.norm() < 1e-9) throw LoadError("joint " + quote(j.name) + ": zero <axis>");
  return a.normalized();
}

// Limits of one joint (continuous and without <limit>: +-pi, not limited).
bool Loader::limits(const urdf::Joint& j, double& lo, double& hi, std::vector<std::string>* warnings) {
  if (j.type == urdf::Joint::CONTINUOUS || !j.limits) {
    lo = -M_PI;
    hi = M_PI;
    return false;
  }
  lo = j.limits->lower;
  hi = j.limits->upper;
  if (!std::isfinite(lo) || !std::isfinite(hi))
    throw LoadError("joint " + quote(j.name) + ": <limit> lower / upper not finite");
  if (lo > hi)
    throw LoadError("joint " + quote(j.name) + ": <limit> lower " + num(lo) + " > upper " + num(hi));
  if (j.type == urdf::Joint::PRISMATIC) return true;
  // Angles are measured in (-pi, pi]: a range reaching past +-pi would put a limit at the
  // wrap, where the angle jumps by 2 pi and the limit kicks. Clip it short of the wrap.
  const double kWrap = M_PI - 0.05;
  if (hi - lo >= 2 * M_PI - 1e-9) {
    warnings->push_back("joint " + quote(j.name) + ": <limit> range " + num(lo) + ".." + num(hi) +
                        " covers a full turn; unlimited");
    lo = -M_PI;
    hi = M_PI;
    return false;
  }
  if (lo < -kWrap || hi > kWrap) {
    warnings->push_back("joint " + quote(j.name) + ": <limit> " + num(lo) + ".." + num(hi) +
                        " rad clipped to +-" + num(kWrap) + " (angles wrap at +-pi)");
    lo = std::max(lo, -kWrap);
    hi = std::min(hi, kWrap);
    if (lo > hi) lo = hi = std::abs(lo) < std::abs(hi) ? lo : hi;
  }
  return true;
}

// <dynamics damping friction> of one joint (0 without the element).
void Loader::dynamics(const urdf::Joint& j, double& damping, double& friction) {
  damping = j.dynamics ? j.dynamics->damping : 0.0;
  friction = j.dynamics ? j.dynamics->friction : 0.0;
  if (!std::isfinite(damping) || damping < 0 || !std::isfinite(friction) || friction < 0)
    throw LoadError("joint " + quote(j.name) +
                    ": <dynamics> damping and friction must be finite and >= 0");
}

// Creates the LinkDef of group g at rest pose `rest`, then its joints and child bodies.
// A group without mass gets a nominal one (`neighbour`: the parent group, -1 at the root).
void Loader::emitBody(int g, const Transform& rest, int neighbour) {
  Group& grp = groups_[g];
  const std::string ln = "link " + quote(grp.top->name);
  if (!(grp.mass.mass > 0)) {
    double ref = neighbour >= 0 ? groups_[neighbour].mass.mass : 0.0;
    for (const auto& j : grp.child_joints) {
      const double c = groups_[groupOf(j->child_link_name)].mass.mass;
      if (c > 0 && (!(ref > 0) || c < ref)) ref = c;
    }
    const double m = std::max(kNominalFraction * ref, 1e-3);
    const double r = 0.03;
    grp.mass.add(m, Vec3::Zero(), 0.4 * m * r * r * Mat3::Identity());
    def_.warnings.push_back(ln + ": massless but joined by moving joints on both sides (" +
                            std::string(neighbour < 0 ? "the root" : "not foldable into a ball") +
                            "); given " + num(m) + " kg");
  }
  LinkDef link;
  link.name = grp.top->name;
  link.mass = grp.mass.mass;
  link.com = grp.mass.com();
  link.inertia = grp.mass.inertia();
  if (!repairInertia(link.inertia, link.mass).empty())
    def_.warnings.push_back(ln + ": lumped inertia repaired (not physical)");
  link.shapes = grp.shapes;
  link.shape_sources = grp.sources;
  link.shape_friction = grp.friction;
  const auto own = extras_.link_material.find(link.name);
  if (own != extras_.link_material.end()) link.material = own->second;
  // Per shape only where a lumped link names another material than the body's.
  for (const std::string& m : grp.materials)
    if (!m.empty() && m != link.material) link.shape_materials = grp.materials;
  link.has_color = grp.has_color;
  if (grp.has_color) link.color = grp.color;
  link.rest_pose = rest;
  linkDamping(&link);
  grp.def_index = int(def_.links.size());
  def_.links.push_back(std::move(link));
  for (const auto& j : grp.child_joints) emitJoint(g, j, rest);
}

void Loader::emitJoint(int parent, const urdf::JointConstSharedPtr& first, const Transform& parent_rest) {
  // Follow the chain through massless geometry-less links with a single moving child.
  std::vector<urdf::JointConstSharedPtr> chain{first};
  std::vector<std::string> dummies;
  const double parent_mass = groups_[parent].mass.mass;
  int child = groupOf(first->child_link_name);
  const bool spherical = extras_.spherical_joints.count(first->name) > 0;
  const bool fixed = first->type == urdf::Joint::FIXED;
  const bool prismatic = first->type == urdf::Joint::PRISMATIC;
  if (movesAsChain(*first) && !spherical) {
    while (isChainLink(groups_[child], parent_mass)) {
      dummies.push_back(groups_[child].top->name);
      chain.push_back(groups_[child].child_joints[0]);
      child = groupOf(chain.back()->child_link_name);
    }
  }
  std::string names;
  for (const auto& j : chain) names += (names.empty() ? "" : "+") + j->name;
  if (chain.size() > 1) {
    const std::string problem = foldProblem(chain, dummies, child);
    if (!problem.empty()) {
      // Keep the first joint as a hinge; its massless child becomes a (nominal) body and the
      // rest of the chain is tried again from there.
      def_.warnings.push_back("joint chain " + quote(names) + ": not a ball joint (" + problem +
                              "); kept as separate hinges");
      // The first massless link becomes a body: a nominal share of the chain's lighter end.
      Group& mid = groups_[groupOf(first->child_link_name)];
      const double m = kNominalFraction * std::min(parent_mass, groups_[child].mass.mass);
      const double r = 0.03;
      mid.mass.add(m, Vec3::Zero(), 0.4 * m * r * r * Mat3::Identity());
      def_.warnings.push_back("link " + quote(mid.top->name) + ": massless link between hinges given " +
                              num(m) + " kg");
      chain.resize(1);
      dummies.clear();
      child = groupOf(first->child_link_name);
      names = first->name;
    }
  }

  RagdollJointDef jd;
  jd.name = names;
  jd.parent = groups_[parent].def_index;
  jd.frame_parent = origin(*first);
  jd.chain_links = dummies;
  if (spherical || fixed) {
    jd.kind = spherical ? RagdollJointKind::Ball : RagdollJointKind::Fixed;
    if (spherical) {
      double damping, friction;
      dynamics(*first, damping, friction);
      jd.axes = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
      jd.lower.assign(3, -M_PI);
      jd.upper.assign(3, M_PI);
      jd.damping.assign(3, damping);
      jd.friction.assign(3, friction);
      jd.source_joints = {first->name};
      sphericalLimits(first->name, &jd);
    } else {
      jd.source_joints = {first->name};
      def_.notes.push_back("joint " + quote(first->name) + ": fixed, kept as a weld (<preserveFixedJoint>)");
    }
    jd.frame_child = Transform();
  } else {
    Quat Q = Quat::Identity();  // Q2 Q3 ... accumulated (derivation: ball_chain.cpp)
    for (size_t k = 0; k < chain.size(); ++k) {
      const urdf::Joint& j = *chain[k];
      if (k > 0) Q = Q * origin(j).q;
      double lo, hi;
      jd.limited |= limits(j, lo, hi, &def_.warnings);
      double damping, friction;
      dynamics(j, damping, friction);
      jd.damping.push_back(damping);
      jd.friction.push_back(friction);
      jd.axes.push_back(Q * unitAxis(j));
      jd.lower.push_back(lo);
      jd.upper.push_back(hi);
      jd.source_joints.push_back(j.name);
      if (k < dummies.size()) jd.chain_offsets.emplace_back(Vec3::Zero(), Q);  // dummy k's frame
    }
    jd.frame_child = Transform(Vec3::Zero(), Q.conjugate());
    if (prismatic) {
      jd.kind = RagdollJointKind::Prismatic;
      if (!first->limits) jd.limited = false;
    } else if (chain.size() == 1) {
      jd.kind = RagdollJointKind::Hinge;
    } else {
      jd.kind = RagdollJointKind::Ball;
      const std::string where = "joint chain " + quote(names);
      // The Euler decomposition of the chain is singular where the middle angle reaches
      // +-pi/2; keep its range clear of that (the solver cannot hold a limit through it).
      const double kMiddleMax = M_PI / 2 - 0.05;
      if (jd.axes.size() == 3 && (jd.lower[1] < -kMiddleMax || jd.upper[1] > kMiddleMax)) {
        jd.lower[1] = std::max(jd.lower[1], -kMiddleMax);
        jd.upper[1] = std::min(jd.upper[1], kMiddleMax);
        jd.limited = true;
        def_.notes.push_back(where + ": middle axis range clamped to +-" + std::to_string(kMiddleMax) +
                             " rad (the chain is singular at +-pi/2)");
      }
      if (chain.size() == 2) {
        jd.axes.push_back(jd.axes[0].cross(jd.axes[1]).normalized());
        jd.lower.push_back(0.0);
        jd.upper.push_back(0.0);
        jd.damping.push_back(0.0);
        jd.friction.push_back(0.0);
        jd.limited = true;
        def_.notes.push_back(where + ": 2-joint chain, ball joint with the third axis locked");
      }
    }
  }
  jd.child = int(def_.links.size());  // emitBody appends the child next
  const Transform rest = parent_rest * jd.frame_parent * jd.frame_child.inverse();
  def_.no_collide.emplace_back(jd.parent, jd.child);
  def_.joints.push_back(std::move(jd));
  folded_links_ += dummies.size();
  for (const auto& d : dummies) folded_mass_ += groups_[groupOf(d)].mass.mass;
  emitBody(child, rest, parent);
}

}  // namespace urdf_load
}  // namespace ragdoll_sim
