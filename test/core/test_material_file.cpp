// config/materials.yaml through loadMaterialFile: the 15 rows of the issue's friction table
// resolve to the table's numbers (ranges -> middle, an empty column -> the other), pairs not
// listed combine, and a bad file is refused with a message naming the entry and its line.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <fstream>

#include "ragdoll_sim/material_file.hpp"

using namespace ragdoll_sim;

namespace {

const std::string kShipped = std::string(RAGDOLL_SIM_SOURCE_DIR) + "/config/materials.yaml";

Material pair(const MaterialTable& t, const std::string& a, const std::string& b) {
  const int ia = t.find(a), ib = t.find(b);
  EXPECT_GE(ia, 1) << a;
  EXPECT_GE(ib, 1) << b;
  if (ia < 1 || ib < 1) return Material();
  EXPECT_GT(t.pairGiven(ia, ib), 0) << a << "/" << b << " is not listed";
  return t.resolve(t.material(ia), t.material(ib));
}

}  // namespace

TEST(MaterialFile, ShippedTableIsTheIssuesFifteenRows) {
  const MaterialFileResult r = loadMaterialFile(kShipped);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(YAML::LoadFile(kShipped)["materials"]["pairs"].size(), 15u);
  struct Row {
    const char* a;
    std::vector<const char*> b;
    double mu_s, mu_k;
  };
  const std::vector<const char*> metals = {"metal", "steel", "aluminum", "copper"};
  const std::vector<Row> rows = {
      {"aluminum", {"steel"}, 0.61, 0.47},
      {"copper", {"steel"}, 0.53, 0.36},
      {"leather", metals, 0.4, 0.2},
      {"rubber", {"asphalt"}, 0.9, 0.65},          // kinetic 0.5-0.8
      {"rubber", {"asphalt_wet"}, 0.5, 0.5},       // - / 0.25-0.75
      {"rubber", {"concrete"}, 1.0, 0.725},        // kinetic 0.6-0.85
      {"rubber", {"concrete_wet"}, 0.30, 0.60},    // kinetic 0.45-0.75
      {"steel", {"steel"}, 0.80, 0.80},
      {"steel", {"teflon"}, 0.04, 0.04},
      {"teflon", {"teflon"}, 0.04, 0.04},
      {"wood", {"concrete"}, 0.62, 0.62},
      {"wood", metals, 0.4, 0.4},                  // clean metal, static 0.2-0.6
      {"wood", {"ice"}, 0.05, 0.05},
      {"wood", {"wood"}, 0.375, 0.375},            // static 0.25-0.5
      {"waxed_wood", {"dry_snow"}, 0.04, 0.04},
  };
  int listed = 0;
  for (const Row& row : rows)
    for (const char* b : row.b) {
      for (const auto& [x, y] : {std::make_pair(row.a, b), std::make_pair(b, row.a)}) {
        const Material m = pair(r.table, x, y);
        EXPECT_DOUBLE_EQ(m.static_friction, row.mu_s) << x << "/" << y;
        EXPECT_DOUBLE_EQ(m.kinetic_friction, row.mu_k) << x << "/" << y;
      }
      ++listed;
    }
  // Nothing else is listed: 15 rows, two of them for the four metal surfaces.
  int given = 0;
  for (int i = 1; i < r.table.size(); ++i)
    for (int j = i; j < r.table.size(); ++j) given += r.table.pairGiven(i, j) > 0;
  EXPECT_EQ(given, listed);
  EXPECT_EQ(listed, 15 + 2 * 3);

  // Friction only: restitution and rolling resistance combine from the surfaces (max).
  const MaterialTable& t = r.table;
  const Material sole = pair(t, "rubber", "concrete");
  EXPECT_DOUBLE_EQ(sole.restitution, std::max(t.material(t.find("rubber")).restitution,
                                              t.material(t.find("concrete")).restitution));
  EXPECT_DOUBLE_EQ(sole.rolling_resistance, t.material(t.find("rubber")).rolling_resistance);
  // A pair not listed follows the combine rule (geometric mean).
  const Material a = t.material(t.find("leather")), b = t.material(t.find("concrete"));
  EXPECT_DOUBLE_EQ(t.resolve(a, b).kinetic_friction, std::sqrt(a.kinetic_friction * b.kinetic_friction));

  // The bundled ragdoll: rubber soles, the rest in leather; exact names before "*".
  const std::vector<std::pair<std::string, std::string>> links = {
      {"foot_l", "rubber"}, {"foot_r", "rubber"}, {"*", "leather"}};
  EXPECT_EQ(r.link_materials, links);
}

