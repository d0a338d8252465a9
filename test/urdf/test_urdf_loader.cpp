// Tests of the URDF loader: our ragdoll (structure, masses, inertias, rest pose, clearances),
// ball-chain frames against URDF forward kinematics, lumping / volume / mesh approximations,
// the peer ragdoll, real robots (recorded only) and malformed inputs.
#include <gtest/gtest.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>

#include "ragdoll_sim/urdf_loader.hpp"

using namespace ragdoll_sim;

namespace {

const std::string kSource = RAGDOLL_SIM_SOURCE_DIR;
const std::string kOurRagdoll = kSource + "/urdf/ragdoll.urdf";
const std::string kShared = kSource + "/../shared";

const UrdfLoadResult& ours() {
  static const UrdfLoadResult r = loadUrdfFile(kOurRagdoll);
  return r;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

Transform fromUrdf(const urdf::Pose& p) {
  return {Vec3(p.position.x, p.position.y, p.position.z),
          Quat(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z)};
}

Transform rot(const Vec3& axis, double t) { return {Vec3::Zero(), Quat(Eigen::AngleAxisd(t, axis))}; }

void expectNear(const Transform& a, const Transform& b, double tol) {
  EXPECT_LT((a.p - b.p).norm(), tol);
  EXPECT_LT(a.q.angularDistance(b.q), tol);
}

int count(const RagdollDef& d, RagdollJointKind k) {
  int n = 0;
  for (const auto& j : d.joints) n += j.kind == k;
  return n;
}

// For random angles, the child pose from composing the URDF joints (origin, then rotation about
// the axis) equals frame_parent * R(a0,t0) R(a1,t1) R(a2,t2) * frame_child^-1 (3rd angle 0 for
// a 2-joint chain), and the rest poses agree at zero angles.
void checkChainKinematics(const std::string& xml) {
  const UrdfLoadResult r = loadUrdfString(xml);
  ASSERT_TRUE(r.ok) << r.error;
  const auto model = urdf::parseURDF(xml);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> angle(-1.5, 1.5);
  for (const RagdollJointDef& j : r.def.joints) {
    ASSERT_EQ(j.axes.size(), j.kind == RagdollJointKind::Ball ? 3u : 1u);
    for (int trial = 0; trial < 20; ++trial) {
      Transform urdf_fk, ours = j.frame_parent;
      for (size_t k = 0; k < j.axes.size(); ++k) {
        const double t = k < j.source_joints.size() ? angle(rng) : 0.0;
        if (k < j.source_joints.size()) {
          const auto uj = model->getJoint(j.source_joints[k]);
          urdf_fk = urdf_fk * fromUrdf(uj->parent_to_joint_origin_transform) *
                    rot(Vec3(uj->axis.x, uj->axis.y, uj->axis.z).normalized(), t);
        }
        ours = ours * rot(j.axes[k], t);
      }
      expectNear(ours * j.frame_child.inverse(), urdf_fk, 1e-9);
    }
    expectNear(r.def.links[j.parent].rest_pose * j.frame_parent * j.frame_child.inverse(),
               r.def.links[j.child].rest_pose, 1e-12);
  }
}

// ---- separation of convex shapes by support functions ----------------------------------------
// h(d) = max over the shape of d . x, for unit d, with the shape at world pose W.
double support(const ShapeDef& s, const Transform& W, const Vec3& d) {
  const Vec3 l = W.q.conjugate() * d;
  const Geometry& g = s.geometry;
  double e = 0;
  switch (g.type) {
    case ShapeType::Sphere: e = g.radius; break;
    case ShapeType::Box: e = g.half_extents.dot(l.cwiseAbs()); break;
    case ShapeType::Cylinder: e = g.half_height * std::abs(l.z()) + g.radius * l.head<2>().norm(); break;
    default: ADD_FAILURE() << "unexpected shape type";
  }
  return W.p.dot(d) + e;
}

// Largest gap min_B(n.x) - max_A(n.x) over candidate directions n: a lower bound of the distance
// between A and B (any positive value proves separation; it is <= 0 whenever they overlap).
double clearance(const ShapeDef& a, const Transform& Wa, const ShapeDef& b, const Transform& Wb) {
  std::vector<Vec3> dirs{Wb.p - Wa.p};
  const Mat3 Ra = Wa.q.toRotationMatrix(), Rb = Wb.q.toRotationMatrix();
  for (int i = 0; i < 3; ++i) {
    dirs.push_back(Ra.col(i));
    dirs.push_back(Rb.col(i));
    for (int k = 0; k < 3; ++k) dirs.push_back(Ra.col(i).cross(Rb.col(k)));
  }
  const int n = 4000;  // Fibonacci sphere
  for (int i = 0; i < n; ++i) {
    const double z = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - z * z), phi = i * 2.399963229728653;
    dirs.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
  }
  double best = -1e9;
  for (Vec3 d : dirs) {
    if (d.norm() < 1e-9) continue;
    for (int sign : {1, -1}) {
      d = sign * d.normalized();
      best = std::max(best, -support(b, Wb, -d) - support(a, Wa, d));
    }
  }
  return best;
}

// Smallest clearance between the shapes of links i and k at their rest poses.
double linkClearance(const RagdollDef& d, int i, int k) {
  double worst = 1e9;
  for (const ShapeDef& a : d.links[i].shapes)
    for (const ShapeDef& b : d.links[k].shapes)
      worst = std::min(worst, clearance(a, d.links[i].rest_pose * a.local, b, d.links[k].rest_pose * b.local));
  return worst;
}

// Smallest clearance between links that are not in no_collide; names the pair.
double minNonAdjacentClearance(const RagdollDef& d, std::string* pair) {
  double worst = 1e9;
  for (int i = 0; i < int(d.links.size()); ++i)
    for (int k = i + 1; k < int(d.links.size()); ++k) {
      bool adjacent = false;
      for (auto [p, c] : d.no_collide) adjacent |= (p == i && c == k) || (p == k && c == i);
      const double c = adjacent ? 1e9 : linkClearance(d, i, k);
      if (c < worst) {
        worst = c;
        *pair = d.links[i].name + " / " + d.links[k].name;
      }
    }
  return worst;
}

}  // namespace

