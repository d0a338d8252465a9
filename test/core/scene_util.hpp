// Small scene builders shared by the core tests.
#pragma once

#include <vector>

#include "ragdoll_sim/world.hpp"

namespace ragdoll_sim {
namespace test {

inline Mat3 boxInertia(const Vec3& half, double mass) {
  const Vec3 s = 2.0 * half;
  return (mass / 12.0 * Vec3(s.y() * s.y() + s.z() * s.z(), s.x() * s.x() + s.z() * s.z(),
                             s.x() * s.x() + s.y() * s.y()))
      .asDiagonal();
}

// Static plane through the origin with normal q * z (a slope when q tilts it).
inline BodyId addGround(World& w, const Material& m = Material(), const Quat& q = Quat::Identity()) {
  BodyDef d;
  d.type = BodyType::Static;
  d.pose.q = q;
  const BodyId g = w.createBody(d);
  w.addShape(g, {Geometry::plane(Vec3::UnitZ(), 0.0), Transform(), m});
  return g;
}

// Shapeless bodies (joint tests): a static frame, and a dynamic body with its COM at `com`.
inline BodyId addStatic(World& w, const Transform& pose = Transform()) {
  BodyDef d;
  d.type = BodyType::Static;
  d.pose = pose;
  return w.createBody(d);
}

inline BodyId addDynamic(World& w, double mass, const Mat3& inertia, const Transform& pose,
                         const Vec3& com = Vec3::Zero(), const Vec3& v = Vec3::Zero(),
                         const Vec3& omega = Vec3::Zero()) {
  BodyDef d;
  d.mass = mass;
  d.inertia = inertia;
  d.pose = pose;
  d.com = com;
  d.linear_velocity = v;
  d.angular_velocity = omega;
  return w.createBody(d);
}

inline BodyId addBody(World& w, const Geometry& g, double mass, const Mat3& inertia,
                      const Transform& pose, const Material& m = Material(),
                      const Vec3& v = Vec3::Zero()) {
  const BodyId b = addDynamic(w, mass, inertia, pose, Vec3::Zero(), v);
  w.addShape(b, {g, Transform(), m});
  return b;
}

inline BodyId addBox(World& w, const Vec3& half, double mass, const Vec3& pos,
                     const Material& m = Material()) {
  return addBody(w, Geometry::box(half), mass, boxInertia(half, mass), Transform(pos, Quat::Identity()), m);
}

inline BodyId addSphere(World& w, double r, double mass, const Vec3& pos, const Material& m = Material()) {
  return addBody(w, Geometry::sphere(r), mass, Mat3::Identity() * 0.4 * mass * r * r,
                 Transform(pos, Quat::Identity()), m);
}

// Ball joint from the +x face of a (centre + half_x) to the -x face of b: links of a chain
// along x.
inline JointId chainLink(World& w, BodyId a, BodyId b, double half_x) {
  BallJointDef j;
  j.body_a = a;
  j.body_b = b;
  j.frame_a = Transform(Vec3(half_x, 0, 0), Quat::Identity());
  j.frame_b = Transform(Vec3(-half_x, 0, 0), Quat::Identity());
  return w.createBallJoint(j);
}

// A chain of `masses.size()` shapeless bodies hung from a static anchor at `top` by ball
// joints, links 0.3 m long along `dir` from the anchor, every joint closed (+x: horizontal, it
// swings under gravity; -z: it hangs at rest). The joints go to *joints, top first.
inline std::vector<BodyId> addChain(World& w, const Vec3& top, const std::vector<double>& masses,
                                    const Vec3& dir = Vec3::UnitX(),
                                    std::vector<JointId>* joints = nullptr) {
  const BodyId anchor = addStatic(w, Transform(top, Quat::Identity()));
  std::vector<BodyId> chain;
  BodyId parent = anchor;
  for (size_t i = 0; i < masses.size(); ++i) {
    const double m = masses[i];
    const Vec3 pos = top + (0.15 + 0.3 * double(i)) * dir;
    const BodyId b = addDynamic(w, m, Mat3::Identity() * 0.01 * m, Transform(pos, Quat::Identity()));
    BallJointDef j;
    j.body_a = parent;
    j.body_b = b;
    j.frame_a.p = parent == anchor ? Vec3::Zero() : Vec3(0.15 * dir);
    j.frame_b.p = -0.15 * dir;
    const JointId id = w.createBallJoint(j);
    if (joints) joints->push_back(id);
    chain.push_back(b);
    parent = b;
  }
  return chain;
}

// Period of an oscillating value: steps the world `steps` times and averages the time between
// downward zero crossings (linearly interpolated). Returns -1 with fewer than 3 crossings.
template <class Value>
double oscillationPeriod(World& w, double dt, int steps, Value value) {
  double prev = value(), t_first = -1.0, t_last = -1.0;
  int crossings = 0;
  for (int i = 0; i < steps; ++i) {
    w.step(dt);
    const double x = value();
    if (prev > 0 && x <= 0) {
      const double t = w.time() - dt * x / (x - prev);
      if (t_first < 0) t_first = t;
      t_last = t;
      ++crossings;
    }
    prev = x;
  }
  return crossings >= 3 ? (t_last - t_first) / (crossings - 1) : -1.0;
}

}  // namespace test
}  // namespace ragdoll_sim
