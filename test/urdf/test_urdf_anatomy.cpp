// Anatomy from the URDF: a spherical joint's swing-twist <limit> and a link's <gazebo>
// dampingFactor reach the RagdollDef and act in the World as documented.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "ragdoll_sim/urdf_loader.hpp"

using namespace ragdoll_sim;

namespace {

constexpr double kDt = 1e-3;

// world -(fixed)- base -(spherical "shoulder", <limit .../>)- arm, the arm's COM 0.5 m along x.
std::string shoulderUrdf(const std::string& limit) {
  return "<robot name='s'><link name='world'/>"
         "<joint name='bolt' type='fixed'><parent link='world'/><child link='base'/></joint>"
         "<link name='base'><inertial><mass value='1'/><inertia ixx='0.01' iyy='0.01' izz='0.01' "
         "ixy='0' ixz='0' iyz='0'/></inertial></link>"
         "<joint name='shoulder' type='spherical'><parent link='base'/><child link='arm'/>"
         "<origin xyz='0 0 1'/>" + limit + "</joint>"
         "<link name='arm'><inertial><origin xyz='0.5 0 0'/><mass value='1'/><inertia ixx='0.002' "
         "iyy='0.02' izz='0.02' ixy='0' ixz='0' iyz='0'/></inertial></link></robot>";
}

// The arm released horizontal falls about y; returns the largest and the final swing.
void dropArm(const RagdollDef& def, double* max_swing, double* final_swing) {
  WorldDef wd;
  wd.sleep.enabled = false;
  World w(wd);
  const Ragdoll r = spawnRagdoll(w, def, Transform());
  *max_swing = 0.0;
  for (int i = 0; i < 2000; ++i) {
    w.step(kDt);
    *max_swing = std::max(*max_swing, w.ballSwingTwist(r.joints.at(0))[0]);
  }
  *final_swing = w.ballSwingTwist(r.joints.at(0))[0];
}

}  // namespace

TEST(UrdfAnatomy, SphericalLimitReachesTheJointAndHolds) {
  const UrdfLoadResult res = loadUrdfString(
      shoulderUrdf("<limit cone_y='0.8' cone_z='0.5' twist_lower='-0.3' twist_upper='0.2'/>"));
  ASSERT_TRUE(res.ok) << res.error;
  ASSERT_EQ(res.def.joints.size(), 1u);
  const RagdollJointDef& j = res.def.joints[0];
  ASSERT_TRUE(j.swing_twist.has_value());
  EXPECT_EQ(j.swing_twist->cone_1, 0.8);
  EXPECT_EQ(j.swing_twist->cone_2, 0.5);
  EXPECT_EQ(j.swing_twist->twist_lower, -0.3);
  EXPECT_EQ(j.swing_twist->twist_upper, 0.2);
  double max_swing, final_swing;
  dropArm(res.def, &max_swing, &final_swing);
  EXPECT_LT(max_swing, 0.8 + 0.02);
  EXPECT_NEAR(final_swing, 0.8, 0.01);
  // Without the extension the same arm swings through the horizontal plane's lowest point.
  const UrdfLoadResult free = loadUrdfString(shoulderUrdf(""));
  ASSERT_TRUE(free.ok) << free.error;
  EXPECT_FALSE(free.def.joints[0].swing_twist.has_value());
  double free_max, free_final;
  dropArm(free.def, &free_max, &free_final);
  EXPECT_GT(free_max, 1.5);
  std::printf("[ anatomy  ] spherical <limit cone_y=0.8>: max swing %.4f, held %.4f rad; without: "
              "max swing %.4f rad\n", max_swing, final_swing, free_max);
}