TEST(MaterialFile, ListsAndPartialPairs) {
  const MaterialFileResult r = loadMaterialString(R"(
materials:
  combine: {friction: min, restitution: average}
  surfaces:
    a: [0.5, 0.4, 0.2]
    b: [0.9, 0.8, 0.6, 0.1]
    c: [0.7, 0.6, 0.4]
  pairs:
    - [a, [b, c], 0.3, 0.2]
    - [b, b, 0.1, 0.1, 0.9]
    - [c, c, 1, 1, 0, 0.3]
link_materials: {"*": c, z: a, y: b}
)");
  ASSERT_TRUE(r.ok) << r.error;
  const MaterialTable& t = r.table;
  const Material ab = pair(t, "a", "b"), bb = pair(t, "b", "b"), cc = pair(t, "c", "c");
  EXPECT_DOUBLE_EQ(ab.kinetic_friction, 0.2);
  EXPECT_DOUBLE_EQ(ab.restitution, 0.4);            // average of 0.2 and 0.6
  EXPECT_DOUBLE_EQ(ab.rolling_resistance, 0.1);     // max
  EXPECT_DOUBLE_EQ(pair(t, "c", "a").static_friction, 0.3);
  EXPECT_DOUBLE_EQ(bb.restitution, 0.9);
  EXPECT_DOUBLE_EQ(bb.rolling_resistance, 0.1);     // left out: from the surfaces
  EXPECT_DOUBLE_EQ(cc.rolling_resistance, 0.3);
  EXPECT_DOUBLE_EQ(cc.restitution, 0.0);
  EXPECT_EQ(t.friction_rule, CombineRule::Min);
  const std::vector<std::pair<std::string, std::string>> links = {{"y", "b"}, {"z", "a"}, {"*", "c"}};
  EXPECT_EQ(r.link_materials, links);
}

TEST(MaterialFile, BadFilesNameTheEntry) {
  const std::string head = "materials:\n  surfaces:\n    ice: [0.1, 0.03, 0.1]\n    rubber: [1, 0.8, 0.3]\n";
  struct Case {
    std::string text;
    std::vector<std::string> expect;  // substrings of the error
  };
  const std::vector<Case> cases = {
      {"materials: [1, 2]", {"materials (line 1) must be a dictionary"}},
      {"material:\n  surfaces: {}\n", {"line 1", "unknown key 'material'"}},
      {"link_materials: {}\n", {"no materials: key"}},
      {"materials: {surfaces: {ice: [0.1, 0.03]}}", {"materials/surfaces/ice", "line 1", "restitution"}},
      {"materials:\n  surfaces:\n    ice: [0.1, -0.03, 0.1]\n", {"materials/surfaces/ice (line 3)", ">= 0"}},
      {"materials:\n  surfaces:\n    ice: [0.1, 0.03, 1.5]\n", {"surfaces/ice", "restitution <= 1"}},
      {"materials:\n  surfaces:\n    ice: [0.1, 0.03, x]\n", {"surfaces/ice"}},
      {"materials:\n  surfaces:\n    ice: [0.1, 0.03, .nan]\n", {"surfaces/ice"}},
      {"materials:\n  surfaces:\n    ice: [0.1, 0.03, 0.1]\n    ice: [0.2, 0.1, 0.1]\n",
       {"surfaces/ice (line 4) is listed twice"}},
      {"materials:\n  combine: {friction: median}\n", {"materials/combine/friction (line 2)", "geometric_mean"}},
      {"materials:\n  combine: {bounce: max}\n", {"materials/combine", "unknown key 'bounce'"}},
      {"materials:\n  pair: []\n", {"unknown key 'pair'", "known: combine, surfaces, pairs"}},
      {head + "  pairs:\n    - [ice, rubber, 0.1]\n", {"materials/pairs[0] (line 6) must be"}},
      {head + "  pairs:\n    - [ice, rubbr, 0.1, 0.1]\n", {"materials/pairs[0] (line 6) names 'rubbr'", "materials/surfaces"}},
      {head + "  pairs:\n    - [ice, [rubber, wood], 0.1, 0.1]\n", {"pairs[0]", "names 'wood'"}},
      {head + "  pairs:\n    - [ice, [], 0.1, 0.1]\n", {"pairs[0]", "must be"}},
      {head + "  pairs:\n    - [ice, rubber, 0.1, 0.1, 0.2, 0.1, 9, 1, 2]\n", {"pairs[0]", "must be"}},
      {head + "  pairs:\n    - [ice, rubber, 0.1, 0.1]\n    - [rubber, [ice], 0.2, 0.2]\n",
       {"materials/pairs[1] (line 7) lists the pair 'rubber'/'ice' again", "first in", "pairs[0] (line 6)"}},
      {head + "link_materials:\n  foot_l: rubbr\n", {"link_materials/foot_l (line 6) names 'rubbr'"}},
      {head + "link_materials:\n  foot_l: [rubber]\n", {"link_materials/foot_l", "must be a surface name"}},
      {head + "link_materials: rubber\n", {"link_materials (line 5) must be a dictionary"}},
      {"materials: {surfaces: [", {"line", "not YAML"}},
      {"", {"must be a dictionary"}},
  };
  for (const Case& c : cases) {
    const MaterialFileResult r = loadMaterialString(c.text, "m.yaml");
    EXPECT_FALSE(r.ok) << c.text;
    EXPECT_EQ(r.error.rfind("m.yaml", 0), 0u) << r.error;
    for (const std::string& e : c.expect)
      EXPECT_NE(r.error.find(e), std::string::npos) << "expected '" << e << "' in: " << r.error;
    EXPECT_EQ(r.error.find('\n'), std::string::npos) << r.error;
  }
}

TEST(MaterialFile, FilesThatAreNotRegularAreRefused) {
  for (const char* path : {"/dev/zero", "/nonexistent/materials.yaml", "/tmp"}) {
    const MaterialFileResult r = loadMaterialFile(path);
    EXPECT_FALSE(r.ok) << path;
    EXPECT_NE(r.error.find(path), std::string::npos) << r.error;
  }
}
