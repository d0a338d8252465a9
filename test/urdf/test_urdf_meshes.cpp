// Mesh collision geometry: package:// (next to the URDF, in package_paths, in
// ROS_PACKAGE_PATH), file:// and relative paths resolve to convex hulls (an OBJ fixture, an STL
// written here); unresolved meshes fall back to the visual geometry or a box fitted to the
// inertia, with one warning per link.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "ragdoll_sim/drop_check.hpp"
#include "ragdoll_sim/urdf_loader.hpp"

using namespace ragdoll_sim;
namespace fs = std::filesystem;

namespace {

const std::string kFixtures = std::string(RAGDOLL_SIM_SOURCE_DIR) + "/test/urdf/fixtures";
const std::string kPackage = kFixtures + "/ragdoll_mesh_fixture";

// Axis-aligned bounding box of a hull shape's vertices in the link frame.
void bounds(const ShapeDef& s, Vec3* lo, Vec3* hi) {
  ASSERT_EQ(s.geometry.type, ShapeType::ConvexHull);
  ASSERT_TRUE(s.geometry.hull);
  *lo = Vec3::Constant(1e9);
  *hi = Vec3::Constant(-1e9);
  for (const Vec3& v : s.geometry.hull->vertices) {
    *lo = lo->cwiseMin(s.local.apply(v));
    *hi = hi->cwiseMax(s.local.apply(v));
  }
}

int warningsAbout(const RagdollDef& d, const std::string& link) {
  return int(std::count_if(d.warnings.begin(), d.warnings.end(), [&](const std::string& w) {
    return w.find("link '" + link + "'") != std::string::npos;
  }));
}

std::string oneMeshRobot(const std::string& filename) {
  return "<robot name='m'><link name='a'><inertial><mass value='1'/><inertia ixx='0.01' iyy='0.01' "
         "izz='0.01' ixy='0' ixz='0' iyz='0'/></inertial><collision><geometry><mesh filename='" +
         filename + "'/></geometry></collision></link></robot>";
}

// An ASCII STL box of size (x, y, z) with a corner at the origin, 12 triangles.
void writeBoxStl(const std::string& path, const Vec3& size) {
  std::ofstream f(path);
  f << "solid box\n";
  auto corner = [&](int c) { return Vec3((c & 1) * size.x(), ((c >> 1) & 1) * size.y(), ((c >> 2) & 1) * size.z()); };
  const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
  for (const auto& q : quads) {
    const int tris[2][3] = {{q[0], q[1], q[2]}, {q[0], q[2], q[3]}};
    for (const auto& tri : tris) {
      f << " facet normal 0 0 0\n  outer loop\n";
      for (int k = 0; k < 3; ++k) {
        const Vec3 v = corner(tri[k]);
        f << "   vertex " << v.x() << " " << v.y() << " " << v.z() << "\n";
      }
      f << "  endloop\n endfacet\n";
    }
  }
  f << "endsolid box\n";
}

}  // namespace

TEST(UrdfMeshes, FixturePackageRelativeAndMissingMeshes) {
  const UrdfLoadResult r = loadUrdfFile(kPackage + "/urdf/meshes.urdf");  // package next to the file
  ASSERT_TRUE(r.ok) << r.error;
  const RagdollDef& d = r.def;
  Vec3 lo, hi;
  // package://ragdoll_mesh_fixture/meshes/wedge.obj: the 6-vertex wedge.
  const LinkDef& base = d.links[d.findLink("base")];
  ASSERT_EQ(base.shapes.size(), 1u);
  bounds(base.shapes[0], &lo, &hi);
  EXPECT_EQ(base.shapes[0].geometry.hull->vertices.size(), 6u);
  EXPECT_LT((lo - Vec3::Zero()).norm(), 1e-6);  // assimp reads floats
  EXPECT_LT((hi - Vec3(0.2, 0.1, 0.05)).norm(), 1e-6);
  EXPECT_NEAR(base.shapes[0].geometry.volume(), 0.5 * 0.2 * 0.1 * 0.05, 1e-9);
  EXPECT_NE(base.shape_sources[0].find("convex hull of package://ragdoll_mesh_fixture/meshes/wedge.obj"),
            std::string::npos) << base.shape_sources[0];
  EXPECT_EQ(warningsAbout(d, "base"), 0);
  // ../meshes/wedge.obj relative to the URDF, scale 2.
  const LinkDef& rel = d.links[d.findLink("relative")];
  ASSERT_EQ(rel.shapes.size(), 1u);
  bounds(rel.shapes[0], &lo, &hi);
  EXPECT_LT((hi - lo - Vec3(0.4, 0.2, 0.1)).norm(), 1e-6);
  // Two unresolved meshes: one box fitted to the inertia, one warning for the link.
  const LinkDef& missing = d.links[d.findLink("missing")];
  ASSERT_EQ(missing.shapes.size(), 1u);
  EXPECT_EQ(missing.shapes[0].geometry.type, ShapeType::Box);
  // I = m/12 (b^2 + c^2) ... for full sides: sides^2 = 6/m (I2 + I3 - I1) -> 0.3, 0.2, 0.1 m
  const Vec3 h = missing.shapes[0].geometry.half_extents;
  std::array<double, 3> sides = {2 * h.x(), 2 * h.y(), 2 * h.z()};
  std::sort(sides.begin(), sides.end());
  EXPECT_NEAR(sides[0], std::sqrt(6 * (0.002 + 0.003 - 0.004)), 1e-9);
  EXPECT_NEAR(sides[2], std::sqrt(6 * (0.003 + 0.004 - 0.002)), 1e-9);
  EXPECT_EQ(warningsAbout(d, "missing"), 1);
  EXPECT_NE(missing.shape_sources[0].find("unresolved"), std::string::npos);
  // Unresolved file:// mesh, but a <visual> box: that box, one warning.
  const LinkDef& vis = d.links[d.findLink("visual_only")];
  ASSERT_EQ(vis.shapes.size(), 1u);
  EXPECT_EQ(vis.shapes[0].geometry.type, ShapeType::Box);
  EXPECT_LT((vis.shapes[0].geometry.half_extents - Vec3(0.05, 0.1, 0.15)).norm(), 1e-12);
  EXPECT_EQ(warningsAbout(d, "visual_only"), 1);
  // And the model drops onto its hulls and boxes without trouble.
  const DropReport drop = dropTest(d, DropSettings());
  EXPECT_TRUE(drop.finite);
  EXPECT_GT(drop.min_lowest_point, -0.01);
  EXPECT_LT(drop.lowest_point, 0.01);
}

