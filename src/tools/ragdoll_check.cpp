// ragdoll_check <file.urdf> [--seconds S] [--no-drop]: what the URDF loader builds from a file
// (bodies, masses, shapes and which were approximated, joints and how each URDF joint was
// mapped, excluded collision pairs, notes and warnings), then a drop test (drop_check.hpp) and
// one key=value summary line. No ROS master needed.
// ragdoll_check --world FILE [MODEL.urdf] [--spawn X Y Z] [--strict]: what the SDF world loader
// builds from a world file, as one line "world=NAME status=ok models=N static_shapes=S
// dynamic_bodies=D skipped=K unresolved=U", its notes and warnings, then a drop of the model (the
// bundled ragdoll by default) into it through a ROS-free Scene (world_check.hpp).
// --injury (with or without --world): the drop through a Scene, then the head's injury reports
// (injury_check.hpp, docs/injury.md): peak g, HIC15 / HIC36 with their windows, peak angular
// acceleration, peak neck force and torque.
// The drop's verdict (judgeDrop: fell through, joints stretched, exploded, NaN, not at rest) ends
// the summary line as verdict=pass|fail, after one "reason: ..." line per broken rule.
// Exit: 0 loaded (and the drop passed), 1 refused (by a loader, or the spawn), 2 bad usage, 3 the
// drop failed its verdict.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <string>

#include "ragdoll_sim/drop_check.hpp"
#include "ragdoll_sim/urdf_loader.hpp"
#include "ragdoll_sim/world_file.hpp"
#include "world_check.hpp"

using namespace ragdoll_sim;

namespace {

std::string shapeText(const ShapeDef& s) {
  const Geometry& g = s.geometry;
  char buf[160];
  switch (g.type) {
    case ShapeType::Sphere:
      if (g.radius == 0)
        std::snprintf(buf, sizeof buf, "point");
      else
        std::snprintf(buf, sizeof buf, "sphere r=%.3g", g.radius);
      break;
    case ShapeType::Capsule:
      std::snprintf(buf, sizeof buf, "capsule r=%.3g l=%.3g", g.radius, 2 * g.half_height);
      break;
    case ShapeType::Cylinder:
      std::snprintf(buf, sizeof buf, "cylinder r=%.3g l=%.3g", g.radius, 2 * g.half_height);
      break;
    case ShapeType::Box:
      std::snprintf(buf, sizeof buf, "box %.3gx%.3gx%.3g", 2 * g.half_extents.x(),
                    2 * g.half_extents.y(), 2 * g.half_extents.z());
      break;
    case ShapeType::ConvexHull:
      std::snprintf(buf, sizeof buf, "hull %zu vertices", g.hull ? g.hull->vertices.size() : size_t(0));
      break;
    default: std::snprintf(buf, sizeof buf, "%s", shapeTypeName(g.type));
  }
  return buf;
}

bool approximated(const std::string& source) {
  return source.find("unresolved") != std::string::npos || source.find("visual") != std::string::npos ||
         source.find("hull") != std::string::npos;
}

int usage() {
  std::fprintf(stderr,
               "usage: ragdoll_check <file.urdf> [--seconds S] [--no-drop]\n"
               "       ragdoll_check --world FILE [MODEL.urdf] [--spawn X Y Z] [--strict] [--seconds S]"
               " [--no-drop] [--injury]\n"
               "       ragdoll_check --injury [MODEL.urdf] [--spawn X Y Z] [--seconds S]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string file, world;
  DropSettings drop;
  bool run_drop = true, strict = false, injury = false;
  std::optional<Vec3> spawn;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--world" && i + 1 < argc) {
      world = argv[++i];
    } else if (a == "--spawn" && i + 3 < argc) {
      Vec3 p;
      for (int k = 0; k < 3; ++k) {
        char* end = nullptr;
        p[k] = std::strtod(argv[++i], &end);
        if (end == argv[i] || *end != '\0') return usage();
      }
      spawn = p;  // a non-finite one is the Scene's to refuse (exit 1)
    } else if (a == "--injury") {
      injury = true;
    } else if (a == "--strict") {
      strict = true;
    } else if (a == "--seconds" && i + 1 < argc) {
      drop.seconds = std::atof(argv[++i]);
      if (!(drop.seconds > 0)) return usage();
    } else if (a == "--no-drop") {
      run_drop = false;
    } else if (a.rfind("--", 0) == 0 || !file.empty()) {
      return usage();
    } else {
      file = a;
    }
  }
  if (!world.empty() || injury) {
    if (injury && !run_drop) return usage();
    WorldCheckArgs w;
    w.world = world;
    w.model = file;
    w.spawn = spawn;
    w.strict = strict;
    w.drop = run_drop;
    w.injury = injury;
    w.settings = drop;
    return checkWorld(w, argv[0]);
  }
  if (file.empty() || strict || spawn) return usage();
  const std::string base = std::filesystem::path(file).filename().string();

