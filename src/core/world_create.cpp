// The create and destroy API (bodies, shapes, joints, collision filter) and joint breaking.
// Destroyed bodies and joints keep their slots, so every other id keeps its index.
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
  if (const std::string e = worldPointError("centre of mass", m.x); !e.empty())
    throw std::invalid_argument("ragdoll_sim: body '" + def.name + "': " + e);
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
  w.guard_clean.push_back(0);
  w.solver_reset.push_back(0);
  w.solver_fault.push_back(0);
  w.static_touched.push_back(0);
  const int index = int(w.bodies.size() - 1);
  if (def.type == BodyType::Dynamic) w.dynamic_bodies.push_back(index);
  else w.touchStatic(index);
  w.schedule_fresh = false;  // the per-body vectors may have grown
  return BodyId{int32_t(index)};
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
  impl_->shapesChanged(id.index);
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
  if (!joint_broke.exchange(false, std::memory_order_relaxed)) return;
  bool any = false;
  for (Joint* j : active_joints) {
    if (!j->broken) continue;
    any = true;
    setCollides(j->a, j->b, true);
    broken_events.push_back(JointId{int32_t(j - joints.data())});
  }
  if (!any) return;
  schedule_fresh = false;
  active_joints.erase(std::remove_if(active_joints.begin(), active_joints.end(),
                                     [](const Joint* j) { return j->broken; }),
                      active_joints.end());
}

void World::breakJoint(JointId id) {
  Joint& j = impl_->joint(id);
  if (j.broken) return;
  j.broken = true;
  impl_->schedule_fresh = false;
  impl_->setCollides(j.a, j.b, true);
  impl_->wake(j.a);
  impl_->wake(j.b);
}


template <class Pred>
void World::Impl::removeContacts(Pred&& drop) {
  size_t kept = 0;
  for (size_t k = 0; k < contacts.size(); ++k) {
    const Contact& c = contacts[k];
    if (drop(c)) {
      if (c.manifold.count > 0) {
        wake(c.body_a);
        wake(c.body_b);
      }
      continue;
    }
    if (kept != k) {
      contacts[kept] = contacts[k];
      contact_keys[kept] = contact_keys[k];
      manifold_caches[kept] = manifold_caches[k];
    }
    ++kept;
  }
  contacts.resize(kept);
  contact_keys.resize(kept);
  manifold_caches.resize(kept);
  pairs_dirty = true;  // no pair of a removed shape may be carried over
  settled = false;
  schedule_fresh = false;  // the contacts' indices moved
}

// As breakJoint, the pair collides again (unless the joint broke already, which did that).
void World::Impl::removeJoint(int k) {
  Joint& j = joints[k];
  if (!j.broken) setCollides(j.a, j.b, true);
  j.broken = true;  // left out of islands and solving like a broken joint
  joint_alive[k] = 0;
  schedule_fresh = false;
  wake(j.a);
  wake(j.b);
}

void World::destroyJoint(JointId id) {
  impl_->joint(id);  // throws for a bad id
  impl_->removeJoint(id.index);
}

void World::destroyBody(BodyId id) {
  Impl& w = *impl_;
  w.checkBody(id);
  const int b = id.index;
  for (size_t k = 0; k < w.joints.size(); ++k)
    if (w.joint_alive[k] && (w.joints[k].a == b || w.joints[k].b == b)) w.removeJoint(int(k));
  w.removeContacts([b](const Contact& c) { return c.body_a == b || c.body_b == b; });
  Body& body = w.bodies[b];
  if (!body.shape_ids.empty()) w.shapesChanged(b);
  for (const int s : body.shape_ids) w.shapes[s].alive = false;
  body.shapes.clear();
  body.shape_ids.clear();
  body.no_collide.clear();
  for (int i = 0; i < b; ++i) {  // pairs with a lower body are listed under that one
    std::vector<int>& v = w.bodies[i].no_collide;
    v.erase(std::remove(v.begin(), v.end(), b), v.end());
  }
  body.alive = false;
  w.untrack(b);
  w.dynamic_bodies.erase(std::remove(w.dynamic_bodies.begin(), w.dynamic_bodies.end(), b),
                         w.dynamic_bodies.end());
  BodyMotion& m = w.motions[b];
  m.awake = false;
  m.v.setZero();
  m.w.setZero();
  m.force.setZero();
  m.torque.setZero();
  w.pairs_dirty = true;
  w.settled = false;
  w.schedule_fresh = false;
}

void World::removeShape(BodyId id, int index) {
  Impl& w = *impl_;
  w.checkBody(id);
  Body& body = w.bodies[id.index];
  if (index < 0 || index >= int(body.shapes.size()))
    throw std::out_of_range("ragdoll_sim: removeShape: body '" + body.def.name + "' has no shape " +
                            std::to_string(index));
  const int s = body.shape_ids[index];
  w.removeContacts([s](const Contact& c) { return c.shape_a == s || c.shape_b == s; });
  w.shapes[s].alive = false;
  w.shapesChanged(id.index);
  body.shapes.erase(body.shapes.begin() + index);
  body.shape_ids.erase(body.shape_ids.begin() + index);
  for (int k = index; k < int(body.shape_ids.size()); ++k) w.shapes[body.shape_ids[k]].index = k;
  BodyMotion& m = w.motions[id.index];
  m.extent = 0.0;
  for (const ShapeDef& d : body.shapes)
    m.extent = std::max(m.extent, maxExtent(d.geometry, d.local, m.local_com));
  w.wake(id.index);
}

void World::setShapeMaterial(BodyId id, int index, const Material& material) {
  Impl& w = *impl_;
  w.checkBody(id);
  Body& body = w.bodies[id.index];
  if (index < 0 || index >= int(body.shapes.size()))
    throw std::out_of_range("ragdoll_sim: setShapeMaterial: body '" + body.def.name +
                            "' has no shape " + std::to_string(index));
  const std::string e = materialError(material);
  if (!e.empty())
    throw std::invalid_argument("ragdoll_sim: a shape of body '" + body.def.name + "': material " + e);
  body.shapes[index].material = material;
  const int s = body.shape_ids[index];
  for (Contact& c : w.contacts)
    if (c.shape_a == s || c.shape_b == s) w.applyPairMaterial(c, w.shapeDef(c.shape_a), w.shapeDef(c.shape_b));
}

}  // namespace ragdoll_sim
