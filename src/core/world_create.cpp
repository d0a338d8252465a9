// The create API (bodies, shapes, joints, collision filter) and joint breaking.
#include <algorithm>
#include <utility>

#include "ragdoll_sim/range_check.hpp"

#include "world_impl.hpp"

namespace ragdoll_sim {

BodyId World::createBody(const BodyDef& def) {
  Impl& w = *impl_;
  Body body;
  body.def = def;
  if (!def.pose.p.allFinite() || !def.pose.q.coeffs().allFinite() ||
      !def.linear_velocity.allFinite() || !def.angular_velocity.allFinite())
    throw std::invalid_argument("ragdoll_sim: body '" + def.name +
                                "' needs a finite pose and velocity");
  BodyMotion m;
  m.local_com = def.com;
  m.q = def.pose.q.normalized();
  m.x = snapPosition(def.pose.p + m.q * def.com);
  if (!m.x.allFinite() || !def.com.allFinite())
    throw std::invalid_argument("ragdoll_sim: body '" + def.name +
                                "' has a non-finite centre of mass position");
  const std::string e = firstError({nonNegativeError("linear_damping", def.linear_damping),
                                    nonNegativeError("angular_damping", def.angular_damping),
                                    finiteError("gravity_scale", def.gravity_scale)});
  if (!e.empty()) throw std::invalid_argument("ragdoll_sim: body '" + def.name + "': " + e);
  m.inertia_local = def.inertia;
  m.linear_damping = def.linear_damping;
  m.angular_damping = def.angular_damping;
  m.gravity_scale = def.gravity_scale;
  if (def.type == BodyType::Dynamic) {
    if (!(def.mass > 0.0) || !def.inertia.allFinite() || def.inertia.determinant() <= 0.0)
      throw std::invalid_argument("ragdoll_sim: body '" + def.name +
                                  "' needs a positive mass and a positive definite inertia");
    m.inv_mass = 1.0 / def.mass;
    m.inv_inertia_local = def.inertia.inverse();
    m.v = def.linear_velocity;
    m.w = def.angular_velocity;
    m.awake = true;
  }
  w.bodies.push_back(std::move(body));
  w.motions.push_back(m);
  w.solver.emplace_back();
  w.rotations.emplace_back(Mat3::Identity());
  w.last_finite.push_back({m.x, m.q});
  w.solver_reset.push_back(0);
  w.solver_fault.push_back(0);
  return BodyId{int32_t(w.bodies.size() - 1)};
}

void World::addShape(BodyId id, const ShapeDef& def) {
  impl_->checkBody(id);
  std::string e = firstError({geometryError(def.geometry), poseError("local", def.local)});
  if (e.empty() && !(e = materialError(def.material)).empty()) e = "material " + e;
  if (!e.empty())
    throw std::invalid_argument("ragdoll_sim: a shape of body '" +
                                impl_->bodies[id.index].def.name + "': " + e);
  Body& b = impl_->bodies[id.index];
  b.shapes.push_back(def);
  b.shape_ids.push_back(int(impl_->shapes.size()));
  impl_->shapes.push_back({id.index, int(b.shapes.size() - 1)});
  impl_->settled = false;
  // farthest shape point from the COM, for the sleep speed
  BodyMotion& m = impl_->motions[id.index];
  m.extent = std::max(m.extent, maxExtent(def.geometry, def.local, m.local_com));
}

JointId World::createBallJoint(const BallJointDef& def) { return impl_->addJoint("ball", def); }

JointId World::createHingeJoint(const HingeJointDef& def) {
  return impl_->addJoint("hinge", def);
}

JointId World::createFixedJoint(const FixedJointDef& def) {
  return impl_->addJoint("fixed", def);
}

JointId World::createPrismaticJoint(const PrismaticJointDef& def) {
  return impl_->addJoint("prismatic", def);
}

void World::disableCollision(BodyId a, BodyId b) {
  impl_->checkBody(a);
  impl_->checkBody(b);
  impl_->setCollides(a.index, b.index, false);
  impl_->settled = false;
}

// A joint whose anchor force reached its limit breaks (a rigid anchor never transmits more
// than break_force: its impulse is capped at break_force h). solveIsland marks it broken at
// the end of the substep, which drops it from the solver; here, after the islands, the pair
// collides again and the event is recorded. The bodies keep their momentum.
void World::Impl::breakJoints() {
  bool any = false;
  for (Joint* j : active_joints) {
    if (!j->broken) continue;
    any = true;
    setCollides(j->a, j->b, true);
    broken_events.push_back(JointId{int32_t(j - joints.data())});
  }
  if (any)
    active_joints.erase(std::remove_if(active_joints.begin(), active_joints.end(),
                                       [](const Joint* j) { return j->broken; }),
                        active_joints.end());
}

void World::breakJoint(JointId id) {
  Joint& j = impl_->joints.at(id.index);
  if (j.broken) return;
  j.broken = true;
  impl_->setCollides(j.a, j.b, true);
  impl_->wake(j.a);
  impl_->wake(j.b);
}

}  // namespace ragdoll_sim
