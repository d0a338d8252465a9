// URIs of SDF worlds -> files: model://NAME through the model search paths (Gazebo's
// GAZEBO_MODEL_PATH convention), package:// and relative paths through the URDF mesh resolver.
#include <tinyxml2.h>

#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "input_file.hpp"
#include "mesh_loader.hpp"
#include "world_load.hpp"

namespace ragdoll_sim {
namespace world_load {
namespace {

namespace fs = std::filesystem;

void splitInto(const char* env, std::vector<std::string>* out) {
  std::stringstream ss(env ? env : "");
  for (std::string p; std::getline(ss, p, ':');)
    if (!p.empty()) out->push_back(p);
}

bool isDir(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(p, ec);
}

bool present(const fs::path& p) {
  std::error_code ec;
  return fs::exists(p, ec);
}

// The SDF file of a model folder: model.config's <sdf> with the newest version SDFormat reads,
// else model.sdf, else "".
std::string fileOfModelDir(const fs::path& dir, std::string* why) {
  std::string text, error;
  const fs::path config = dir / "model.config";
  if (present(config) && readInputFile(config.string(), "model.config", &text, &error)) {
    tinyxml2::XMLDocument doc;
    if (doc.Parse(text.data(), text.size()) == tinyxml2::XML_SUCCESS && doc.RootElement()) {
      std::string best;
      double best_version = -1;
      for (auto* s = doc.RootElement()->FirstChildElement("sdf"); s; s = s->NextSiblingElement("sdf")) {
        const char* file = s->GetText();
        if (!file) continue;
        double v = s->DoubleAttribute("version", 0.0);
        if (v > kNewestSdfVersion + 1e-9) v = 0.0;  // SDFormat 12 cannot read it: last resort
        if (v > best_version && present(dir / file)) {
          best_version = v;
          best = (dir / file).string();
        }
      }
      if (!best.empty()) return best;
    }
  }
  if (present(dir / "model.sdf")) return (dir / "model.sdf").string();
  *why = "model folder " + dir.string() + " has no model.config naming an existing SDF file";
  return "";
}

}  // namespace

Resolver::Resolver(const WorldLoadOptions& options) {
  model_paths_ = options.model_paths;
  if (model_paths_.empty()) {
    for (const char* var : {"GAZEBO_MODEL_PATH", "SDF_PATH", "GZ_SIM_RESOURCE_PATH", "ROS_PACKAGE_PATH"})
      splitInto(std::getenv(var), &model_paths_);
  }
  package_paths_ = options.package_paths.empty() ? mesh::packagePathFromEnv() : options.package_paths;
}

std::string Resolver::modelDir(const std::string& name) const {
  if (name.empty() || name == "." || name == ".." || name.find('/') != std::string::npos) return "";
  const auto cached = model_dirs_.find(name);
  if (cached != model_dirs_.end()) return cached->second;
  std::string& found = model_dirs_[name];
  for (const std::string& root : model_paths_) {
    if (isDir(fs::path(root) / name)) return found = (fs::path(root) / name).string();
    // A ROS package exporting its models keeps them in <package>/models.
    std::error_code ec;
    for (fs::directory_iterator it(root, ec), end; !ec && it != end; it.increment(ec)) {
      const fs::path p = it->path() / "models" / name;
      if (isDir(p)) return found = p.string();
    }
  }
  return found;
}

std::string Resolver::modelFile(const std::string& uri, const std::string& base_dir,
                                std::string* why, std::string* mapped) const {
  const std::string kModel = "model://";
  if (uri.rfind("http://", 0) == 0 || uri.rfind("https://", 0) == 0) {
    *why = "online URI (models are not downloaded)";
    return "";
  }
  fs::path target;
  if (uri.rfind(kModel, 0) == 0) {
    const std::string rest = uri.substr(kModel.size());
    if (!rest.empty() && rest[0] == '/') {
      // model:///abs/path: another machine's folder as often as this one's.
      if (isDir(rest) || present(rest)) {
        target = rest;
      } else {
        const std::string base = fs::path(rest).lexically_normal().filename().string();
        const std::string dir = modelDir(base.empty() ? fs::path(rest).parent_path().filename().string() : base);
        if (dir.empty()) {
          *why = "absolute path not found, nor a model " + quote(base) + " in the model search path";
          return "";
        }
        *mapped = "absolute model URI " + uri + " not found; using " + dir + " (same last component)";
        target = dir;
      }
    } else {
      const size_t slash = rest.find('/');
      const std::string name = rest.substr(0, slash);
      const std::string dir = modelDir(name);
      if (dir.empty()) {
        *why = "model " + quote(name) + " not found in the model search path (" +
               (model_paths_.empty() ? std::string("empty: set GAZEBO_MODEL_PATH") : "") +
               [&] {
                 std::string s;
                 for (const auto& p : model_paths_) s += (s.empty() ? "" : ":") + p;
                 return s;
               }() + ")";
        return "";
      }
      target = slash == std::string::npos ? fs::path(dir) : fs::path(dir) / rest.substr(slash + 1);
    }
  } else {
    const std::string f = mesh::resolveUri(uri, base_dir, package_paths_, why);
    if (f.empty()) return "";
    target = f;
  }
  if (isDir(target)) return fileOfModelDir(target, why);
  if (!present(target)) {
    *why = "file " + target.string() + " not found";
    return "";
  }
  return target.string();
}

std::string Resolver::resource(const std::string& uri, const std::string& base_dir,
                               std::string* why) const {
  const std::string kModel = "model://";
  if (uri.rfind("http://", 0) == 0 || uri.rfind("https://", 0) == 0) {
    *why = "online URI (not downloaded)";
    return "";
  }
  if (uri.rfind(kModel, 0) == 0) {
    const std::string rest = uri.substr(kModel.size());
    const size_t slash = rest.find('/');
    const std::string dir = modelDir(rest.substr(0, slash));
    if (dir.empty() || slash == std::string::npos) {
      *why = "model " + quote(rest.substr(0, slash)) + " not found in the model search path";
      return "";
    }
    const fs::path p = fs::path(dir) / rest.substr(slash + 1);
    if (!present(p)) {
      *why = "file " + p.string() + " not found";
      return "";
    }
    return p.string();
  }
  return mesh::resolveUri(uri, base_dir, package_paths_, why);
}

}  // namespace world_load
}  // namespace ragdoll_sim
