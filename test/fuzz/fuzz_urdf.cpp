// libFuzzer target: arbitrary bytes as URDF text to loadUrdfString. A refused file must say why;
// a loaded one must be a consistent RagdollDef (indices in range, finite numbers, positive
// masses) that spawns on a ground plane and steps with a finite state. Meshes are not loaded
// (load_meshes = false): a fuzzed file name could point anywhere on this machine (/dev/zero);
// the fallback primitives are fuzzed instead. Built by scripts/fuzz.sh (make fuzz, make test).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "ragdoll_sim/drop_check.hpp"
#include "ragdoll_sim/urdf_loader.hpp"

#define FUZZ_TARGET_NAME "fuzz_urdf"
#include "fuzz_check.hpp"

using namespace ragdoll_sim;

namespace {

using fuzz::finite;

void checkShape(const LinkDef& l, const ShapeDef& s) {
  const Geometry& g = s.geometry;
  FUZZ_CHECK(finite(s.local), "link '%s': shape pose", l.name.c_str());
  FUZZ_CHECK(std::isfinite(g.radius) && std::isfinite(g.half_height) && g.half_extents.allFinite(),
             "link '%s': shape size", l.name.c_str());
  FUZZ_CHECK(g.type != ShapeType::ConvexHull || g.hull, "link '%s': hull without data",
             l.name.c_str());
  FUZZ_CHECK(std::isfinite(s.material.static_friction) && std::isfinite(s.material.kinetic_friction),
             "link '%s': friction", l.name.c_str());
}

void checkDef(const RagdollDef& def) {
  const int n = static_cast<int>(def.links.size());
  FUZZ_CHECK(n > 0, "a loaded ragdoll has no links");
  FUZZ_CHECK(def.root >= 0 && def.root < n, "root %d of %d links", def.root, n);
  for (const LinkDef& l : def.links) {
    FUZZ_CHECK(std::isfinite(l.mass) && l.mass > 0, "link '%s': mass %g", l.name.c_str(), l.mass);
    FUZZ_CHECK(l.com.allFinite() && l.inertia.allFinite(), "link '%s': com / inertia",
               l.name.c_str());
    FUZZ_CHECK(finite(l.rest_pose), "link '%s': rest pose", l.name.c_str());
    for (const ShapeDef& s : l.shapes) checkShape(l, s);
  }
  for (const RagdollJointDef& j : def.joints) {
    FUZZ_CHECK(j.parent >= 0 && j.parent < n && j.child >= 0 && j.child < n && j.parent != j.child,
               "joint '%s': parent %d child %d of %d links", j.name.c_str(), j.parent, j.child, n);
    FUZZ_CHECK(finite(j.frame_parent) && finite(j.frame_child), "joint '%s': frames",
               j.name.c_str());
    const size_t axes = static_cast<size_t>(jointAxisCount(j.kind));
    FUZZ_CHECK(j.axes.size() >= axes, "joint '%s': %zu axes for %zu angles", j.name.c_str(),
               j.axes.size(), axes);
    for (const Vec3& a : j.axes) FUZZ_CHECK(a.allFinite(), "joint '%s': axis", j.name.c_str());
    if (j.limited)
      for (size_t k = 0; k < axes; ++k)
        FUZZ_CHECK(k < j.lower.size() && k < j.upper.size() && j.lower[k] <= j.upper[k],
                   "joint '%s': limits of axis %zu", j.name.c_str(), k);
  }
  for (const auto& p : def.no_collide)
    FUZZ_CHECK(p.first >= 0 && p.first < n && p.second >= 0 && p.second < n,
               "no_collide pair (%d, %d) of %d links", p.first, p.second, n);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  UrdfLoadOptions options;
  options.load_meshes = false;
  options.package_paths = {"/nonexistent"};  // not $ROS_PACKAGE_PATH
  const UrdfLoadResult r = loadUrdfString(xml, options);
  if (!r.ok) {
    FUZZ_CHECK(!r.error.empty(), "refused without an error message");
    return 0;
  }
  checkDef(r.def);
  // Big fuzzed robots would only slow the search down; the drop is 20 steps (node defaults).
  if (r.def.links.size() > 64) return 0;
  DropSettings drop;
  drop.seconds = 0.02;
  const DropReport rep = dropTest(r.def, drop);
  FUZZ_CHECK(rep.finite, "the drop went non-finite after %g s", rep.seconds);
  return 0;
}