TEST(UrdfMeshes, PackageFoundInPackagePathsOrRosPackagePath) {
  const std::string xml = oneMeshRobot("package://ragdoll_mesh_fixture/meshes/wedge.obj");
  UrdfLoadOptions o;  // no base_dir: only the search paths can find the package
  o.package_paths = {kFixtures};
  const UrdfLoadResult by_option = loadUrdfString(xml, o);
  ASSERT_TRUE(by_option.ok) << by_option.error;
  EXPECT_EQ(by_option.def.links[0].shapes.at(0).geometry.type, ShapeType::ConvexHull);
  EXPECT_TRUE(by_option.def.warnings.empty());

  const char* old = std::getenv("ROS_PACKAGE_PATH");
  const std::string saved = old ? old : "";
  setenv("ROS_PACKAGE_PATH", ("/nonexistent:" + kFixtures).c_str(), 1);
  const UrdfLoadResult by_env = loadUrdfString(xml);
  if (old) setenv("ROS_PACKAGE_PATH", saved.c_str(), 1);
  else unsetenv("ROS_PACKAGE_PATH");
  ASSERT_TRUE(by_env.ok) << by_env.error;
  EXPECT_EQ(by_env.def.links[0].shapes.at(0).geometry.type, ShapeType::ConvexHull);

  o.package_paths = {"/nonexistent"};
  const UrdfLoadResult not_found = loadUrdfString(xml, o);
  ASSERT_TRUE(not_found.ok) << not_found.error;
  EXPECT_EQ(not_found.def.links[0].shapes.at(0).geometry.type, ShapeType::Box);
  ASSERT_EQ(not_found.def.warnings.size(), 1u);
  EXPECT_NE(not_found.def.warnings[0].find("ragdoll_mesh_fixture not found"), std::string::npos)
      << not_found.def.warnings[0];
}

TEST(UrdfMeshes, StlByFileUriAndRelativePath) {
  const fs::path dir = fs::temp_directory_path() / ("ragdoll_mesh_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  writeBoxStl((dir / "box.stl").string(), Vec3(0.1, 0.2, 0.3));
  UrdfLoadOptions o;
  o.base_dir = dir.string();
  for (const std::string& uri : {"file://" + (dir / "box.stl").string(), std::string("box.stl")}) {
    const UrdfLoadResult r = loadUrdfString(oneMeshRobot(uri), o);
    ASSERT_TRUE(r.ok) << r.error;
    ASSERT_EQ(r.def.links[0].shapes.size(), 1u) << uri;
    const Geometry& g = r.def.links[0].shapes[0].geometry;
    ASSERT_EQ(g.type, ShapeType::ConvexHull) << uri;
    EXPECT_EQ(g.hull->vertices.size(), 8u);
    EXPECT_EQ(g.hull->faces.size(), 6u);
    EXPECT_NEAR(g.volume(), 0.1 * 0.2 * 0.3, 1e-9);
    EXPECT_TRUE(r.def.warnings.empty()) << r.def.warnings[0];
  }
  UrdfLoadOptions off = o;
  off.load_meshes = false;
  const UrdfLoadResult r = loadUrdfString(oneMeshRobot("box.stl"), off);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(r.def.links[0].shapes.at(0).geometry.type, ShapeType::Box);
  fs::remove_all(dir);
}

TEST(UrdfMeshes, ColladaUnitsAppliedAndAxesKept) {
  UrdfLoadOptions o;
  o.package_paths = {kFixtures};
  const UrdfLoadResult r =
      loadUrdfString(oneMeshRobot("package://ragdoll_mesh_fixture/meshes/wedge_cm.dae"), o);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(r.def.links[0].shapes.size(), 1u);
  Vec3 lo, hi;
  bounds(r.def.links[0].shapes[0], &lo, &hi);
  EXPECT_LT(lo.norm(), 1e-6);
  EXPECT_LT((hi - Vec3(0.2, 0.1, 0.05)).norm(), 1e-6);  // cm -> m, Z_UP not turned to Y up
}
