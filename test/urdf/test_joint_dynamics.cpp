// URDF <dynamics> through the loader and spawnRagdoll, against closed forms. Two free bodies in
// zero gravity, joined at a pivot that is the centre of mass of both (so the anchor couples no
// linear motion), relative spin about a joint axis with inverse inertias 1/I_A + 1/I_B = K:
//   viscous damping c:   I_B w_B' = -c w,  I_A w_A' = c w   =>  w(t) = w0 exp(-c K t),
//   friction torque f with an internal load tau (+tau on B, -tau on A):
//     |tau| <= f: the joint holds (w stays 0);  tau > f: w' = (tau - f) K.
// A ball chain's source joints each give their own axis these values.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "ragdoll_sim/urdf_loader.hpp"

using namespace ragdoll_sim;

namespace {

constexpr double kDt = 1e-3;

// Diagonal inertias (principal axes = link axes).
const Vec3 kIa(0.02, 0.03, 0.04);    // link a, 2 kg
const Vec3 kIb(0.01, 0.015, 0.025);  // link b, 1 kg

std::string link(const std::string& name, double mass, const Vec3& I) {
  return "<link name='" + name + "'><inertial><mass value='" + std::to_string(mass) +
         "'/><inertia ixx='" + std::to_string(I.x()) + "' iyy='" + std::to_string(I.y()) +
         "' izz='" + std::to_string(I.z()) + "' ixy='0' ixz='0' iyz='0'/></inertial></link>";
}

std::string joint(const std::string& name, const std::string& parent, const std::string& child,
                  const std::string& axis, const std::string& dynamics) {
  return "<joint name='" + name + "' type='continuous'><parent link='" + parent +
         "'/><child link='" + child + "'/><origin xyz='0 0 0'/><axis xyz='" + axis + "'/>" +
         dynamics + "</joint>";
}

std::string dummy(const std::string& name) {
  return "<link name='" + name + "'><inertial><mass value='0.0001'/>"
         "<inertia ixx='1e-8' iyy='1e-8' izz='1e-8' ixy='0' ixz='0' iyz='0'/></inertial></link>";
}

// a -(hinge about y)- b
std::string hingeUrdf(const std::string& dynamics) {
  return "<robot name='h'>" + link("a", 2, kIa) + link("b", 1, kIb) +
         joint("h", "a", "b", "0 1 0", dynamics) + "</robot>";
}

// a -(y, x, z chain)- b with per-joint dynamics
std::string ballUrdf(const std::string& dy, const std::string& dx, const std::string& dz) {
  return "<robot name='b'>" + link("a", 2, kIa) + link("b", 1, kIb) + dummy("d1") + dummy("d2") +
         joint("jy", "a", "d1", "0 1 0", dy) + joint("jx", "d1", "d2", "1 0 0", dx) +
         joint("jz", "d2", "b", "0 0 1", dz) + "</robot>";
}

struct Scene {
  World w;
  RagdollDef def;
  Ragdoll r;
  BodyId a, b;

  explicit Scene(const std::string& xml) : w(zeroG()) {
    const UrdfLoadResult res = loadUrdfString(xml);
    EXPECT_TRUE(res.ok) << res.error;
    def = res.def;
    r = spawnRagdoll(w, def, Transform());
    a = r.bodies.at(def.findLink("a"));
    b = r.bodies.at(def.findLink("b"));
  }
  static WorldDef zeroG() {
    WorldDef d;
    d.gravity.setZero();
    d.sleep.enabled = false;  // shapeless bodies count as slow whatever their spin
    return d;
  }
  // Relative spin of b on a about world axis n.
  double rate(const Vec3& n) const {
    return n.dot(w.bodyState(b).angular_velocity - w.bodyState(a).angular_velocity);
  }
};

double K(int axis) { return 1.0 / kIa[axis] + 1.0 / kIb[axis]; }

}  // namespace