  const UrdfLoadResult r = loadUrdfFile(file);
  if (!r.ok) {
    std::printf("ragdoll_check: %s: REFUSED\nerror: %s\n", file.c_str(), r.error.c_str());
    std::printf("summary: file=%s status=refused\n", base.c_str());
    std::fprintf(stderr, "ragdoll_check: %s\n", r.error.c_str());
    return 1;
  }
  const RagdollDef& d = r.def;
  int shapes = 0, approx = 0, points = 0;
  std::printf("ragdoll_check: %s: robot '%s', %zu bodies, %zu joints, %.3f kg, root '%s'\n",
              file.c_str(), d.name.c_str(), d.links.size(), d.joints.size(), d.totalMass(),
              d.links[d.root].name.c_str());
  std::printf("bodies:\n");
  for (const LinkDef& l : d.links) {
    std::printf("  %-24s %9.4f kg  com (%.3f %.3f %.3f)  %zu shape(s)\n", l.name.c_str(), l.mass,
                l.com.x(), l.com.y(), l.com.z(), l.shapes.size());
    for (size_t k = 0; k < l.shapes.size(); ++k) {
      const std::string src = k < l.shape_sources.size() ? l.shape_sources[k] : "";
      const bool ap = approximated(src);
      ++shapes;
      approx += ap;
      points += l.shapes[k].geometry.type == ShapeType::Sphere && l.shapes[k].geometry.radius == 0;
      std::printf("      %-28s %s%s%s\n", shapeText(l.shapes[k]).c_str(), ap ? "APPROXIMATED: " : "",
                  src.c_str(),
                  k < l.shape_friction.size() && l.shape_friction[k] >= 0
                      ? (" mu=" + std::to_string(l.shape_friction[k])).c_str() : "");
    }
  }
  std::printf("joints:\n");
  for (const RagdollJointDef& j : d.joints) {
    std::string from;
    for (const std::string& s : j.source_joints) from += (from.empty() ? "" : ", ") + s;
    std::string via;
    for (const std::string& s : j.chain_links) via += (via.empty() ? "" : ", ") + s;
    std::printf("  %-9s %-28s %s -> %s  from URDF %s%s%s%s\n", jointKindName(j.kind), j.name.c_str(),
                d.links[j.parent].name.c_str(), d.links[j.child].name.c_str(), from.c_str(),
                via.empty() ? "" : " through massless ", via.c_str(), j.limited ? "" : " (unlimited)");
  }
  std::printf("excluded collision pairs (%zu):", d.no_collide.size());
  for (const auto& [a, b] : d.no_collide)
    std::printf(" %s/%s", d.links[a].name.c_str(), d.links[b].name.c_str());
  std::printf("\nnotes (%zu):\n", d.notes.size());
  for (const std::string& n : d.notes) std::printf("  %s\n", n.c_str());
  std::printf("warnings (%zu):\n", d.warnings.size());
  for (const std::string& w : d.warnings) std::printf("  %s\n", w.c_str());

  char summary[512];
  std::snprintf(summary, sizeof summary,
                "summary: file=%s status=ok bodies=%zu joints=%zu mass_kg=%.3f shapes=%d points=%d "
                "approximated=%d warnings=%zu",
                base.c_str(), d.links.size(), d.joints.size(), d.totalMass(), shapes, points, approx,
                d.warnings.size());
  if (!run_drop) {
    std::printf("%s\n", summary);
    return 0;
  }
  const DropReport rep = dropTest(d, drop);
  std::printf("drop: %.2f s of sim time from root z=%.3f m (lowest point %.3f m up)\n", rep.seconds,
              rep.spawn_z, drop.clearance);
  const DropVerdict verdict = judgeDrop(rep, dropRules(drop));
  for (const std::string& reason : verdict.reasons) std::printf("reason: %s\n", reason.c_str());
  std::printf("%s %s\n", summary, dropMetrics(rep, verdict).c_str());
  return verdict.pass ? 0 : 3;
}
