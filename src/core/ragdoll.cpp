// RagdollDef -> bodies, shapes, joints and collision filters in a World.
#include "ragdoll_sim/ragdoll.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <sstream>

namespace ragdoll_sim {

int RagdollDef::findLink(const std::string& link_name) const {
  for (size_t i = 0; i < links.size(); ++i)
    if (links[i].name == link_name) return int(i);
  return -1;
}

double RagdollDef::totalMass() const {
  double m = 0.0;
  for (const LinkDef& l : links) m += l.mass;
  return m;
}

const char* jointKindName(RagdollJointKind kind) {
  switch (kind) {
    case RagdollJointKind::Ball: return "ball";
    case RagdollJointKind::Hinge: return "hinge";
    case RagdollJointKind::Prismatic: return "prismatic";
    case RagdollJointKind::Fixed: return "fixed";
  }
  return "?";
}

int jointAxisCount(RagdollJointKind kind) {
  switch (kind) {
    case RagdollJointKind::Ball: return 3;
    case RagdollJointKind::Fixed: return 0;
    default: return 1;
  }
}

JointMotor passiveMotor(const RagdollJointDef& j, int axis) {
  JointMotor m;
  const size_t a = static_cast<size_t>(axis);
  const double friction = axis >= 0 && a < j.friction.size() ? j.friction[a] : 0.0;
  m.damping = axis >= 0 && a < j.damping.size() ? std::max(j.damping[a], 0.0) : 0.0;
  if (friction > 0.0) {
    m.enabled = true;
    m.hertz = 0.0;
    m.target_velocity = 0.0;
    m.max_torque = friction;
  }
  return m;
}

namespace {

// A joint def of type D between bodies a and b at the joint's frames.
template <class D>
D connected(BodyId a, BodyId b, const RagdollJointDef& j) {
  D d;
  d.body_a = a;
  d.body_b = b;
  d.frame_a = j.frame_parent;
  d.frame_b = j.frame_child;
  return d;
}

// Hinge / prismatic: the axis, its limit and the passive motor of axis 0.
template <class D>
void singleAxis(const RagdollJointDef& j, const Vec3& default_axis, D* d) {
  d->axis = j.axes.empty() ? default_axis : j.axes[0];
  d->enable_limit = j.limited && !j.lower.empty() && !j.upper.empty();
  if (d->enable_limit) {
    d->lower = j.lower[0];
    d->upper = j.upper[0];
  }
  d->motor = passiveMotor(j, 0);
}

}  // namespace

std::string swingTwistLimitsError(const SwingTwistLimits& l,
                                  const std::array<const char*, 4>& names) {
  const double v[4] = {l.cone_1, l.cone_2, l.twist_lower, l.twist_upper};
  std::ostringstream os;
  for (int k = 0; k < 2; ++k)
    if (!(v[k] > 0.0 && v[k] <= M_PI)) {
      os << names[k] << " must be an angle in (0, pi] rad, got " << v[k];
      return os.str();
    }
  for (int k = 2; k < 4; ++k)
    if (!(v[k] >= -M_PI && v[k] <= M_PI)) {
      os << names[k] << " must be an angle in [-pi, pi] rad, got " << v[k];
      return os.str();
    }
  if (l.twist_lower > l.twist_upper) {
    os << names[2] << " must be <= " << names[3] << ", got " << l.twist_lower << " > "
       << l.twist_upper;
    return os.str();
  }
  return "";
}

Ragdoll spawnRagdoll(World& world, const RagdollDef& def, const Transform& root_pose,
                     const Material* material) {
  Ragdoll r;
  const Transform root_rest_inv = def.links.at(def.root).rest_pose.inverse();
  for (size_t i = 0; i < def.links.size(); ++i) {
    const LinkDef& l = def.links[i];
    BodyDef bd;
    // A fixed base is a static root: the joints to it hold the rest as to any static body.
    if (def.fixed_base && int(i) == def.root) bd.type = BodyType::Static;
    bd.name = l.name;
    bd.pose = root_pose * root_rest_inv * l.rest_pose;
    bd.mass = l.mass;
    bd.com = l.com;
    bd.inertia = l.inertia;
    bd.linear_damping = l.linear_damping;
    bd.angular_damping = l.angular_damping;
    const BodyId id = world.createBody(bd);
    for (size_t k = 0; k < l.shapes.size(); ++k) {
      ShapeDef s = l.shapes[k];
      if (material) s.material = *material;
      // The URDF's own friction for this link wins over a blanket material (no table entry).
      if (k < l.shape_friction.size() && l.shape_friction[k] >= 0.0) {
        s.material.static_friction = s.material.kinetic_friction = l.shape_friction[k];
        s.material.id = 0;
      }
      world.addShape(id, s);
    }
    r.bodies.push_back(id);
  }
  for (const RagdollJointDef& j : def.joints) {
    const BodyId a = r.bodies.at(j.parent), b = r.bodies.at(j.child);
    if (j.kind == RagdollJointKind::Ball) {
      BallJointDef bj = connected<BallJointDef>(a, b, j);
      for (int k = 0; k < 3 && k < int(j.axes.size()); ++k) bj.axes[k] = j.axes[k];
      bj.enable_limits = j.limited && j.lower.size() >= 3 && j.upper.size() >= 3;
      for (int k = 0; bj.enable_limits && k < 3; ++k) {
        bj.lower[k] = j.lower[k];
        bj.upper[k] = j.upper[k];
      }
      if (j.swing_twist) {
        bj.enable_limits = true;
        bj.limit_mode = BallLimitMode::SwingTwist;
        bj.swing_cone_angle = j.swing_twist->cone_1;
        bj.swing_cone_angle_2 = j.swing_twist->cone_2;
        bj.twist_lower = j.swing_twist->twist_lower;
        bj.twist_upper = j.swing_twist->twist_upper;
      }
      for (int k = 0; k < 3; ++k) bj.motors[k] = passiveMotor(j, k);
      bj.spring = j.spring;
      r.joints.push_back(world.createBallJoint(bj));
    } else if (j.kind == RagdollJointKind::Prismatic) {
      PrismaticJointDef pj = connected<PrismaticJointDef>(a, b, j);
      singleAxis(j, Vec3::UnitX(), &pj);
      pj.spring.break_force = j.spring.break_force;  // a prismatic anchor has no spring
      r.joints.push_back(world.createPrismaticJoint(pj));  // motor: N s/m damping, N friction
    } else if (j.kind == RagdollJointKind::Fixed) {
      FixedJointDef fj = connected<FixedJointDef>(a, b, j);
      fj.spring = j.spring;
      r.joints.push_back(world.createFixedJoint(fj));
    } else {
      HingeJointDef hj = connected<HingeJointDef>(a, b, j);
      singleAxis(j, Vec3::UnitZ(), &hj);
      hj.spring = j.spring;
      r.joints.push_back(world.createHingeJoint(hj));
    }
  }
  for (const auto& [a, b] : def.no_collide) world.disableCollision(r.bodies.at(a), r.bodies.at(b));
  return r;
}

std::vector<Transform> ballChainLinkPoses(const World& world, const Ragdoll& ragdoll,
                                          const RagdollDef& def, int joint_index) {
  const RagdollJointDef& j = def.joints.at(joint_index);
  std::vector<Transform> poses;
  if (j.kind != RagdollJointKind::Ball) return poses;
  const std::array<double, 3> t = world.ballAngles(ragdoll.joints.at(joint_index));
  Transform frame = world.bodyPose(ragdoll.bodies.at(j.parent)) * j.frame_parent;
  for (size_t k = 0; k < j.chain_links.size() && k < j.chain_offsets.size() && k < 3; ++k) {
    frame = frame * Transform(Vec3::Zero(), Quat(Eigen::AngleAxisd(t[k], j.axes[k])));
    poses.push_back(frame * j.chain_offsets[k]);
  }
  return poses;
}

}  // namespace ragdoll_sim
