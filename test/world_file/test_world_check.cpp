// `ragdoll_check --world FILE [MODEL] [--spawn X Y Z]`: the world line, then the model dropped
// into the world through a Scene with the drop metrics and verdict of the URDF mode; refusals
// exit 1, bad usage 2, a failed drop 3.
#include <cmath>
#include <cstdlib>
#include <map>
#include <sstream>

#include "world_test_util.hpp"

using namespace world_test;

namespace {

std::string shipped(const std::string& name) {
  return std::string(RAGDOLL_SIM_SOURCE_DIR) + "/worlds/" + name + ".world";
}

const std::string kRagdoll = std::string(RAGDOLL_SIM_SOURCE_DIR) + "/urdf/ragdoll.urdf";

// The key=value pairs of the line starting with "summary:".
std::map<std::string, std::string> summary(const std::string& out) {
  std::map<std::string, std::string> kv;
  const size_t at = out.find("summary: ");
  if (at == std::string::npos) return kv;
  std::istringstream line(out.substr(at + 9, out.find('\n', at) - at - 9));
  std::string item;
  while (line >> item) {
    const size_t eq = item.find('=');
    if (eq != std::string::npos) kv[item.substr(0, eq)] = item.substr(eq + 1);
  }
  return kv;
}

double number(const std::map<std::string, std::string>& kv, const std::string& key) {
  const auto it = kv.find(key);
  return it == kv.end() ? std::nan("") : std::atof(it->second.c_str());
}

}  // namespace

// Each shipped world: its line, then the bundled ragdoll dropped above its highest static point
// comes to rest on it whole.
TEST(WorldCheckTool, ShippedWorldsLineAndDrop) {
  const std::map<std::string, std::string> lines = {
      {"stairs", "world=stairs status=ok models=2 static_shapes=9 dynamic_bodies=0 skipped=0 unresolved=0"},
      {"ramp", "world=ramp status=ok models=2 static_shapes=2 dynamic_bodies=0 skipped=0 unresolved=0"},
      {"playground",
       "world=playground status=ok models=12 static_shapes=11 dynamic_bodies=8 skipped=0 unresolved=0"},
  };
  for (const auto& [name, line] : lines) {
    const ToolRun r = ragdollCheck("--world " + shipped(name) + " " + kRagdoll);
    std::printf("%s\n", r.out.substr(0, r.out.find('\n')).c_str());
    std::printf("%s", r.out.substr(r.out.find("summary:")).c_str());
    EXPECT_EQ(r.code, 0) << r.out;
    EXPECT_EQ(r.out.rfind(line + "\nnotes (0):\nwarnings (0):\n", 0), 0u) << r.out;
    const auto kv = summary(r.out);
    EXPECT_EQ(kv.count("world") ? kv.at("world") : "", name) << r.out;
    EXPECT_EQ(kv.count("status") ? kv.at("status") : "", "ok") << r.out;
    EXPECT_EQ(kv.count("verdict") ? kv.at("verdict") : "", "pass") << r.out;
    EXPECT_EQ(r.out.find("reason:"), std::string::npos) << r.out;
    EXPECT_EQ(number(kv, "nan"), 0) << r.out;
    EXPECT_NEAR(number(kv, "drop_s"), 3.0, 1e-9) << r.out;
    EXPECT_LT(number(kv, "max_penetration_mm"), 10.0) << r.out;
    EXPECT_LT(number(kv, "max_anchor_error_mm"), 10.0) << r.out;
    // Dropped from above the highest static point: it fell, and it is not under the ground.
    EXPECT_LT(number(kv, "rest_height_m"), number(kv, "spawn_z_m")) << r.out;
    EXPECT_GT(number(kv, "lowest_mm"), -10.0) << r.out;
  }
}

// The bundled ragdoll is the default model; --spawn places its root link.
TEST(WorldCheckTool, DefaultModelAndSpawn) {
  const ToolRun r = ragdollCheck("--world " + shipped("ramp") + " --spawn 2 0 3 --seconds 0.5");
  EXPECT_EQ(r.code, 0) << r.out;
  const auto kv = summary(r.out);
  EXPECT_EQ(kv.count("model") ? kv.at("model") : "", "ragdoll.urdf") << r.out;
  EXPECT_NE(r.out.find("from root (2.000 0.000 3.000)"), std::string::npos) << r.out;
  EXPECT_NEAR(number(kv, "spawn_z_m"), 3.0, 1e-9) << r.out;
}

