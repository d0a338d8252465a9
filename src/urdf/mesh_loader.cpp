// See mesh_loader.hpp.
#include "mesh_loader.hpp"

#include <assimp/IOSystem.hpp>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <assimp/Importer.hpp>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <sstream>

#include "input_file.hpp"

namespace ragdoll_sim {
namespace mesh {
namespace {

namespace fs = std::filesystem;

bool isPackage(const fs::path& dir, const std::string& pkg) {
  std::error_code ec;
  const fs::path manifest = dir / "package.xml";
  if (!fs::is_regular_file(manifest, ec)) return false;
  std::string text, error;
  return readInputFile(manifest.string(), "package manifest", &text, &error) &&
         text.find("<name>" + pkg + "</name>") != std::string::npos;
}

// A package folder named pkg at or below root (depth levels), or "".
std::string findPackage(const fs::path& root, const std::string& pkg, int depth) {
  std::error_code ec;
  if (!fs::is_directory(root, ec)) return "";
  if (isPackage(root, pkg)) return root.string();
  if (depth == 0) return "";
  for (fs::directory_iterator it(root, ec), end; !ec && it != end; it.increment(ec)) {
    if (!it->is_directory(ec) || it->path().filename().string().rfind('.', 0) == 0) continue;
    const std::string found = findPackage(it->path(), pkg, depth - 1);
    if (!found.empty()) return found;
  }
  return "";
}

// assimp's file access (the mesh and whatever it refers to: .mtl, external buffers) through
// readInputFile, so that assimp never opens a pipe or device nor reads an oversized file; each
// file is read once however often assimp opens it (format probes open the mesh several times).
class BoundedIOSystem : public Assimp::IOSystem {
 public:
  // Open() decides, with the reason kept for the caller: a plain existence test here.
  bool Exists(const char* file) const override {
    std::error_code ec;
    return fs::exists(file, ec);
  }
  char getOsSeparator() const override { return '/'; }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (std::string(mode).find_first_of("wa+") != std::string::npos) return nullptr;
    auto it = read_.find(file);
    if (it == read_.end()) {
      std::string text, error;
      if (!readInputFile(file, "mesh file", &text, &error)) {
        if (error_.empty()) error_ = error;
        return nullptr;
      }
      it = read_.emplace(file, std::move(text)).first;
    }
    const std::string& text = it->second;
    return new Assimp::MemoryIOStream(reinterpret_cast<const uint8_t*>(text.data()), text.size());
  }
  void Close(Assimp::IOStream* stream) override { delete stream; }
  const std::string& error() const { return error_; }