// ---- our ragdoll -----------------------------------------------------------------------------
TEST(OurRagdoll, LoadsWithFifteenLinksAndSeventyKilos) {
  const UrdfLoadResult& r = ours();
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.def.name, "ragdoll");
  ASSERT_EQ(r.def.links.size(), 15u);
  EXPECT_EQ(r.def.links[r.def.root].name, "pelvis");
  for (const char* n : {"pelvis", "torso", "head", "upper_arm_l", "upper_arm_r", "lower_arm_l",
                        "lower_arm_r", "hand_l", "hand_r", "thigh_l", "thigh_r", "shin_l", "shin_r",
                        "foot_l", "foot_r"})
    EXPECT_GE(r.def.findLink(n), 0) << n;
  EXPECT_GT(r.def.totalMass(), 68.0);
  EXPECT_LT(r.def.totalMass(), 72.0);
}

TEST(OurRagdoll, SixBallsEightHingesAllLimited) {
  const RagdollDef& d = ours().def;
  ASSERT_TRUE(ours().ok) << ours().error;
  EXPECT_EQ(count(d, RagdollJointKind::Ball), 6);
  EXPECT_EQ(count(d, RagdollJointKind::Hinge), 8);
  for (const RagdollJointDef& j : d.joints) {
    const size_t n = j.kind == RagdollJointKind::Ball ? 3 : 1;
    ASSERT_EQ(j.axes.size(), n) << j.name;
    ASSERT_EQ(j.lower.size(), n) << j.name;
    ASSERT_EQ(j.upper.size(), n) << j.name;
    EXPECT_EQ(j.source_joints.size(), n) << j.name;
    EXPECT_EQ(j.chain_links.size(), n == 3 ? 2u : 0u) << j.name;
    EXPECT_TRUE(j.limited) << j.name;
    for (size_t k = 0; k < n; ++k) EXPECT_LT(j.lower[k], j.upper[k]) << j.name << " axis " << k;
  }
  const auto hip = std::find_if(d.joints.begin(), d.joints.end(),
                                [&](const RagdollJointDef& j) { return j.child == d.findLink("thigh_l"); });
  ASSERT_NE(hip, d.joints.end());
  EXPECT_EQ(hip->name, "hip_l_y+hip_l_x+hip_l_z");
  EXPECT_EQ(hip->chain_links, (std::vector<std::string>{"hip_l_link1", "hip_l_link2"}));
  EXPECT_EQ(hip->parent, d.findLink("pelvis"));
}

