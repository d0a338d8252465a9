// libFuzzer target: arbitrary bytes as SDF world text to loadWorldString. A refused world must
// say why in one line; a loaded one must be consistent (finite poses, shapes the World accepts,
// joint indices in range, counts that add up). Meshes are not loaded and includes resolve only
// in the fixtures' model folder. Built by scripts/fuzz.sh (make fuzz, make test).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "ragdoll_sim/material.hpp"
#include "ragdoll_sim/world_file.hpp"

#define FUZZ_TARGET_NAME "fuzz_world"
#include "fuzz_check.hpp"

using namespace ragdoll_sim;

namespace {

using fuzz::finite;

void checkModel(const WorldModelDef& m, WorldCounts* counts) {
  const int n = static_cast<int>(m.links.size());
  FUZZ_CHECK(finite(m.pose), "model '%s': pose", m.name.c_str());
  for (const WorldLinkDef& l : m.links) {
    FUZZ_CHECK(finite(l.pose), "link '%s': pose", l.name.c_str());
    if (!l.is_static)
      FUZZ_CHECK(std::isfinite(l.mass) && l.mass > 0 && l.com.allFinite() && l.inertia.allFinite(),
                 "link '%s': mass properties", l.name.c_str());
    for (const WorldCollisionDef& c : l.collisions) {
      FUZZ_CHECK(finite(c.shape.local), "collision '%s': pose", c.name.c_str());
      FUZZ_CHECK(geometryError(c.shape.geometry).empty(), "collision '%s': %s", c.name.c_str(),
                 geometryError(c.shape.geometry).c_str());
      FUZZ_CHECK(materialError(c.shape.material).empty(), "collision '%s': material", c.name.c_str());
    }
    if (l.is_static) counts->static_shapes += static_cast<int>(l.collisions.size());
    else ++counts->dynamic_bodies;
  }
  for (const RagdollJointDef& j : m.joints) {
    FUZZ_CHECK(j.parent >= -1 && j.parent < n && j.child >= 0 && j.child < n,
               "joint '%s': parent %d child %d of %d links", j.name.c_str(), j.parent, j.child, n);
    FUZZ_CHECK(finite(j.frame_parent) && finite(j.frame_child), "joint '%s': frames", j.name.c_str());
    for (const Vec3& a : j.axes) FUZZ_CHECK(a.allFinite(), "joint '%s': axis", j.name.c_str());
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string xml(reinterpret_cast<const char*>(data), size);
  WorldLoadOptions options;
  options.load_meshes = false;
  options.model_paths = {RAGDOLL_SIM_SOURCE_DIR "/test/world_file/fixtures/models"};
  options.package_paths = {"/nonexistent"};
  options.max_sdf_megabytes = 256;  // libFuzzer's memory limit is 2 GB, and ASan doubles it
  const WorldLoadResult r = loadWorldString(xml, options);
  if (!r.ok) {
    FUZZ_CHECK(!r.error.empty(), "refused without an error message");
    FUZZ_CHECK(r.error.find('\n') == std::string::npos, "error of several lines: %s", r.error.c_str());
    return 0;
  }
  FUZZ_CHECK(r.def.gravity.allFinite(), "gravity");
  WorldCounts counts;
  for (const WorldModelDef& m : r.def.models) checkModel(m, &counts);
  FUZZ_CHECK(r.def.counts.models == static_cast<int>(r.def.models.size()), "model count");
  FUZZ_CHECK(counts.static_shapes == r.def.counts.static_shapes &&
                 counts.dynamic_bodies == r.def.counts.dynamic_bodies,
             "counts %d/%d vs %d/%d", counts.static_shapes, counts.dynamic_bodies,
             r.def.counts.static_shapes, r.def.counts.dynamic_bodies);
  return 0;
}