 private:
  std::map<std::string, std::string> read_;  // path -> contents; streams point into these
  std::string error_;                        // the first refusal
};

}  // namespace

std::vector<std::string> packagePathFromEnv() {
  std::vector<std::string> out;
  const char* env = std::getenv("ROS_PACKAGE_PATH");
  std::stringstream ss(env ? env : "");
  for (std::string p; std::getline(ss, p, ':');)
    if (!p.empty()) out.push_back(p);
  return out;
}

std::string resolveUri(const std::string& uri, const std::string& base_dir,
                       const std::vector<std::string>& package_paths, std::string* why) {
  std::error_code ec;
  // Existence only: what kind of file it is, and its size, readVertices checks as it reads.
  auto existing = [&](const fs::path& p) -> std::string {
    if (fs::exists(p, ec)) return p.lexically_normal().string();
    *why = "file " + p.string() + " not found";
    return "";
  };
  const std::string kPackage = "package://", kFile = "file://";
  if (uri.rfind(kPackage, 0) == 0) {
    const std::string rest = uri.substr(kPackage.size());
    const size_t slash = rest.find('/');
    const std::string pkg = rest.substr(0, slash);
    const std::string rel = slash == std::string::npos ? "" : rest.substr(slash + 1);
    // The URDF inside its own package (pkg/urdf/robot.urdf) needs no package path.
    if (!base_dir.empty())
      for (fs::path p = fs::absolute(base_dir, ec); !p.empty() && p != p.root_path(); p = p.parent_path())
        if (p.filename() == pkg) {
          const std::string f = existing(p / rel);
          if (!f.empty()) return f;
        }
    for (const std::string& root : package_paths) {
      const std::string dir = findPackage(root, pkg, 4);
      if (!dir.empty()) return existing(fs::path(dir) / rel);
    }
    *why = "package " + pkg + " not found (next to the URDF or in ROS_PACKAGE_PATH)";
    return "";
  }
  if (uri.rfind(kFile, 0) == 0) return existing(uri.substr(kFile.size()));
  const fs::path p(uri);
  if (p.is_absolute() || base_dir.empty()) return existing(p);
  return existing(fs::path(base_dir) / p);
}

bool readVertices(const std::string& path, const Vec3& scale, std::vector<Vec3>* out,
                  std::string* error, double* volume) {
  Assimp::Importer importer;
  auto* io = new BoundedIOSystem;  // the importer owns it
  importer.SetIOHandler(io);
  // URDF meshes live in the link frame as written: keep a Collada file's axes (assimp would
  // turn a Z_UP file to its own Y-up); its <unit> scale still applies.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_COLLADA_IGNORE_UP_DIRECTION, true);
  // Only positions are needed: no normals, no triangulation beyond what the reader does.
  const aiScene* scene = importer.ReadFile(path, aiProcess_JoinIdenticalVertices);
  if (!scene || !scene->mRootNode) {
    *error = io->error().empty() ? "assimp cannot read " + path + ": " + importer.GetErrorString()
                                 : io->error();
    return false;
  }
  out->clear();
  // Walk the node tree so that node transforms (DAE unit and placement) are applied.
  struct Walk {
    const aiScene* scene;
    const Vec3& scale;
    std::vector<Vec3>* out;
    double* volume;
    void operator()(const aiNode* node, const aiMatrix4x4& parent) const {
      const aiMatrix4x4 T = parent * node->mTransformation;
      for (unsigned m = 0; m < node->mNumMeshes; ++m) {
        const aiMesh* mesh = scene->mMeshes[node->mMeshes[m]];
        auto at = [&](unsigned v) {
          const aiVector3D p = T * mesh->mVertices[v];
          return Vec3(Vec3(p.x, p.y, p.z).cwiseProduct(scale));
        };
        for (unsigned v = 0; v < mesh->mNumVertices; ++v) {
          const Vec3 x = at(v);
          if (x.allFinite()) out->push_back(x);
        }
        // Signed volume of the tetrahedra from the origin to each face (polygons as fans).
        for (unsigned f = 0; volume && f < mesh->mNumFaces; ++f) {
          const aiFace& face = mesh->mFaces[f];
          for (unsigned k = 2; k < face.mNumIndices; ++k) {
            const unsigned a = face.mIndices[0], b = face.mIndices[k - 1], c = face.mIndices[k];
            if (a < mesh->mNumVertices && b < mesh->mNumVertices && c < mesh->mNumVertices)
              *volume += at(a).dot(at(b).cross(at(c))) / 6.0;
          }
        }
      }
      for (unsigned c = 0; c < node->mNumChildren; ++c) (*this)(node->mChildren[c], T);
    }
  };
  if (volume) *volume = 0;
  Walk{scene, scale, out, volume}(scene->mRootNode, aiMatrix4x4());
  if (volume) *volume = std::abs(*volume);
  if (out->empty()) {
    *error = path + " holds no vertices";
    return false;
  }
  return true;
}

std::vector<Vec3> supportPoints(const std::vector<Vec3>& points, int directions) {
  std::vector<int> best;
  for (int i = 0; i < directions; ++i) {  // Fibonacci sphere
    const double z = 1 - 2 * (i + 0.5) / directions, r = std::sqrt(1 - z * z);
    const double phi = i * 2.399963229728653;
    const Vec3 d(r * std::cos(phi), r * std::sin(phi), z);
    int arg = 0;
    for (int k = 1; k < int(points.size()); ++k)
      if (points[k].dot(d) > points[arg].dot(d)) arg = k;
    best.push_back(arg);
  }
  std::sort(best.begin(), best.end());
  best.erase(std::unique(best.begin(), best.end()), best.end());
  std::vector<Vec3> out;
  for (int k : best) out.push_back(points[k]);
  return out;
}

}  // namespace mesh
}  // namespace ragdoll_sim