TEST(OurRagdoll, NoCollidePairsAreTheJointedPairs) {
  const RagdollDef& d = ours().def;
  ASSERT_EQ(d.no_collide.size(), 14u);
  for (const RagdollJointDef& j : d.joints)
    EXPECT_NE(std::find(d.no_collide.begin(), d.no_collide.end(), std::make_pair(j.parent, j.child)),
              d.no_collide.end())
        << j.name;
}

TEST(OurRagdoll, InertiasArePhysical) {
  for (const LinkDef& l : ours().def.links) {
    EXPECT_GT(l.mass, 0) << l.name;
    EXPECT_LT((l.inertia - l.inertia.transpose()).norm(), 1e-12) << l.name;
    const Vec3 e = Eigen::SelfAdjointEigenSolver<Mat3>(l.inertia).eigenvalues();
    EXPECT_GT(e.minCoeff(), 0) << l.name;
    EXPECT_GE(e[0] + e[1], e[2] * (1 - 1e-9)) << l.name;  // triangle inequality (sorted)
  }
}

TEST(OurRagdoll, RestPoseStandsOnFlatSolesOneMetreBelowThePelvis) {
  const RagdollDef& d = ours().def;
  ASSERT_TRUE(ours().ok);
  EXPECT_TRUE(d.links[d.root].rest_pose.p.isZero());
  for (const char* foot : {"foot_l", "foot_r"}) {
    const LinkDef& l = d.links[d.findLink(foot)];
    ASSERT_EQ(l.shapes.size(), 1u);
    ASSERT_EQ(l.shapes[0].geometry.type, ShapeType::Box);
    const Transform W = l.rest_pose * l.shapes[0].local;
    std::vector<double> z;
    for (int c = 0; c < 8; ++c) {
      const Vec3 s((c & 1) ? 1 : -1, (c & 2) ? 1 : -1, (c & 4) ? 1 : -1);
      z.push_back(W.apply(s.cwiseProduct(l.shapes[0].geometry.half_extents)).z());
    }
    std::sort(z.begin(), z.end());
    EXPECT_NEAR(z[0], -1.0, 0.005) << foot;
    EXPECT_NEAR(z[3], z[0], 1e-9) << foot << " sole not flat";
  }
  // Nothing else reaches below the soles.
  for (const LinkDef& l : d.links)
    for (const ShapeDef& s : l.shapes)
      EXPECT_GE(-support(s, l.rest_pose * s.local, -Vec3::UnitZ()), -1.0 - 1e-9) << l.name;
}

TEST(OurRagdoll, NonAdjacentShapesKeepOneCentimetreApart) {
  RagdollDef d = ours().def;
  ASSERT_TRUE(ours().ok);
  std::string pair;
  EXPECT_GE(minNonAdjacentClearance(d, &pair), 0.01 - 1e-9) << pair;
  // Upper arms are jointed to the torso but must not touch it either.
  const int torso = d.findLink("torso");
  for (const char* arm : {"upper_arm_l", "upper_arm_r"})
    EXPECT_GE(linkClearance(d, torso, d.findLink(arm)), 0.01 - 1e-9) << arm;
  // The checks are sensitive: a forearm moved 3 cm inwards (into the torso's side), an upper arm
  // moved 2 cm into the torso.
  d.links[d.findLink("lower_arm_l")].shapes[0].local.p.y() -= 0.03;
  EXPECT_LT(minNonAdjacentClearance(d, &pair), 0.0);
  EXPECT_EQ(pair, "torso / lower_arm_l");
  d.links[d.findLink("upper_arm_r")].shapes[0].local.p.y() += 0.02;
  EXPECT_LT(linkClearance(d, torso, d.findLink("upper_arm_r")), 0.0);
}

