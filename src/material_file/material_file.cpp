// See material_file.hpp: the file's top level here, its entries in material_yaml.cpp.
#include "ragdoll_sim/material_file.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "material_yaml.hpp"
#include "ragdoll_sim/urdf_loader.hpp"  // kMaxInputFileBytes

namespace ragdoll_sim {

MaterialFileResult loadMaterialString(const std::string& yaml, const std::string& name) {
  MaterialFileResult r;
  YAML::Node root;
  try {
    root = YAML::Load(yaml);
  } catch (const YAML::Exception& e) {
    r.error = name + " line " + std::to_string(e.mark.line + 1) + ": not YAML: " + e.msg;
    return r;
  }
  if (!root.IsMap()) {
    r.error = name + ": must be a dictionary with the keys materials (and link_materials)";
    return r;
  }
  for (const auto& kv : root) {
    const std::string key = kv.first.Scalar();
    if (key != "materials" && key != "link_materials") {
      r.error = name + " line " + std::to_string(kv.first.Mark().line + 1) + ": unknown key '" +
                key + "' (known: materials, link_materials)";
      return r;
    }
  }
  const YAML::Node materials = root["materials"], links = root["link_materials"];
  if (!materials.IsDefined()) {
    r.error = name + ": no materials: key (the surfaces and pairs)";
    return r;
  }
  if (!material_yaml::readTable(materials, name + ": materials", &r.table, &r.error) ||
      !material_yaml::readLinkMaterials(links, name + ": link_materials", r.table,
                                        &r.link_materials, &r.error))
    return r;
  r.error = r.table.error();  // what the per-entry checks cannot see (none today)
  r.ok = r.error.empty();
  if (!r.ok) r.error = name + ": " + r.error;
  return r;
}

MaterialFileResult loadMaterialFile(const std::string& path) {
  MaterialFileResult r;
  std::error_code ec;
  // A device or pipe would be read without end.
  if (!std::filesystem::is_regular_file(path, ec)) {
    r.error = path + ": not a readable regular file";
    return r;
  }
  const auto size = std::filesystem::file_size(path, ec);
  if (ec) {
    r.error = path + ": cannot be read (" + ec.message() + ")";
    return r;
  }
  if (size > kMaxInputFileBytes) {
    r.error = path + ": larger than " + std::to_string(kMaxInputFileBytes >> 20) + " MiB";
    return r;
  }
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in) {
    r.error = path + ": cannot be read";
    return r;
  }
  return loadMaterialString(text.str(), path);
}

}  // namespace ragdoll_sim
