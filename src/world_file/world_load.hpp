// The SDF world loader's internal pieces, shared by its source files:
//   include_resolver.cpp  model:// / package:// / file URIs -> files (include targets, meshes)
//   world_xml.cpp         tinyxml2 pre-pass over the world: <include> expansion, what is dropped
//   xml_model.cpp         pre-pass over one model: links, visuals' colours, joints, names, poses
//   sdf_model.cpp         SDFormat DOM of one model -> WorldModelDef (poses, inertia, joints)
//   sdf_geometry.cpp      <collision> geometry -> shapes (meshes through the URDF mesh loader)
//   world_loader.cpp      entry points: pre-pass, SDFormat, identical models parsed once, counts
//   model_ragdoll.cpp     a model as a RagdollDef
#pragma once

#include <array>
#include <cstddef>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "ragdoll_sim/world_file.hpp"

namespace tinyxml2 {
class XMLElement;
class XMLDocument;
}  // namespace tinyxml2

namespace sdf {
inline namespace v12 {
class Model;
class Collision;
}  // namespace v12
}  // namespace sdf

namespace ragdoll_sim {
namespace world_load {

// The newest SDF version SDFormat 12 reads; documents claiming a newer one are read as this.
constexpr double kNewestSdfVersion = 1.9;
// What a world's <include>s may expand to: a small file included thousands of times at each of
// a few levels would otherwise grow without bound before anything is checked.
constexpr size_t kMaxIncludedBytes = size_t(64) << 20;
constexpr int kMaxIncludes = 20000;
// SDFormat 12's memory per element it parses (its description tree is copied for each).
constexpr double kSdfModelMb = 3.0, kSdfLinkMb = 1.0, kSdfCollisionMb = 0.2;

// Thrown with the message that becomes WorldLoadResult::error.
struct LoadError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Text for a message of one line: whitespace runs (a pose split over lines) become one space,
// other control characters '?', and a long text is cut.
inline std::string oneLine(const std::string& s) {
  constexpr size_t kMaxQuoted = 120;
  std::string out;
  for (char c : s) {
    const bool space = c == ' ' || c == '\n' || c == '\r' || c == '\t';
    if (space) {
      if (!out.empty() && out.back() != ' ') out += ' ';
    } else {
      out += (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) ? '?' : c;
    }
    if (out.size() > kMaxQuoted) return out.substr(0, kMaxQuoted) + "...";
  }
  while (!out.empty() && out.back() == ' ') out.pop_back();
  return out;
}

inline std::string quote(const std::string& s) { return "'" + oneLine(s) + "'"; }

inline std::string num(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

// ---- URIs (include_resolver.cpp)
class Resolver {
 public:
  explicit Resolver(const WorldLoadOptions& options);
  // The SDF file an <include><uri> names (a model folder's model.config picks the file), or ""
  // with *why. *mapped gets a sentence when an absolute model:///path was found by its last
  // component in the search paths instead.
  std::string modelFile(const std::string& uri, const std::string& base_dir, std::string* why,
                        std::string* mapped) const;
  // A mesh (or other resource) URI -> file, or "" with *why.
  std::string resource(const std::string& uri, const std::string& base_dir, std::string* why) const;
  const std::vector<std::string>& modelPaths() const { return model_paths_; }

 private:
  std::string modelDir(const std::string& name) const;  // "" when no search path holds it
  std::vector<std::string> model_paths_;
  mutable std::map<std::string, std::string> model_dirs_;  // name -> modelDir (a world repeats them)
  std::vector<std::string> package_paths_;
};

// ---- pre-pass (world_xml.cpp, xml_model.cpp)
using Rgba = std::array<double, 4>;

// What a link's visuals say that the loader keeps (the visuals themselves are dropped).
struct LinkLook {
  bool has_color = false;
  Rgba color{};
  std::string material;  // <material><script><name>
};

struct PreparedModel {
  std::string xml;        // the <model> element for SDFormat (includes expanded, extras dropped)
  std::string name;       // unique in the world
  std::string file_name;  // as written
  std::string key;        // the element without its name and own <pose>: equal keys, equal models
  bool plain_pose = false;       // its own <pose> is six numbers relative to the world
  Transform pose;                // that pose, when plain_pose
  std::map<std::string, LinkLook> looks;  // scoped link name -> what its visuals say
  int models = 0, links = 0, collisions = 0;  // in the element, nested models included
};

struct PreparedWorld {
  double version = 1.7;   // of the document handed to SDFormat
  std::string name = "default";
  std::string frames_xml; // world-level <frame>s
  Vec3 gravity = Vec3(0, 0, -9.8);
  bool has_max_step_size = false;
  double max_step_size = 0;
  std::vector<PreparedModel> models;
  bool models_independent = true;  // no world <frame> and no model pose relative to another
  std::vector<std::string> notes, warnings;
  int skipped = 0, unresolved = 0;
};

// Throws LoadError for a document that cannot be loaded.
void prepareWorld(const std::string& text, const std::string& file, const WorldLoadOptions& options,
                  const Resolver& resolver, PreparedWorld* out);

// Shared by the two pre-pass files.
struct PrepareContext {
  const WorldLoadOptions* options;
  const Resolver* resolver;
  PreparedWorld* out;
  std::map<std::string, int> dropped_kinds;  // element kind -> how many were dropped
  std::vector<std::string> include_stack;    // files being expanded (cycle detection)
  std::map<const tinyxml2::XMLElement*, std::string> included_from;  // top-level model -> file
  size_t included_bytes = 0;  // read by all <include>s so far
  int includes = 0;           // <include>s expanded so far
};

// "model 'a' link 'b' <collision> 'c'": the element and the named elements it sits in.
std::string describe(const tinyxml2::XMLElement* e);
// Pose text: 6 (x y z roll pitch yaw) or 7 (x y z qx qy qz qw... as SDF's quat_xyz) finite numbers.
bool parsePose(const char* text, std::vector<double>* v);
// Makes one piece's (a file's) SDF version explicit where it changes meaning: <pose frame> to
// relative_to, 1.4 joint axes in the model frame.
void normalizeVersion(tinyxml2::XMLElement* root, double version);
// Cleans a <model> in place (includes expanded, extras dropped, names fixed). Returns false when
// nothing physical is left in it (the caller drops it).
bool prepareModel(tinyxml2::XMLElement* model, PrepareContext& ctx, const std::string& scope,
                  std::map<std::string, LinkLook>* looks);
// Replaces <include> `inc` by the model it names (overrides applied) and returns it, with
// *file its canonical path (for the caller's include stack while it prepares the model);
// nullptr when it cannot be resolved (warned and removed, or LoadError under strict).
tinyxml2::XMLElement* expandInclude(tinyxml2::XMLElement* inc, PrepareContext& ctx, std::string* file);
// Renames children <model> (and <include> <name>s already expanded) that repeat a sibling's
// name or hold spaces.
void uniqueModelNames(tinyxml2::XMLElement* parent, PrepareContext& ctx);
void dropElement(tinyxml2::XMLElement* e, PrepareContext& ctx);

// ---- SDFormat DOM (sdf_model.cpp, sdf_geometry.cpp)
struct WalkContext {
  const WorldLoadOptions* options;
  const Resolver* resolver;
  std::vector<std::string>* warnings;
  int* skipped;
};

// A loaded top-level model -> def (links relative to model_pose). Throws LoadError.
void walkModel(const sdf::Model& model, const Transform& model_pose,
               const std::map<std::string, LinkLook>& looks, WalkContext& ctx, WorldModelDef* def);
// One collision -> def, or false: skipped (warned and counted), or a mesh that cannot be read
// (*mesh_failure says why; the caller decides). Throws LoadError for bad sizes. link_frame: the
// link's name in its model's scope (the collision pose is resolved to it).
bool collisionShape(const sdf::Collision& c, const std::string& where, const std::string& link_frame,
                    WalkContext& ctx, WorldCollisionDef* def, std::string* mesh_failure);

}  // namespace world_load
}  // namespace ragdoll_sim
