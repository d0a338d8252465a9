#include "world_startup.hpp"

#include <cmath>

#include <ros/console.h>

#include "ragdoll_sim/world_file.hpp"

namespace ragdoll_sim {
namespace node {

namespace {

bool hasStaticPlane(const WorldFileDef& w) {
  for (const WorldModelDef& m : w.models)
    for (const WorldLinkDef& l : m.links)
      for (const WorldCollisionDef& c : l.collisions)
        if (l.is_static && c.shape.geometry.type == ShapeType::Plane) return true;
  return false;
}

bool gravitySetByUser(const NodeConfig& c) {
  for (const std::string& d : c.differing_from_defaults)
    if (d.rfind("~gravity ", 0) == 0) return true;
  return false;
}

}  // namespace

bool loadStartupWorld(const NodeConfig& c, Scene* scene, std::string* error) {
  if (c.world_file.empty()) return true;
  const std::string where = "~world_file '" + c.world_file + "'";
  WorldLoadOptions options;
  options.strict = c.world_strict;
  const WorldLoadResult r = loadWorldFile(c.world_file, options);
  if (!r.ok) {
    *error = where + (c.world_strict ? " (~world_strict)" : "") + ": " + r.error;
    return false;
  }
  const WorldFileDef& w = r.def;
  // The loader's own step-size note does not know the node's step: the line below replaces it.
  for (const std::string& n : w.notes)
    if (n.rfind("<physics><max_step_size>", 0) != 0)
      ROS_INFO("world '%s': %s", w.name.c_str(), n.c_str());
  for (const std::string& n : w.warnings) ROS_WARN("world '%s': %s", w.name.c_str(), n.c_str());
  if (w.has_max_step_size && std::abs(w.max_step_size - scene->dt()) > 1e-12)
    ROS_INFO("world '%s': <physics><max_step_size> %g s is not obeyed; the node steps %g s "
             "(~physics_rate %g Hz)", w.name.c_str(), w.max_step_size, scene->dt(), c.physics_rate);
  const Vec3 g_param = c.scene.world.gravity;
  if (!scene->loadWorld(w, error)) {
    *error = where + ": " + *error;
    return false;
  }
  // A ~gravity other than the default is the user's choice (gravity_z:=...): it wins.
  if (gravitySetByUser(c) && (w.gravity - g_param).norm() > 0) {
    scene->setGravity(g_param);
    ROS_INFO("world '%s': gravity (%g, %g, %g) replaced by ~gravity (%g, %g, %g)", w.name.c_str(),
             w.gravity.x(), w.gravity.y(), w.gravity.z(), g_param.x(), g_param.y(), g_param.z());
  } else if ((w.gravity - g_param).norm() > 0) {
    ROS_INFO("world '%s': gravity (%g, %g, %g) from the world file", w.name.c_str(),
             w.gravity.x(), w.gravity.y(), w.gravity.z());
  }
  const char* ground = hasStaticPlane(w) ? "the world's plane replaces the default ground"
                       : c.scene.ground   ? "the default ground plane z = 0 stays"
                                          : "no ground plane (~ground false)";
  ROS_INFO("%s (%s): %s", worldSummaryLine(w).c_str(), c.world_file.c_str(), ground);
  return true;
}

}  // namespace node
}  // namespace ragdoll_sim