TEST(OurRagdoll, BallChainFramesReproduceUrdfKinematics) {
  checkChainKinematics(readFile(kOurRagdoll));
}

// ---- loader semantics on small documents -----------------------------------------------------
namespace {
std::string boxLink(const std::string& name, double m, const std::string& extra = "") {
  return "<link name='" + name + "'><inertial><origin xyz='0.01 0.02 0.03' rpy='0.1 0.2 0.3'/>" +
         "<mass value='" + std::to_string(m) +
         "'/><inertia ixx='0.02' iyy='0.03' izz='0.04' ixy='0.001' ixz='0' iyz='0.002'/></inertial>"
         "<collision><origin xyz='0 0 0.1'/><geometry><box size='0.1 0.2 0.3'/></geometry></collision>" +
         extra + "</link>";
}
std::string dummyLink(const std::string& name) {
  return "<link name='" + name + "'><inertial><mass value='0.001'/>"
         "<inertia ixx='1e-6' iyy='1e-6' izz='1e-6' ixy='0' ixz='0' iyz='0'/></inertial></link>";
}
std::string joint(const std::string& name, const std::string& type, const std::string& parent,
                  const std::string& child, const std::string& xyz, const std::string& rpy,
                  const std::string& axis) {
  return "<joint name='" + name + "' type='" + type + "'><parent link='" + parent +
         "'/><child link='" + child + "'/><origin xyz='" + xyz + "' rpy='" + rpy +
         "'/><axis xyz='" + axis + "'/><limit lower='-1' upper='1.5' effort='1' velocity='1'/></joint>";
}
std::string robot(const std::string& body) { return "<robot name='t'>" + body + "</robot>"; }
}  // namespace

TEST(UrdfLoader, RotatedChainsBecomeBallsWithMatchingFrames) {
  // 3-chain with rotated inner origins Q2, Q3 and axes chosen so that a0, Q2 x2, Q2 Q3 x3 are the
  // orthonormal a0, a1, a2; then a 2-chain and a continuous hinge.
  const Vec3 a0(0, 0.6, 0.8), a1(1, 0, 0), a2 = a0.cross(a1);
  const Quat Q2 = quatFromRpy(0.4, 0.1, -0.7), Q3 = quatFromRpy(-0.2, 0.9, 0.1);
  auto str = [](const Vec3& v) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%.17g %.17g %.17g", v.x(), v.y(), v.z());
    return std::string(buf);
  };
  const std::string xml = robot(
      boxLink("a", 2) + boxLink("b", 3) + boxLink("c", 1) + boxLink("e", 1) + dummyLink("d1") +
      dummyLink("d2") + dummyLink("d3") +
      joint("j1", "revolute", "a", "d1", "0.1 0.2 0.3", "0.3 -0.2 0.5", str(a0)) +
      joint("j2", "revolute", "d1", "d2", "0 0 0", "0.4 0.1 -0.7", str(Q2.conjugate() * a1)) +
      joint("j3", "continuous", "d2", "b", "0 0 0", "-0.2 0.9 0.1", str((Q2 * Q3).conjugate() * a2)) +
      joint("k1", "revolute", "b", "d3", "0 0 -0.4", "0 0 0.3", "1 0 0") +
      joint("k2", "revolute", "d3", "c", "0 0 0", "0 0.5 0", "0 1 0") +
      joint("h", "continuous", "c", "e", "0 0.1 -0.2", "0.5 0 0", "0 1 1"));
  checkChainKinematics(xml);
  const UrdfLoadResult r = loadUrdfString(xml);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.def.joints.size(), 3u);
  const RagdollJointDef& ball3 = r.def.joints[0];
  EXPECT_EQ(ball3.name, "j1+j2+j3");
  EXPECT_EQ(ball3.chain_links, (std::vector<std::string>{"d1", "d2"}));
  EXPECT_TRUE(ball3.limited);
  EXPECT_DOUBLE_EQ(ball3.upper[2], M_PI);  // continuous axis
  const RagdollJointDef& ball2 = r.def.joints[1];
  EXPECT_EQ(ball2.kind, RagdollJointKind::Ball);
  EXPECT_EQ(ball2.lower[2], 0.0);
  EXPECT_EQ(ball2.upper[2], 0.0);
  EXPECT_NEAR(ball2.axes[2].dot(ball2.axes[0].cross(ball2.axes[1])), 1.0, 1e-12);
  const RagdollJointDef& hinge = r.def.joints[2];
  EXPECT_EQ(hinge.kind, RagdollJointKind::Hinge);
  EXPECT_FALSE(hinge.limited);
  EXPECT_NEAR(hinge.axes[0].norm(), 1.0, 1e-12);
  EXPECT_EQ(r.def.no_collide.size(), 3u);
}

