// World::jointWrench and World::jointAxisEfforts (world_reports.hpp), read on request from the
// impulses the joint's parts accumulated over the last substep (JointBase::impulse_h): nothing
// is kept per step for them.
//   - Every part's impulse acts on B along its row, minus on A (part_rows.hpp): angular rows
//     (hinge axis, angle motors and limits, swing-twist limits, rotation locks) as a couple,
//     linear rows (anchor, prismatic line, motor and limit) at B's anchor, so the torque about
//     B's anchor is the angular rows' alone.
//   - Viscous motor damping's impulse is kept for its substep's sweeps only: its torque is
//     -c theta_dot at the bodies' current velocities (what the implicit step leaves, to first
//     order). A spring anchor's force is likewise -k x - c v at the current poses.
//   - Ball joints: the effort of Euler axis i is the torque on B projected on the world axis of
//     revolute joint i of the chain R(a0,t0) R(a1,t1) R(a2,t2) at the current angles; its links
//     are massless and share the origin, so every joint of it carries B's torque, and the
//     Euler rows are the dual basis of these axes (row_i . axis_k = delta_ik).
#include "ragdoll_sim/world.hpp"

#include <cmath>

#include "world_impl.hpp"

namespace ragdoll_sim {

namespace {

Vec3 pointVelocity(const BodyMotion& m, const Vec3& p) { return m.v + m.w.cross(p - m.x); }

struct JointPoses {
  const BodyMotion& A;
  const BodyMotion& B;
  double inv_h;  // 0 before the first substep: everything reads zero
};

// Motor (with its damping) and limit efforts of the angle rows on B, one per row.
template <int N>
void angleEfforts(const AngleAxes<N>& ax, const JointPoses& p, double e[N]) {
  for (int i = 0; i < N; ++i) e[i] = 0.0;
  const Vec3 dw = p.B.w - p.A.w;
  for (int i = 0; i < ax.count; ++i) {  // the warm start applies rows below count only
    double lambda = ax.motor_parts[i].impulse;
    if (ax.limits_enabled) lambda += ax.limits[i].lower_impulse - ax.limits[i].upper_impulse;
    e[i] = lambda * p.inv_h - ax.motors[i].damping * ax.rows[i].dot(dw);
  }
}

template <int N>
Vec3 angleTorque(const AngleAxes<N>& ax, const double e[N]) {
  Vec3 t = Vec3::Zero();
  for (int i = 0; i < ax.count; ++i) t += e[i] * ax.rows[i];
  return t;
}

Vec3 anchorForce(const JointBase& j, const AnchorPart& anchor, const JointPoses& p) {
  if (!(j.spring.stiffness > 0.0)) return anchor.point.impulse * p.inv_h;
  if (p.inv_h == 0.0) return Vec3::Zero();
  const Vec3 pa = p.A.linkPose().apply(j.frame_a.p), pb = p.B.linkPose().apply(j.frame_b.p);
  return -j.spring.stiffness * (pb - pa) -
         j.spring.damping * (pointVelocity(p.B, pb) - pointVelocity(p.A, pa));
}

Vec3 swingTwistTorque(const BallJoint& b, const JointPoses& p) {
  if (!b.swing_twist_limits) return Vec3::Zero();
  const SwingTwistPart& st = b.swing_twist;
  Vec3 t = Vec3::Zero();
  if (st.angles.swing_valid) t += st.cone_impulse * st.cone_row;
  if (st.angles.twist_valid)
    t += (st.twist.lower_impulse - st.twist.upper_impulse) * st.angles.twist_row;
  return t * p.inv_h;
}

// World axes of the ball's chain of revolute joints at the current angles (joint_angles.hpp:
// R' = Rx(t0) Ry(t1) Rz(s t2) in the basis Q = frame A * P).
void ballChainAxes(const JointBase& j, const BallJoint& b, const JointPoses& p, Vec3 axes[3]) {
  const Quat fa = j.frameRotationA(p.A.q), fb = j.frameRotationB(p.B.q);
  const Vec3 t = b.euler.angles(fa, fb);
  const Mat3 Q = (fa * b.euler.qP).toRotationMatrix();
  const double c0 = std::cos(t[0]), s0 = std::sin(t[0]), c1 = std::cos(t[1]), s1 = std::sin(t[1]);
  axes[0] = Q.col(0);
  axes[1] = c0 * Q.col(1) + s0 * Q.col(2);
  axes[2] = b.euler.s * (s1 * Q.col(0) - s0 * c1 * Q.col(1) + c0 * c1 * Q.col(2));
}

struct PrismaticReading {
  Vec3 axis, force;  // world
  double effort;     // N along +axis on B
};

PrismaticReading prismaticReading(const JointBase& j, const PrismaticJoint& pj,
                                  const JointPoses& p) {
  PrismaticReading r;
  r.axis = p.A.q * (j.frame_a.q * pj.axis);
  const Vec3 n1 = p.A.q * pj.off_axis_in_a, n2 = r.axis.cross(n1);
  const Vec3 pb = p.B.linkPose().apply(j.frame_b.p);
  double lambda = pj.linear_motor.impulse;
  if (pj.limit_enabled) lambda += pj.linear_limit.lower_impulse - pj.linear_limit.upper_impulse;
  const double rate = r.axis.dot(pointVelocity(p.B, pb) - pointVelocity(p.A, pb));
  r.effort = lambda * p.inv_h - pj.motor.damping * rate;
  r.force = (pj.line.impulse.x() * n1 + pj.line.impulse.y() * n2) * p.inv_h + r.effort * r.axis;
  return r;
}

}  // namespace

JointWrench World::jointWrench(JointId id) const {
  const Joint& j = impl_->joint(id);
  JointWrench w;
  if (j.broken || !(j.impulse_h > 0.0)) return w;
  const JointPoses p{impl_->motions[j.a], impl_->motions[j.b], 1.0 / j.impulse_h};
  if (const HingeJoint* h = j.as<HingeJoint>()) {
    double e[1];
    angleEfforts(h->axes, p, e);
    w.force = anchorForce(j, h->anchor, p);
    const HingeAxisPart& ha = h->hinge_axis;
    w.torque = (ha.impulse.x() * ha.u1 + ha.impulse.y() * ha.u2) * p.inv_h + angleTorque(h->axes, e);
  } else if (const BallJoint* b = j.as<BallJoint>()) {
    double e[3];
    angleEfforts(b->axes, p, e);
    w.force = anchorForce(j, b->anchor, p);
    w.torque = angleTorque(b->axes, e) + swingTwistTorque(*b, p);
  } else if (const FixedJoint* f = j.as<FixedJoint>()) {
    w.force = anchorForce(j, f->anchor, p);
    w.torque = f->angle_lock.impulse * p.inv_h;
  } else if (const PrismaticJoint* s = j.as<PrismaticJoint>()) {
    w.force = prismaticReading(j, *s, p).force;
    w.torque = s->angle_lock.impulse * p.inv_h;
  }
  return w;
}

int World::jointAxisEfforts(JointId id, double out[3]) const {
  const Joint& j = impl_->joint(id);
  out[0] = out[1] = out[2] = 0.0;
  const int n = j.type() == JointType::Ball ? 3 : j.type() == JointType::Fixed ? 0 : 1;
  if (j.broken || !(j.impulse_h > 0.0)) return n;
  const JointPoses p{impl_->motions[j.a], impl_->motions[j.b], 1.0 / j.impulse_h};
  if (const HingeJoint* h = j.as<HingeJoint>()) {
    angleEfforts(h->axes, p, out);
  } else if (const BallJoint* b = j.as<BallJoint>()) {
    double e[3];
    angleEfforts(b->axes, p, e);
    const Vec3 torque = angleTorque(b->axes, e) + swingTwistTorque(*b, p);
    Vec3 axes[3];
    ballChainAxes(j, *b, p, axes);
    for (int i = 0; i < 3; ++i) out[i] = torque.dot(axes[i]);
  } else if (const PrismaticJoint* s = j.as<PrismaticJoint>()) {
    out[0] = prismaticReading(j, *s, p).effort;
  }
  return n;
}

}  // namespace ragdoll_sim
