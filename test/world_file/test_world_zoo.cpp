// The 14 real Gazebo worlds of ../shared/world_zoo (skipped when it is absent): at least 12 load,
// and the counts agree with its MANIFEST.tsv where the manifest pins them.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <map>

#include "world_test_util.hpp"

using namespace ragdoll_sim;

namespace {

const std::string kZoo = std::string(RAGDOLL_SIM_SOURCE_DIR) + "/../shared/world_zoo";

struct Expected {
  int models, static_shapes, dynamic_bodies;
};

// From MANIFEST.tsv: n_models less the model://sun includes (a light) and the Fuel URIs that
// are not saved; static_shapes = its primitive counts (inline and in included models) less the
// meshes, which are not bundled; dynamic_bodies = the links of its has_dynamic models.
const std::map<std::string, Expected>& expected() {
  static const std::map<std::string, Expected> e = {
      {"casannis_stairs", {7, 7, 0}},        // 8 - sun; box:6 plane:1
      {"unitree_stairs", {3, 8, 0}},         // 4 - sun; box:3 + box:4 plane:1
      {"pal_simple_ramp", {16, 16, 0}},      // 17 - sun; box:15 + plane:1
      {"drc_qual_task_3", {26, 46, 0}},      // box:26 cylinder:1 + box:18 plane:1
      {"gzclassic_friction_demo", {7, 1, 6}},
      {"px4_safe_landing", {12, 2, 8}},      // plane:1 box:1 (+ 2 meshes)
      {"champ_outdoor", {42, 22, 18}},       // box:18 cylinder:3 plane:1 (+ meshes)
      {"gz_3k_shapes", {3004, 1, 3003}},
      {"px4_walls", {5, 5, 0}},
      {"tb3_world", {1, 9, 0}},              // 3 - 2 Fuel URIs; cylinder:9 (+ 6 meshes)
      {"gz_global_illumination", {7, 6, 1}}, // box:6; the pump's mesh is a Fuel URI
      {"robocup_game_field", {5, 30, 1}},    // 6 - sun; box:22 cylinder:6 plane:2; the ball
  };
  return e;
}

}  // namespace

TEST(WorldZoo, AtLeastTwelveOfFourteenLoad) {
  namespace fs = std::filesystem;
  if (!fs::is_directory(kZoo)) GTEST_SKIP() << kZoo << " not present";
  WorldLoadOptions o;
  o.model_paths = {kZoo + "/models"};
  int loaded = 0, total = 0;
  std::vector<fs::path> files;
  for (const auto& f : fs::directory_iterator(kZoo))
    if (f.path().extension() == ".world") files.push_back(f.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& f : files) {
    ++total;
    const std::string name = f.stem().string();
    const auto t0 = std::chrono::steady_clock::now();
    const WorldLoadResult r = loadWorldFile(f.string(), o);
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!r.ok) {
      std::printf("%-26s REFUSED: %s\n", name.c_str(), r.error.c_str());
      continue;
    }
    ++loaded;
    std::printf("%-26s %s (%.2f s, %zu notes, %zu warnings)\n", name.c_str(), worldSummaryLine(r.def).c_str(),
                s, r.def.notes.size(), r.def.warnings.size());
    const auto e = expected().find(name);
    if (e != expected().end()) {
      EXPECT_EQ(r.def.counts.models, e->second.models) << name;
      EXPECT_EQ(r.def.counts.static_shapes, e->second.static_shapes) << name;
      EXPECT_EQ(r.def.counts.dynamic_bodies, e->second.dynamic_bodies) << name;
    }
    if (name == "gzclassic_friction_demo") {
      EXPECT_TRUE(r.def.gravity.isApprox(Vec3(0, -1, -1)));  // tilted, in <physics> (SDF 1.5)
      const WorldModelDef* box = world_test::model(r.def, "box_01_model");
      ASSERT_NE(box, nullptr);
      EXPECT_TRUE(box->links[0].collisions[0].has_friction);
      EXPECT_EQ(box->links[0].visual_material, "Gazebo/Rocky");  // SDF 1.4's bare <script>
    }
    for (const WorldModelDef& m : r.def.models)
      for (const WorldLinkDef& l : m.links) {
        EXPECT_TRUE(l.pose.p.allFinite() && l.pose.q.coeffs().allFinite()) << name << " " << m.name;
        for (const WorldCollisionDef& c : l.collisions) EXPECT_EQ(geometryError(c.shape.geometry), "") << name;
      }
  }
  EXPECT_EQ(total, 14);
  EXPECT_GE(loaded, 12);
}

TEST(WorldZoo, ThreeThousandShapesLoad) {
  const std::string file = kZoo + "/gz_3k_shapes.world";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " not present";
  const auto t0 = std::chrono::steady_clock::now();
  const WorldLoadResult r = loadWorldFile(file);
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_TRUE(r.ok) << r.error;
  std::printf("gz_3k_shapes: %.3f s\n", s);
  EXPECT_EQ(r.def.counts.dynamic_bodies, 3003);
  // Models parsed once and placed from their own pose: spot checks against the file.
  const WorldModelDef* box0 = world_test::model(r.def, "box_0");
  const WorldModelDef* cyl1 = world_test::model(r.def, "cylinder_1");
  ASSERT_TRUE(box0 && cyl1);
  EXPECT_TRUE(box0->links[0].pose.p.isApprox(Vec3(-750.0, 0, 0.5)));
  EXPECT_TRUE(cyl1->links[0].pose.p.isApprox(Vec3(-748.5, -1.5, 0.5)));
  EXPECT_EQ(cyl1->links[0].mass, 2.0);
  EXPECT_EQ(cyl1->links[0].collisions[0].shape.geometry.type, ShapeType::Cylinder);
  EXPECT_TRUE(cyl1->links[0].has_color);
  EXPECT_EQ(cyl1->links[0].color[1], 1.0);  // green
}

TEST(WorldZoo, AbsoluteIncludeMappedToItsLastComponent) {
  const std::string file = kZoo + "/unitree_stairs.world";
  if (!std::filesystem::exists(file)) GTEST_SKIP() << file << " not present";
  WorldLoadOptions o;
  o.model_paths = {kZoo + "/models"};
  o.strict = true;
  const WorldLoadResult r = loadWorldFile(file, o);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_TRUE(world_test::contains(r.def.warnings, "absolute model URI model:///home/unitree/"));
  EXPECT_EQ(r.def.counts.unresolved, 0);
}
