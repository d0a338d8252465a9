// Commands (impulses, forces, states, motors) and queries of the World.
#include <algorithm>

#include "world_impl.hpp"

namespace ragdoll_sim {

void World::applyLinearImpulse(BodyId id, const Vec3& impulse, const Vec3& world_point) {
  impl_->checkBody(id);
  impl_->wake(id.index);
  BodyMotion& m = impl_->motions[id.index];
  if (m.inv_mass == 0.0) return;
  const Mat3 R = m.q.toRotationMatrix();
  m.v += m.inv_mass * impulse;
  m.w += R * m.inv_inertia_local * R.transpose() * (world_point - m.x).cross(impulse);
}

void World::applyLinearImpulseToCenter(BodyId id, const Vec3& impulse) {
  impl_->checkBody(id);
  impl_->wake(id.index);
  BodyMotion& m = impl_->motions[id.index];
  m.v += m.inv_mass * impulse;
}

void World::applyAngularImpulse(BodyId id, const Vec3& impulse) {
  impl_->checkBody(id);
  impl_->wake(id.index);
  BodyMotion& m = impl_->motions[id.index];
  if (m.inv_mass == 0.0) return;
  const Mat3 R = m.q.toRotationMatrix();
  m.w += R * m.inv_inertia_local * R.transpose() * impulse;
}

void World::applyForce(BodyId id, const Vec3& force, const Vec3& world_point) {
  impl_->checkBody(id);
  impl_->wake(id.index);
  BodyMotion& m = impl_->motions[id.index];
  m.force += force;
  m.torque += (world_point - m.x).cross(force);
}

void World::applyTorque(BodyId id, const Vec3& torque) {
  impl_->checkBody(id);
  impl_->wake(id.index);
  impl_->motions[id.index].torque += torque;
}

void World::setBodyState(BodyId id, const Transform& pose, const Vec3& v, const Vec3& w) {
  impl_->checkBody(id);
  impl_->wake(id.index);
  impl_->forgetBoxes(id.index);
  BodyMotion& m = impl_->motions[id.index];
  m.q = pose.q.normalized();
  m.x = snapPosition(pose.p + m.q * m.local_com);
  m.x_carry.setZero();
  const bool dyn = impl_->isDynamic(id.index);
  m.v = dyn ? v : Vec3::Zero();
  m.w = dyn ? w : Vec3::Zero();
  m.force.setZero();
  m.torque.setZero();
}

int World::bodyCount() const { return int(impl_->bodies.size()); }
int World::jointCount() const { return int(impl_->joints.size()); }
bool World::isAwake(BodyId id) const {
  impl_->checkBody(id);
  return impl_->motions[id.index].awake;
}

void World::wake(BodyId id) {
  impl_->checkBody(id);
  impl_->wake(id.index);
}

int World::awakeBodyCount() const {
  int n = 0;
  for (const BodyMotion& m : impl_->motions) n += m.awake ? 1 : 0;
  return n;
}

IslandCounters World::islandCounters() const {
  IslandCounters c;
  for (const IslandRange& r : impl_->island_ranges) {
    ++c.islands;
    c.split_islands += r.split ? 1 : 0;
    c.largest_island = std::max(c.largest_island, r.body_end - r.body_begin);
    c.bodies += r.body_end - r.body_begin;
    c.joints += r.joint_end - r.joint_begin;
    c.contacts += r.contact_end - r.contact_begin;
    c.resting_islands += r.resting ? 1 : 0;
    c.resting_bodies += r.resting ? r.body_end - r.body_begin : 0;
  }
  for (const SolveData::LaneCount& n : impl_->lane_counts) {
    c.lane_batches += n.batches;
    c.contact_lane_rows += n.contact_rows;
    c.contact_lanes += n.contact_lanes;
    c.joint_lane_rows += n.joint_rows;
    c.joint_lanes += n.joint_lanes;
  }
  return c;
}

bool World::isValid(BodyId id) const { return impl_->validBody(id); }
bool World::isValid(JointId id) const { return impl_->validJoint(id); }

BodyState World::bodyState(BodyId id) const {
  impl_->checkBody(id);
  const BodyMotion& m = impl_->motions[id.index];
  return {m.linkPose(), m.x, m.v, m.w};
}

Transform World::bodyPose(BodyId id) const {
  impl_->checkBody(id);
  return impl_->motions[id.index].linkPose();
}

const BodyDef& World::bodyDef(BodyId id) const {
  impl_->checkBody(id);
  return impl_->bodies[id.index].def;
}

const std::vector<ShapeDef>& World::bodyShapes(BodyId id) const {
  impl_->checkBody(id);
  return impl_->bodies[id.index].shapes;
}

Vec3 World::comPosition(BodyId id) const {
  impl_->checkBody(id);
  return impl_->motions[id.index].x;
}

Vec3 World::pointVelocity(BodyId id, const Vec3& p) const {
  impl_->checkBody(id);
  const BodyMotion& m = impl_->motions[id.index];
  return m.v + m.w.cross(p - m.x);
}

JointType World::jointType(JointId id) const { return impl_->joint(id).type(); }

double World::hingeAngle(JointId id) const {
  const Joint& j = impl_->joint(id);
  const HingeJoint* h = j.as<HingeJoint>();
  return h ? h->angle(j, impl_->motions) : 0.0;
}

std::array<double, 3> World::ballAngles(JointId id) const {
  const Joint& j = impl_->joint(id);
  const BallJoint* b = j.as<BallJoint>();
  return b ? b->eulerAngles(j, impl_->motions) : std::array<double, 3>{0, 0, 0};
}

std::array<double, 2> World::ballSwingTwist(JointId id) const {
  const Joint& j = impl_->joint(id);
  const BallJoint* b = j.as<BallJoint>();
  return b ? b->swingTwistAngles(j, impl_->motions) : std::array<double, 2>{0, 0};
}

double World::prismaticPosition(JointId id) const {
  const Joint& j = impl_->joint(id);
  const PrismaticJoint* p = j.as<PrismaticJoint>();
  return p ? p->position(j, impl_->motions) : 0.0;
}

Vec3 World::jointAnchorError(JointId id) const {
  const Joint& j = impl_->joint(id);
  const auto& m = impl_->motions;
  const Vec3 e = m[j.b].linkPose().apply(j.frame_b.p) - m[j.a].linkPose().apply(j.frame_a.p);
  const PrismaticJoint* p = j.as<PrismaticJoint>();
  return p ? p->offAxis(j, m, e) : e;
}

double World::jointForce(JointId id) const { return impl_->joint(id).force; }
double World::jointTorque(JointId id) const { return impl_->joint(id).torque; }
bool World::isJointBroken(JointId id) const { return impl_->joint(id).broken; }

std::vector<JointId> World::takeBrokenJoints() {
  std::vector<JointId> out;
  out.swap(impl_->broken_events);
  return out;
}

void World::setJointMotor(JointId id, int axis, const JointMotor& motor) {
  Joint& j = impl_->joint(id);
  const std::string e = jointMotorError(motor);
  if (!e.empty())
    throw std::invalid_argument("ragdoll_sim: setJointMotor, axis " + std::to_string(axis) +
                                " of the joint between '" + impl_->bodies[j.a].def.name +
                                "' and '" + impl_->bodies[j.b].def.name + "': motor." + e);
  j.motorAt(axis) = motor;
  if (!motor.enabled) j.clearMotorImpulse(axis);
  impl_->wake(j.a);
  impl_->wake(j.b);
}

Vec3 World::linearMomentum() const {
  Vec3 p = Vec3::Zero();
  for (size_t i = 0; i < impl_->bodies.size(); ++i)
    if (impl_->isDynamic(int(i))) p += impl_->motions[i].v / impl_->motions[i].inv_mass;
  return p;
}

Vec3 World::angularMomentum(const Vec3& about) const {
  Vec3 L = Vec3::Zero();
  for (size_t i = 0; i < impl_->bodies.size(); ++i) {
    if (!impl_->isDynamic(int(i))) continue;
    const BodyMotion& m = impl_->motions[i];
    const Mat3 R = m.q.toRotationMatrix();
    L += (m.x - about).cross(m.v / m.inv_mass) + R * m.inertia_local * R.transpose() * m.w;
  }
  return L;
}

double World::kineticEnergy() const {
  double e = 0.0;
  for (size_t i = 0; i < impl_->bodies.size(); ++i) {
    if (!impl_->isDynamic(int(i))) continue;
    const BodyMotion& m = impl_->motions[i];
    const Vec3 wb = m.q.conjugate() * m.w;
    e += 0.5 * m.v.squaredNorm() / m.inv_mass + 0.5 * wb.dot(m.inertia_local * wb);
  }
  return e;
}

std::vector<ContactInfo> World::contacts() const {
  std::vector<ContactInfo> out;
  for (const Contact& c : impl_->contacts)
    for (int i = 0; i < c.manifold.count; ++i)
      out.push_back({BodyId{c.body_a}, BodyId{c.body_b}, c.origin + c.manifold.points[i].point,
                     c.manifold.normal, c.manifold.points[i].separation, c.normal_impulse[i]});
  return out;
}

}  // namespace ragdoll_sim