// A spawn the Scene refuses, a model that is not there: exit 1 with one message naming it.
TEST(WorldCheckTool, RefusedSpawnOrModelExitsOne) {
  const ToolRun nan = ragdollCheck("--world " + shipped("ramp") + " --spawn 0 nan 1");
  EXPECT_EQ(nan.code, 1) << nan.out;
  EXPECT_NE(nan.out.find("spawn at (0 nan 1) refused"), std::string::npos) << nan.out;
  EXPECT_EQ(nan.out.find("summary:"), std::string::npos) << nan.out;
  const ToolRun far = ragdollCheck("--world " + shipped("ramp") + " --spawn 0 0 1e9");
  EXPECT_EQ(far.code, 1) << far.out;
  EXPECT_NE(far.out.find("refused"), std::string::npos) << far.out;
  const ToolRun missing = ragdollCheck("--world " + shipped("ramp") + " /nonexistent/robot.urdf");
  EXPECT_EQ(missing.code, 1) << missing.out;
  EXPECT_NE(missing.out.find("/nonexistent/robot.urdf"), std::string::npos) << missing.out;
}

// The URDF mode's verdict: a model without collision geometry falls through the world's
// ground plane, which fails the drop (exit 3) with its reason.
TEST(WorldCheckTool, FailedDropExitsThree) {
  const ToolRun r = ragdollCheck("--world " + shipped("ramp") + " " + RAGDOLL_SIM_SOURCE_DIR +
                                 "/test/urdf/fixtures/no_collision.urdf --spawn 8 0 0.3 --seconds 0.5");
  EXPECT_EQ(r.code, 3) << r.out;
  EXPECT_NE(r.out.find("reason: fell through the ground"), std::string::npos) << r.out;
  const auto kv = summary(r.out);
  EXPECT_EQ(kv.count("verdict") ? kv.at("verdict") : "", "fail") << r.out;
}

TEST(WorldCheckTool, BadUsageExitsTwo) {
  for (const std::string& args : {"--world " + shipped("ramp") + " --spawn 0 0",
                                   "--world " + shipped("ramp") + " --spawn 0 x 1",
                                   "--world " + shipped("ramp") + " a.urdf b.urdf",
                                   kRagdoll + " --spawn 0 0 1"}) {
    const ToolRun r = ragdollCheck(args);
    EXPECT_EQ(r.code, 2) << args << ": " << r.out;
    EXPECT_NE(r.out.find("usage:"), std::string::npos) << args << ": " << r.out;
  }
}

// The key=value pairs of the line starting with "injury: status=".
std::map<std::string, std::string> injuryLine(const std::string& out) {
  const size_t at = out.find("injury: status=");
  if (at == std::string::npos) return {};
  return summary("summary: " + out.substr(at + 8, out.find('\n', at) - at - 8) + "\n");
}

// --injury: the bundled ragdoll dropped on the default ground (and into a world): its fall
// ends at rest within the run, with a finite peak above 1 g and HIC windows around the peak.
TEST(WorldCheckTool, InjuryReportOfADrop) {
  const ToolRun r = ragdollCheck("--injury --spawn 0 0 2 --seconds 3.2");
  EXPECT_EQ(r.code, 0) << r.out;
  std::printf("%s", r.out.substr(r.out.find("injury:")).c_str());
  EXPECT_NE(r.out.find("injury: ragdoll 'ragdoll', head 'head', neck 'neck_y+neck_x+neck_z'"),
            std::string::npos) << r.out;
  const auto kv = injuryLine(r.out);
  EXPECT_EQ(kv.count("status") ? kv.at("status") : "", "rest") << r.out;
  const double peak = number(kv, "peak_g"), at = number(kv, "peak_s");
  EXPECT_GT(peak, 5.0) << r.out;
  EXPECT_LT(peak, 1e5) << r.out;
  EXPECT_GT(number(kv, "hic15"), 0.0) << r.out;
  EXPECT_GE(number(kv, "hic36"), number(kv, "hic15")) << r.out;
  EXPECT_LE(number(kv, "hic15_t1"), at) << r.out;
  EXPECT_GE(number(kv, "hic15_t2"), at) << r.out;
  EXPECT_GT(number(kv, "end_s"), at) << r.out;
  EXPECT_LE(number(kv, "end_s"), 3.2) << r.out;
  for (const char* key : {"peak_angular_acceleration", "neck_force_n", "neck_torque_nm"})
    EXPECT_TRUE(std::isfinite(number(kv, key))) << key << ": " << r.out;

  const ToolRun w = ragdollCheck("--world " + shipped("ramp") + " --injury --seconds 0.2");
  EXPECT_EQ(w.code, 0) << w.out;
  const auto wk = injuryLine(w.out);
  EXPECT_EQ(wk.count("status") ? wk.at("status") : "", "running") << w.out;
  EXPECT_TRUE(std::isfinite(number(wk, "peak_g"))) << w.out;
  EXPECT_EQ(ragdollCheck("--injury --no-drop").code, 2);
}