TEST(UrdfAnatomy, BadSphericalLimitNamesJointAndField) {
  const struct {
    const char* limit;
    const char* message;
  } cases[] = {
      {"<limit cone_y='-0.5'/>", "joint 'shoulder': <limit> cone_y must be an angle in (0, pi]"},
      {"<limit cone_z='4'/>", "joint 'shoulder': <limit> cone_z must be an angle in (0, pi]"},
      {"<limit cone_y='nan'/>", "joint 'shoulder': <limit> cone_y must be a number"},
      {"<limit twist_lower='0.4' twist_upper='0.1'/>",
       "joint 'shoulder': <limit> twist_lower must be <= twist_upper, got 0.4 > 0.1"},
      {"<limit twist_upper='-4'/>", "joint 'shoulder': <limit> twist_upper must be an angle in [-pi, pi]"},
  };
  for (const auto& c : cases) {
    const UrdfLoadResult res = loadUrdfString(shoulderUrdf(c.limit));
    EXPECT_FALSE(res.ok) << c.limit;
    EXPECT_NE(res.error.find(c.message), std::string::npos) << c.limit << " -> " << res.error;
  }
}

// dampingFactor d: v(t) = v0 (1 - d)^(t / 1 ms) in Gazebo; here c = -ln(1 - d) / 1 ms, applied
// implicitly per substep h: v_n = v0 / (1 + c h)^n.
TEST(UrdfAnatomy, DampingFactorDecaysVelocityAsGazebo) {
  const double d = 0.002;
  const std::string xml =
      "<robot name='f'><link name='puck'><inertial><mass value='2'/><inertia ixx='0.01' "
      "iyy='0.01' izz='0.01' ixy='0' ixz='0' iyz='0'/></inertial></link>"
      "<gazebo reference='puck'><dampingFactor>" + std::to_string(d) +
      "</dampingFactor></gazebo></robot>";
  const UrdfLoadResult res = loadUrdfString(xml);
  ASSERT_TRUE(res.ok) << res.error;
  const double c = -std::log(1.0 - d) / 0.001;
  EXPECT_NEAR(res.def.links[0].linear_damping, c, 1e-9 * c);
  EXPECT_NEAR(res.def.links[0].angular_damping, c, 1e-9 * c);
  WorldDef wd;
  wd.gravity.setZero();
  wd.sleep.enabled = false;
  World w(wd);
  const Ragdoll r = spawnRagdoll(w, res.def, Transform());
  const BodyId b = r.bodies.at(0);
  w.setBodyState(b, Transform(), Vec3(3.0, 0, 0), Vec3(0, 0, 2.0));
  const double T = 0.5;
  for (int i = 0; i < int(T / kDt + 0.5); ++i) w.step(kDt);
  const int substeps = w.def().solver.substeps;
  const int n = int(T / kDt + 0.5) * substeps;
  const double h = kDt / substeps;
  const double discrete = std::pow(1.0 + c * h, -n);  // this solver's implicit law
  const double gazebo = std::pow(1.0 - d, T / 0.001);  // Gazebo's per-step law at 1 ms
  const double v = w.bodyState(b).linear_velocity.x() / 3.0;
  const double wz = w.bodyState(b).angular_velocity.z() / 2.0;
  EXPECT_NEAR(v, discrete, 1e-9);
  EXPECT_NEAR(wz, discrete, 1e-9);
  EXPECT_NEAR(v, gazebo, 0.01 * gazebo);
  std::printf("[ anatomy  ] dampingFactor %.3f -> c = %.4f 1/s; v/v0 after %.1f s: %.6f (implicit "
              "law %.6f, Gazebo 1 ms law %.6f, exp(-c t) %.6f)\n",
              d, c, T, v, discrete, gazebo, std::exp(-c * T));
}

TEST(UrdfAnatomy, BadDampingFactorIsNotedAndIgnored) {
  const std::string xml =
      "<robot name='f'><link name='puck'><inertial><mass value='2'/><inertia ixx='0.01' "
      "iyy='0.01' izz='0.01' ixy='0' ixz='0' iyz='0'/></inertial></link>"
      "<gazebo reference='puck'><dampingFactor>1.5</dampingFactor></gazebo></robot>";
  const UrdfLoadResult res = loadUrdfString(xml);
  ASSERT_TRUE(res.ok) << res.error;
  EXPECT_EQ(res.def.links[0].linear_damping, 0.0);
  bool noted = false;
  for (const auto& n : res.def.notes)
    noted |= n.find("<dampingFactor> is not a number in [0, 1)") != std::string::npos;
  EXPECT_TRUE(noted);
}