TEST(UrdfLoader, NonOrthogonalChainKeepsItsHinges) {
  const UrdfLoadResult r = loadUrdfString(robot(
      boxLink("a", 2) + boxLink("b", 3) + dummyLink("d1") + dummyLink("d2") +
      joint("j1", "revolute", "a", "d1", "0 0 0", "0 0 0", "1 0 0") +
      joint("j2", "revolute", "d1", "d2", "0 0 0", "0 0 0", "1 1 0") +
      joint("j3", "revolute", "d2", "b", "0 0 0", "0 0 0", "0 0 1")));
  ASSERT_TRUE(r.ok) << r.error;
  // j1 stays a hinge (d1 gets a nominal mass); j2 and j3 are orthogonal: a 2-joint ball.
  ASSERT_EQ(r.def.joints.size(), 2u);
  EXPECT_EQ(r.def.joints[0].name, "j1");
  EXPECT_EQ(r.def.joints[0].kind, RagdollJointKind::Hinge);
  EXPECT_EQ(r.def.joints[1].name, "j2+j3");
  EXPECT_EQ(r.def.joints[1].kind, RagdollJointKind::Ball);
  EXPECT_NEAR(r.def.links[r.def.findLink("d1")].mass, 0.2 + 0.001, 1e-12);
  int warned = 0;
  for (const auto& w : r.def.warnings)
    warned += w.find("j1+j2+j3") != std::string::npos && w.find("not orthogonal") != std::string::npos;
  EXPECT_EQ(warned, 1);
}

TEST(UrdfLoader, FixedJointLumpsMassPropertiesAndShapes) {
  const std::string xml = robot(boxLink("a", 2) + boxLink("b", 3) +
                                joint("f", "fixed", "a", "b", "0.3 -0.1 0.2", "0.4 0.5 -0.6", "1 0 0"));
  const UrdfLoadResult r = loadUrdfString(xml);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.def.links.size(), 1u);
  const LinkDef& l = r.def.links[0];
  EXPECT_DOUBLE_EQ(l.mass, 5.0);
  ASSERT_EQ(l.shapes.size(), 2u);
  // Independent reference: each link's inertia rotated into a's frame and shifted to the COM.
  const auto model = urdf::parseURDF(xml);
  const Transform Tb = fromUrdf(model->getJoint("f")->parent_to_joint_origin_transform);
  Vec3 com = Vec3::Zero();
  std::vector<std::tuple<double, Vec3, Mat3>> parts;
  for (auto [name, T] : {std::make_pair("a", Transform()), std::make_pair("b", Tb)}) {
    const urdf::Inertial& in = *model->getLink(name)->inertial;
    const Transform F = T * fromUrdf(in.origin);
    Mat3 I;
    I << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
    const Mat3 R = F.q.toRotationMatrix();
    parts.emplace_back(in.mass, F.p, R * I * R.transpose());
    com += in.mass * F.p / 5.0;
  }
  Mat3 I = Mat3::Zero();
  for (auto& [m, c, Ic] : parts) {
    const Vec3 d = c - com;
    I += Ic + m * (d.squaredNorm() * Mat3::Identity() - d * d.transpose());
  }
  EXPECT_LT((l.com - com).norm(), 1e-12);
  EXPECT_LT((l.inertia - I).norm(), 1e-12);
  expectNear(l.shapes[1].local, Tb * Transform(Vec3(0, 0, 0.1), Quat::Identity()), 1e-12);
  EXPECT_FALSE(r.def.notes.empty());
  // b keeps its frame for TF: fixed on a's body at the joint origin.
  ASSERT_EQ(r.def.fixed_frames.size(), 1u);
  EXPECT_EQ(r.def.fixed_frames[0].name, "b");
  EXPECT_EQ(r.def.fixed_frames[0].link, 0);
  expectNear(r.def.fixed_frames[0].offset, Tb, 1e-12);
}

