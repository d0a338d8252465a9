// Mass and inertia conditioning (stabilize.hpp): ratios brought within bounds, totals kept,
// and a chain with a 1500:1 mass ratio holds its anchors better after it.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cstdio>

#include "ragdoll_sim/stabilize.hpp"

using namespace ragdoll_sim;

namespace {
// torso (30 kg) - arm (1 kg) - hand (0.02 kg, thin rod inertia), hinges about y, links along x.
RagdollDef chain() {
  RagdollDef d;
  const double masses[3] = {30.0, 1.0, 0.02};
  for (int i = 0; i < 3; ++i) {
    LinkDef l;
    l.name = "link" + std::to_string(i);
    l.mass = masses[i];
    l.inertia = masses[i] * Vec3(0.001, 0.02, 0.02).asDiagonal();
    l.rest_pose = Transform(Vec3(0.3 * i, 0, 0), Quat::Identity());
    ShapeDef sh;
    sh.geometry = Geometry::box(Vec3(0.12, 0.04, 0.04));
    l.shapes.push_back(sh);
    d.links.push_back(l);
  }
  for (int i = 0; i < 2; ++i) {
    RagdollJointDef j;
    j.name = "j" + std::to_string(i);
    j.kind = RagdollJointKind::Hinge;
    j.parent = i;
    j.child = i + 1;
    j.frame_parent = Transform(Vec3(0.15, 0, 0), Quat::Identity());
    j.frame_child = Transform(Vec3(-0.15, 0, 0), Quat::Identity());
    j.axes = {Vec3::UnitY()};
    d.joints.push_back(j);
  }
  return d;
}

double worstAnchorAfterHit(const RagdollDef& def) {
  WorldDef wd;
  wd.gravity.setZero();
  wd.solver.position_iterations = 0;  // the velocity solver alone: what conditioning is for
  World w(wd);
  const Ragdoll r = spawnRagdoll(w, def, Transform());
  w.applyLinearImpulse(r.bodies[2], Vec3(0, 0, 0.5), w.bodyPose(r.bodies[2]).p);
  double worst = 0.0;
  for (int i = 0; i < 200; ++i) {
    w.step(1e-3);
    for (JointId j : r.joints) worst = std::max(worst, w.jointAnchorError(j).norm());
  }
  return worst;
}
}  // namespace

TEST(Stabilize, RatiosWithinBoundsAndTotalsKept) {
  RagdollDef d = chain();
  const double total = d.totalMass();
  StabilizeSettings s;
  s.max_mass_ratio = 4.0;
  s.max_inertia_ratio = 10.0;
  const auto report = stabilizeRagdoll(d, s);
  EXPECT_FALSE(report.empty());
  EXPECT_NEAR(d.totalMass(), total, 1e-12);
  for (const RagdollJointDef& j : d.joints) {
    const double a = d.links[j.parent].mass, b = d.links[j.child].mass;
    EXPECT_LE(std::max(a, b) / std::min(a, b), 4.0 + 1e-9) << j.name;
  }
  for (const LinkDef& l : d.links) {
    const Vec3 e = Eigen::SelfAdjointEigenSolver<Mat3>(l.inertia).eigenvalues();
    EXPECT_LE(e.maxCoeff() / e.minCoeff(), 10.0 + 1e-9) << l.name;
  }
  std::printf("[ stabilize] masses 30 / 1 / 0.02 -> %.3f / %.3f / %.3f kg (total %.3f kept)\n",
              d.links[0].mass, d.links[1].mass, d.links[2].mass, d.totalMass());
  // An already conditioned def is left alone.
  EXPECT_TRUE(stabilizeRagdoll(d, s).empty());
}

TEST(Stabilize, ConditionedChainHoldsAnchorsBetter) {
  RagdollDef raw = chain(), conditioned = chain();
  stabilizeRagdoll(conditioned);
  const double before = worstAnchorAfterHit(raw), after = worstAnchorAfterHit(conditioned);
  std::printf("[ stabilize] hand hit, no projection: max anchor error %.3f mm raw, %.3f mm conditioned\n",
              1e3 * before, 1e3 * after);
  EXPECT_LT(after, 0.5 * before);
}
