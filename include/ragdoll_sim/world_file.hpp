// Gazebo SDF world files -> WorldFileDef (ROS-free). Parsed by SDFormat 12 (libsdformat) after a
// tinyxml2 pre-pass that expands <include>s itself (model:// through the search paths, cycles
// refused), renames duplicate model names and names with spaces, and drops what is not simulated
// (plugins, lights, sensors, actors, GUI, <state> ...) with one note per kind. What cannot be
// resolved is warned about and skipped unless WorldLoadOptions::strict. See docs/worlds.md.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "ragdoll_sim/ragdoll.hpp"

namespace ragdoll_sim {

// One <collision> of a link.
struct WorldCollisionDef {
  std::string name;
  // Geometry (ellipsoids and meshes as convex hulls), its pose in the link frame, and the
  // <surface> coefficients in `material` where given (has_friction / has_restitution).
  ShapeDef shape;
  bool has_friction = false;     // <surface><friction><ode><mu>/<mu2> given
  double mu = 0, mu2 = 0;        // as written (shape.material holds their mean)
  bool has_restitution = false;  // <bounce><restitution_coefficient> given
  // Material name: <surface><ragdoll_sim:material>, else the link's visual material script name
  // as written ("Gazebo/Wood", which the Scene takes as table entry "wood" when it has one); "".
  std::string material;
  double plane_size[2] = {0, 0}; // plane: <size> along the plane (the shape itself is unbounded)
  std::string source;            // "box", "convex hull of ...", "box fitted to the inertia (...)"
};

struct WorldLinkDef {
  std::string name;                  // scoped in its model ("nested::link")
  Transform pose;                    // link frame in the world
  bool is_static = false;            // its model, or a model it is nested in, is static
  bool has_inertial = false;         // <inertial> given (else SDF's default: 1 kg, unit inertia)
  double mass = 1.0;
  Vec3 com = Vec3::Zero();           // link frame
  Mat3 inertia = Mat3::Identity();   // about com, link-frame axes
  std::vector<WorldCollisionDef> collisions;
  bool has_color = false;            // a <visual><material> diffuse (else ambient) colour
  std::array<double, 4> color = {0.5, 0.5, 0.5, 1.0};  // rgba
  // The first visual's <material><script><name> ("Gazebo/Wood"): the only material name a
  // Gazebo world usually gives, for a material table to go by; "" when none.
  std::string visual_material;
};

struct WorldModelDef {
  std::string name;         // unique in the world (renamed where the file's was not)
  std::string file_name;    // the name as written (or as <include><name> set it)
  bool is_static = false;   // the top-level <static> (a nested model may be static on its own)
  Transform pose;           // model frame in the world
  std::vector<WorldLinkDef> links;  // nested models' links included, scoped "nested::link"
  // Through the URDF loader's mapping: revolute -> Hinge, continuous -> Hinge (unlimited),
  // prismatic, ball, fixed. parent / child index `links`; parent -1 is the world (a fixed base).
  // frame_parent / frame_child: the joint frame in each link's frame (parent -1: in the world).
  std::vector<RagdollJointDef> joints;
};

struct WorldCounts {
  int models = 0;          // models loaded (top level; nested ones belong to their parent)
  int static_shapes = 0;   // collisions of static links
  int dynamic_bodies = 0;  // links that are not static
  int skipped = 0;         // collisions and models skipped (heightmap, polyline, missing mesh ...)
  int unresolved = 0;      // <include>s that could not be resolved
};

struct WorldFileDef {
  std::string name;
  Vec3 gravity = Vec3(0, 0, -9.8);  // <gravity>, or <physics><gravity> before SDF 1.6
  bool has_max_step_size = false;
  double max_step_size = 0.001;     // <physics><max_step_size>: reported, not obeyed
  std::vector<WorldModelDef> models;
  WorldCounts counts;
  std::vector<std::string> notes;     // one per kind of thing not simulated
  std::vector<std::string> warnings;  // unresolved includes, renames, skipped geometry
};

struct WorldLoadOptions {
  // An unresolved <include> is an error (else a warning, and the rest loads).
  bool strict = false;
  // model:// lookup roots; empty: $GAZEBO_MODEL_PATH, $SDF_PATH, $GZ_SIM_RESOURCE_PATH, then
  // $ROS_PACKAGE_PATH (each root R: R/NAME and R/*/models/NAME).
  std::vector<std::string> model_paths;
  std::vector<std::string> package_paths;  // package:// lookup; empty: $ROS_PACKAGE_PATH
  std::string base_dir;                    // relative URIs (loadWorldFile: the file's folder)
  bool load_meshes = true;
  int max_include_depth = 16;              // deeper nesting of <include>s is refused
  // SDFormat 12 holds about 3 MB per model, 1 MB per link and 0.2 MB per collision it parses
  // (models that differ only in name and pose are parsed once); a world whose estimate is above
  // this is refused before SDFormat sees it.
  double max_sdf_megabytes = 3072;
};

struct WorldLoadResult {
  bool ok = false;
  std::string error;  // one message naming the offending element when !ok
  WorldFileDef def;
};

WorldLoadResult loadWorldString(const std::string& xml, const WorldLoadOptions& options = {});
WorldLoadResult loadWorldFile(const std::string& path, WorldLoadOptions options = {});

// A model's links (root: the first, rest poses relative to it) and the joints between them
// (joined pairs do not collide) as a RagdollDef: spawnRagdoll(world, def, m.links[0].pose)
// places every link where the world file has it. A joint to the world (parent -1) on the root
// link sets fixed_base (of any type: the root is pinned, a warning says when it was not fixed);
// one on another link is left out with a warning (the model stays free). Links get the visual
// colour, the visual material as LinkDef::material, each collision's material name
// (shape_materials) and <mu>/<mu2> mean (shape_friction).
RagdollDef modelRagdollDef(const WorldModelDef& m);

// "world=NAME status=ok models=N static_shapes=S dynamic_bodies=D skipped=K unresolved=U"
std::string worldSummaryLine(const WorldFileDef& def);

}  // namespace ragdoll_sim