TEST(JointDynamics, HingeViscousDampingDecaysExponentially) {
  const double c = 0.01;  // N m s/rad: decay rate c K = 1/s
  Scene s(hingeUrdf("<dynamics damping='" + std::to_string(c) + "'/>"));
  ASSERT_EQ(s.def.joints.size(), 1u);
  s.w.setBodyState(s.b, Transform(), Vec3::Zero(), Vec3(0, 1.0, 0));
  const double L0 = s.w.angularMomentum(Vec3::Zero()).y();
  for (int i = 0; i < 1000; ++i) s.w.step(kDt);
  const double expected = std::exp(-c * K(1) * 1.0);
  EXPECT_NEAR(s.rate(Vec3::UnitY()), expected, 1e-3 * expected);
  EXPECT_NEAR(s.w.angularMomentum(Vec3::Zero()).y(), L0, 1e-9);
  std::printf("[ dynamics ] hinge damping c=%.3f: spin after 1 s %.6f rad/s, closed form %.6f\n", c,
              s.rate(Vec3::UnitY()), expected);
}

TEST(JointDynamics, HingeFrictionHoldsBelowAndSlipsAbove) {
  const double f = 0.5;  // N m
  for (const double tau : {0.4, 0.8}) {
    Scene s(hingeUrdf("<dynamics friction='" + std::to_string(f) + "'/>"));
    const double T = 0.2;
    for (int i = 0; i < int(std::lround(T / kDt)); ++i) {
      s.w.applyTorque(s.b, Vec3(0, tau, 0));
      s.w.applyTorque(s.a, Vec3(0, -tau, 0));
      s.w.step(kDt);
    }
    const double w = s.rate(Vec3::UnitY());
    const double angle = s.w.hingeAngle(s.r.joints[0]);
    if (tau < f) {
      EXPECT_LT(std::abs(w), 1e-9) << "slipped under a load of " << tau << " N m";
      EXPECT_LT(std::abs(angle), 1e-9);
    } else {
      const double expected = (tau - f) * K(1) * T;  // 6 rad/s
      EXPECT_NEAR(w, expected, 1e-3 * expected);
      EXPECT_NEAR(angle, 0.5 * (tau - f) * K(1) * T * T, 0.01);
    }
    std::printf("[ dynamics ] hinge friction %.2f N m, load %.2f N m: spin after %.1f s %.6f rad/s, "
                "angle %.6f rad\n", f, tau, T, w, angle);
  }
}

TEST(JointDynamics, BallChainDampingPerSourceJoint) {
  const double c[3] = {0.004, 0.006, 0.0};  // jy (axis 0), jx (axis 1), jz (axis 2: none)
  const Vec3 axes[3] = {Vec3::UnitY(), Vec3::UnitX(), Vec3::UnitZ()};
  const int inertia_index[3] = {1, 0, 2};
  for (int k = 0; k < 3; ++k) {
    Scene s(ballUrdf("<dynamics damping='" + std::to_string(c[0]) + "'/>",
                     "<dynamics damping='" + std::to_string(c[1]) + "'/>", ""));
    ASSERT_EQ(s.def.joints.size(), 1u);
    ASSERT_EQ(s.def.joints[0].kind, RagdollJointKind::Ball);
    s.w.setBodyState(s.b, Transform(), Vec3::Zero(), 0.5 * axes[k]);
    for (int i = 0; i < 500; ++i) s.w.step(kDt);
    const double expected = 0.5 * std::exp(-c[k] * K(inertia_index[k]) * 0.5);
    EXPECT_NEAR(s.rate(axes[k]), expected, 1e-3 * expected) << "axis " << k;
    std::printf("[ dynamics ] ball axis %d damping %.3f: spin after 0.5 s %.6f rad/s, closed form %.6f\n",
                k, c[k], s.rate(axes[k]), expected);
  }
}

TEST(JointDynamics, BallChainFrictionOnlyOnItsAxis) {
  // Friction 0.3 N m on jx only; a 0.2 N m load about x holds, the same load about z spins.
  const double f = 0.3, tau = 0.2, T = 0.2;
  const Vec3 loads[2] = {Vec3::UnitX(), Vec3::UnitZ()};
  for (const Vec3& n : loads) {
    Scene s(ballUrdf("", "<dynamics friction='" + std::to_string(f) + "'/>", ""));
    for (int i = 0; i < int(std::lround(T / kDt)); ++i) {
      s.w.applyTorque(s.b, tau * n);
      s.w.applyTorque(s.a, -tau * n);
      s.w.step(kDt);
    }
    const double w = s.rate(n);
    if (n.x() > 0) {
      EXPECT_LT(std::abs(w), 1e-9);
    } else {
      const double expected = tau * K(2) * T;
      EXPECT_NEAR(w, expected, 1e-3 * expected);
    }
  }
}