TEST(UrdfLoader, VolumeMassAndMeshApproximationsAreNoted) {
  const UrdfLoadResult r = loadUrdfString(robot(
      "<link name='a'><collision><geometry><sphere radius='0.1'/></geometry></collision></link>" +
      boxLink("b", 3, "<collision><geometry><mesh filename='package://x/b.stl'/></geometry></collision>") +
      joint("h", "revolute", "a", "b", "0 0 -0.2", "0 0 0", "0 1 0")));
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_NEAR(r.def.links[0].mass, 1000 * 4.0 / 3.0 * M_PI * 1e-3, 1e-9);
  EXPECT_NEAR(r.def.links[0].inertia(0, 0), 0.4 * r.def.links[0].mass * 0.01, 1e-12);
  ASSERT_EQ(r.def.links[1].shapes.size(), 2u);
  EXPECT_EQ(r.def.links[1].shapes[1].geometry.type, ShapeType::Box);
  int noted = 0, warned = 0;
  for (const auto& n : r.def.notes) noted += n.find("'a'") != std::string::npos || n.find("'b'") != std::string::npos;
  for (const auto& w : r.def.warnings) warned += w.find("'b'") != std::string::npos;
  EXPECT_EQ(noted, 1);   // a: volume mass
  EXPECT_EQ(warned, 1);  // b: the unresolved mesh
}

// ---- other models ----------------------------------------------------------------------------
TEST(PeerRagdoll, Ragdoll15Loads) {
  const std::string path = kShared + "/peers/ragdoll15.urdf";
  if (!std::filesystem::exists(path)) GTEST_SKIP() << path << " not present";
  const UrdfLoadResult r = loadUrdfFile(path);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.def.links.size(), 15u);
  // 26 revolute joints: waist, neck, shoulders, hips as 3-chains, 8 single hinges.
  EXPECT_EQ(count(r.def, RagdollJointKind::Ball), 6);
  EXPECT_EQ(count(r.def, RagdollJointKind::Hinge), 8);
  EXPECT_NEAR(r.def.totalMass(), 70.02, 0.01);
  checkChainKinematics(readFile(path));
}

TEST(UrdfZoo, EveryRobotLoads) {
  const std::string dir = kShared + "/urdf_zoo";
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << dir << " not present";
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".urdf") continue;
    const UrdfLoadResult r = loadUrdfFile(entry.path().string());
    EXPECT_TRUE(r.ok) << r.error;  // the drop itself: test/zoo/test_zoo.cpp
  }
}

