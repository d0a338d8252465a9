// See world_check.hpp.
#include "world_check.hpp"
#include "injury_check.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <vector>

#include "mesh_loader.hpp"
#include "ragdoll_sim/material_file.hpp"
#include "ragdoll_sim/scene.hpp"
#include "ragdoll_sim/urdf_loader.hpp"
#include "ragdoll_sim/world_file.hpp"

namespace ragdoll_sim {

namespace fs = std::filesystem;

namespace {

// Scene messages: warnings and errors on stderr, so that stdout stays the report.
struct StderrListener : SceneListener {
  void message(const SceneMessage& m) override {
    if (m.level == SceneMessage::Level::Warn || m.level == SceneMessage::Level::Error)
      std::fprintf(stderr, "ragdoll_check: %s\n", m.text.c_str());
  }
};

void printLines(const char* title, const std::vector<std::string>& lines) {
  std::printf("%s (%zu):\n", title, lines.size());
  for (const std::string& l : lines) std::printf("  %s\n", l.c_str());
}

// Height under the origin of a static plane facing up (-inf for one that does not).
double planeHeight(const WorldLinkDef& l, const WorldCollisionDef& c) {
  const Geometry& g = c.shape.geometry;
  const Transform w = l.pose * c.shape.local;
  const Vec3 n = w.q * g.normal;
  return n.z() > 0.5 ? n.dot(w.apply(g.normal * g.offset)) / n.z() : -std::numeric_limits<double>::infinity();
}

// The highest static point anywhere, not only over the origin, because a falling model spans
// more than that column (a ground plane counts at its height under the origin; a world without
// one has the default ground at z = 0). With `planes_only`, the ground a model may fall to
// without falling through.
double staticHeight(const WorldFileDef& def, bool planes_only) {
  double top = -std::numeric_limits<double>::infinity();
  bool plane = false;
  for (const WorldModelDef& m : def.models)
    for (const WorldLinkDef& l : m.links) {
      if (!l.is_static) continue;
      for (const WorldCollisionDef& c : l.collisions) {
        if (c.shape.geometry.type != ShapeType::Plane) {
          if (!planes_only) top = std::max(top, highestPoint(c.shape, l.pose));
          continue;
        }
        plane = true;
        top = std::max(top, planeHeight(l, c));
      }
    }
  if (!plane) top = std::max(top, 0.0);
  return std::isfinite(top) ? top : 0.0;
}

}  // namespace

std::string packageFile(const std::string& relative, const char* argv0) {
  std::string why;
  const std::string found =
      mesh::resolveUri("package://ragdoll_sim/" + relative, "", mesh::packagePathFromEnv(), &why);
  std::error_code ec;
  if (!found.empty() && fs::is_regular_file(found, ec)) return found;
  std::vector<fs::path> candidates;
  const fs::path exe = fs::canonical("/proc/self/exe", ec);
  if (!ec)  // <prefix>/lib/ragdoll_sim/ragdoll_check
    candidates.push_back(exe.parent_path().parent_path().parent_path() / "share/ragdoll_sim" / relative);
  if (argv0) candidates.push_back(fs::path(argv0).parent_path() / "../../share/ragdoll_sim" / relative);
#ifdef RAGDOLL_SIM_SOURCE_DIR
  candidates.push_back(fs::path(RAGDOLL_SIM_SOURCE_DIR) / relative);
#endif
  for (const fs::path& p : candidates)
    if (fs::is_regular_file(p, ec)) return p.lexically_normal().string();
  return "";
}

int checkWorld(const WorldCheckArgs& args, const char* argv0) {
  WorldLoadResult r;
  if (!args.world.empty()) {
    WorldLoadOptions options;
    options.strict = args.strict;
    r = loadWorldFile(args.world, options);
    if (!r.ok) {
      std::fprintf(stderr, "ragdoll_check: %s: %s\n", args.world.c_str(), r.error.c_str());
      return 1;
    }
    std::printf("%s\n", worldSummaryLine(r.def).c_str());
    printLines("notes", r.def.notes);
    printLines("warnings", r.def.warnings);
    if (!args.drop) return 0;
  } else {
    r.ok = true;
    r.def.name = "ground";  // the Scene's default plane alone
  }

  const std::string model = args.model.empty() ? packageFile("urdf/ragdoll.urdf", argv0) : args.model;
  if (model.empty()) {
    std::fprintf(stderr,
                 "ragdoll_check: the bundled ragdoll (urdf/ragdoll.urdf) was not found; name a URDF\n");
    return 1;
  }
  const UrdfLoadResult u = loadUrdfFile(model);
  if (!u.ok) {
    std::fprintf(stderr, "ragdoll_check: %s: %s\n", model.c_str(), u.error.c_str());
    return 1;
  }

  SceneDef sd;
  sd.dt_ns = int64_t(std::llround(args.settings.dt * 1e9));
  sd.world.solver.substeps = args.settings.substeps;
  sd.spawn_overlap = SpawnOverlap::Lift;
  // The node's table: the same file it loads into ~materials and ~link_materials.
  const std::string table_file = packageFile("config/materials.yaml", argv0);
  if (table_file.empty()) {
    std::fprintf(stderr, "ragdoll_check: the materials table (config/materials.yaml) was not found\n");
    return 1;
  }
  const MaterialFileResult table = loadMaterialFile(table_file);
  if (!table.ok) {
    std::fprintf(stderr, "ragdoll_check: %s\n", table.error.c_str());
    return 1;
  }
  sd.world.materials = table.table;
  sd.link_materials = table.link_materials;
  std::string error;
  StderrListener listener;
  Scene scene(sd, &listener);
  if (!args.world.empty() && !scene.loadWorld(r.def, &error)) {
    std::fprintf(stderr, "ragdoll_check: %s: %s\n", args.world.c_str(), error.c_str());
    return 1;
  }
  Vec3 at;
  if (args.spawn) {
    at = *args.spawn;
  } else {
    at = Vec3(0, 0, staticHeight(r.def, false) + args.settings.clearance - restLowestPoint(u.def));
  }
  SpawnDef spawn;
  spawn.name = "ragdoll";
  for (int i = 2; scene.find(spawn.name) >= 0; ++i) spawn.name = "ragdoll_" + std::to_string(i);
  spawn.def = u.def;
  spawn.pose = Transform(at, Quat::Identity());
  if (scene.addRagdoll(spawn, &error) != SpawnResult::Added || !scene.start(&error)) {
    std::fprintf(stderr, "ragdoll_check: spawn at (%g %g %g) refused: %s\n", at.x(), at.y(), at.z(),
                 error.c_str());
    return 1;
  }
  const int k = scene.find(spawn.name);
  std::vector<InjuryReport> falls;  // that ended during the drop
  const DropReport rep = measureDrop(scene.world(), scene.bodies(k), scene.def(k), [&] {
    scene.step();
    for (const InjuryReport& f : scene.injuryReports()) falls.push_back(f);
  }, args.settings);
  const Vec3 p = scene.spawnPose(k).p;
  std::printf("drop: %s into world '%s', %.2f s of sim time from root (%.3f %.3f %.3f)\n",
              fs::path(model).filename().c_str(), r.def.name.c_str(), rep.seconds, p.x(), p.y(), p.z());
  DropReport judged = rep;
  judged.spawn_z = p.z();
  // A world's stairs, slopes and moving objects may keep a model going: rest is not asked.
  VerdictRules rules = dropRules(args.settings, staticHeight(r.def, true));
  rules.expect_rest = false;
  const DropVerdict verdict = judgeDrop(judged, rules);
  for (const std::string& reason : verdict.reasons) std::printf("reason: %s\n", reason.c_str());
  std::printf("summary: world=%s model=%s status=ok spawn_z_m=%.3f %s\n", r.def.name.c_str(),
              fs::path(model).filename().c_str(), p.z(), dropMetrics(rep, verdict).c_str());
  if (args.injury) {
    if (scene.headLink(k).empty())
      std::printf("injury: no head link found in %s (name one: a link named like 'head')\n",
                  fs::path(model).filename().c_str());
    else
      printInjury(falls, scene.injury(k));
  }
  return verdict.pass ? 0 : 3;
}

std::string dropMetrics(const DropReport& rep, const DropVerdict& verdict) {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "drop_s=%.2f nan=%d max_penetration_mm=%.2f max_anchor_error_mm=%.2f "
                "final_anchor_error_mm=%.2f rest_height_m=%.3f lowest_mm=%.1f min_lowest_mm=%.1f "
                "max_speed=%.3f final_speed=%.3f final_contact_speed=%.3f late_energy_change_j=%.3f "
                "verdict=%s",
                rep.seconds, rep.finite ? 0 : 1, 1e3 * rep.max_penetration, 1e3 * rep.max_anchor_error,
                1e3 * rep.final_anchor_error, rep.rest_height, 1e3 * rep.lowest_point,
                1e3 * rep.min_lowest_point, rep.max_speed, rep.final_speed, rep.final_contact_speed,
                rep.late_energy_change, verdict.pass ? "pass" : "fail");
  return buf;
}

}  // namespace ragdoll_sim