// ---- malformed input -------------------------------------------------------------------------
TEST(UrdfLoader, MalformedInputsFailWithNamedElements) {
  const std::string good_link = boxLink("a", 1);
  const std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"", {"empty"}},
      {"not xml", {"XML", "line 1"}},
      {"<foo/>", {"robot"}},
      {robot(good_link + "<link name='b'/>" + joint("j", "revolute", "a", "ghost", "0 0 0", "0 0 0", "1 0 0")),
       {"ghost", "j"}},
      {robot(boxLink("heavy", -2)), {"heavy"}},
      {robot(good_link + boxLink("b", 1) + joint("j", "revolute", "a", "b", "0 nan 0", "0 0 0", "1 0 0")),
       {"j"}},
      {robot(good_link + boxLink("b", 1)), {"'a'", "'b'"}},  // two roots
      {robot(good_link + boxLink("b", 1) + joint("flat", "planar", "a", "b", "0 0 0", "0 0 0", "1 0 0")),
       {"flat", "planar"}},
      {robot(good_link + boxLink("b", 1) + joint("j", "revolute", "a", "b", "0 0 0", "0 0 0", "1 0 0") +
             boxLink("c", 1) + joint("free", "floating", "b", "c", "0 0 0", "0 0 0", "1 0 0")),
       {"free", "floating"}},  // floating below the root
  };
  for (const auto& [xml, names] : cases) {
    const UrdfLoadResult r = loadUrdfString(xml);
    EXPECT_FALSE(r.ok) << xml;
    EXPECT_FALSE(r.error.empty()) << xml;
    for (const std::string& n : names) EXPECT_NE(r.error.find(n), std::string::npos) << r.error;
  }
  const UrdfLoadResult missing = loadUrdfFile("/nonexistent/robot.urdf");
  EXPECT_FALSE(missing.ok);
  EXPECT_NE(missing.error.find("/nonexistent/robot.urdf"), std::string::npos);
}

// ---- <dynamics> ------------------------------------------------------------------------------
namespace {
// joint() with `inner` (e.g. a <dynamics/> element) before </joint>.
std::string jointWith(const std::string& inner, const std::string& name, const std::string& type,
                      const std::string& parent, const std::string& child, const std::string& axis) {
  std::string j = joint(name, type, parent, child, "0 0 0", "0 0 0", axis);
  return j.insert(j.size() - std::string("</joint>").size(), inner);
}
}  // namespace

TEST(UrdfLoader, DynamicsDampingAndFrictionGoToTheirAxes) {
  // a hinge h, a 3-chain b1 b2 b3 (ball) and a 2-chain c1 c2 (ball with a locked third axis).
  const UrdfLoadResult r = loadUrdfString(robot(
      boxLink("a", 2) + boxLink("h_child", 1) + boxLink("b", 1) + boxLink("c", 1) +
      dummyLink("d1") + dummyLink("d2") + dummyLink("d3") +
      jointWith("<dynamics damping='0.7' friction='1.5'/>", "h", "revolute", "a", "h_child", "0 1 0") +
      jointWith("<dynamics damping='0.1'/>", "b1", "revolute", "a", "d1", "0 1 0") +
      jointWith("<dynamics friction='0.2' damping='0.3'/>", "b2", "revolute", "d1", "d2", "1 0 0") +
      joint("b3", "revolute", "d2", "b", "0 0 0", "0 0 0", "0 0 1") +
      jointWith("<dynamics friction='4'/>", "c1", "continuous", "a", "d3", "1 0 0") +
      jointWith("<dynamics damping='2'></dynamics>", "c2", "revolute", "d3", "c", "0 0 1")));
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.def.joints.size(), 3u);
  auto byName = [&](const std::string& name) -> const RagdollJointDef& {
    for (const RagdollJointDef& j : r.def.joints)
      if (j.name == name) return j;
    ADD_FAILURE() << "no joint " << name;
    return r.def.joints[0];
  };
  const RagdollJointDef& h = byName("h");
  EXPECT_EQ(h.damping, (std::vector<double>{0.7}));
  EXPECT_EQ(h.friction, (std::vector<double>{1.5}));
  const RagdollJointDef& ball = byName("b1+b2+b3");
  EXPECT_EQ(ball.damping, (std::vector<double>{0.1, 0.3, 0.0}));
  EXPECT_EQ(ball.friction, (std::vector<double>{0.0, 0.2, 0.0}));
  const RagdollJointDef& ball2 = byName("c1+c2");
  EXPECT_EQ(ball2.damping, (std::vector<double>{0.0, 2.0, 0.0}));
  EXPECT_EQ(ball2.friction, (std::vector<double>{4.0, 0.0, 0.0}));

  // What spawnRagdoll puts on the axes.
  const JointMotor hm = passiveMotor(h, 0);
  EXPECT_TRUE(hm.enabled);
  EXPECT_DOUBLE_EQ(hm.hertz, 0.0);
  EXPECT_DOUBLE_EQ(hm.target_velocity, 0.0);
  EXPECT_DOUBLE_EQ(hm.max_torque, 1.5);
  EXPECT_DOUBLE_EQ(hm.damping, 0.7);
  EXPECT_FALSE(passiveMotor(ball, 0).enabled);  // damping only
  EXPECT_DOUBLE_EQ(passiveMotor(ball, 0).damping, 0.1);
  EXPECT_TRUE(passiveMotor(ball, 1).enabled);
  EXPECT_DOUBLE_EQ(passiveMotor(ball, 1).max_torque, 0.2);
  const JointMotor none = passiveMotor(ball, 2);
  EXPECT_FALSE(none.enabled);
  EXPECT_DOUBLE_EQ(none.damping, 0.0);
  EXPECT_FALSE(passiveMotor(ball, 7).enabled);  // out of range: nothing
}

TEST(UrdfLoader, OurRagdollHasNoJointDynamics) {
  ASSERT_TRUE(ours().ok) << ours().error;
  for (const RagdollJointDef& j : ours().def.joints) {
    EXPECT_EQ(j.damping, std::vector<double>(j.axes.size(), 0.0)) << j.name;
    EXPECT_EQ(j.friction, std::vector<double>(j.axes.size(), 0.0)) << j.name;
  }
}

TEST(UrdfLoader, EmptyDynamicsIsZeroAndOtherAttributesAreNoted) {
  // urdfdom alone rejects <dynamics/> without damping and friction; we read it as both 0. A
  // commented-out element and one inside <gazebo> (not URDF's) are left alone.
  const std::string xml = robot(
      boxLink("a", 2) + boxLink("b", 1) + boxLink("c", 1) + "<!-- <joint name='x'><dynamics/></joint> -->" +
      "<gazebo reference='h1'><joint name='g'><dynamics/></joint></gazebo>" +
      jointWith("<dynamics/>", "h1", "revolute", "a", "b", "0 1 0") +
      jointWith("<dynamics damping=\"0.25\" spring_stiffness='3' spring_reference='0.1'/>", "h2",
                "revolute", "b", "c", "1 0 0"));
  EXPECT_FALSE(urdf::parseURDF(xml)) << "urdfdom accepts an empty <dynamics/> now";
  const UrdfLoadResult r = loadUrdfString(xml);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.def.joints.size(), 2u);
  ASSERT_EQ(r.def.joints[0].name, "h1");  // a -> b -> c: h1 first
  EXPECT_EQ(r.def.joints[0].damping, (std::vector<double>{0.0}));
  EXPECT_EQ(r.def.joints[0].friction, (std::vector<double>{0.0}));
  EXPECT_EQ(r.def.joints[1].damping, (std::vector<double>{0.25}));
  int empty = 0, ignored = 0, other = 0;
  for (const std::string& n : r.def.notes) {
    if (n.find("dynamics") == std::string::npos) continue;
    if (n.find("'h1'") != std::string::npos && n.find("without damping or friction") != std::string::npos) ++empty;
    else if (n.find("'h2'") != std::string::npos && n.find("ignored") != std::string::npos &&
             (n.find("spring_stiffness") != std::string::npos || n.find("spring_reference") != std::string::npos)) ++ignored;
    else ++other;
  }
  EXPECT_EQ(empty, 1);
  EXPECT_EQ(ignored, 2);
  EXPECT_EQ(other, 0);
}

TEST(UrdfLoader, NegativeOrBadDynamicsFailNamingTheJoint) {
  for (const std::string dyn : {"<dynamics damping='-0.5'/>", "<dynamics friction='-1'/>",
                                "<dynamics damping='abc'/>"}) {
    const UrdfLoadResult r = loadUrdfString(robot(boxLink("a", 2) + boxLink("b", 1) +
                                                  jointWith(dyn, "bad_j", "revolute", "a", "b", "0 1 0")));
    EXPECT_FALSE(r.ok) << dyn;
    EXPECT_NE(r.error.find("bad_j"), std::string::npos) << r.error;
  }
}
