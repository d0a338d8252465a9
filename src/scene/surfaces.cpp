// Shape surfaces by material name (surfaces.hpp).
#include "surfaces.hpp"

#include <algorithm>
#include <cctype>

namespace ragdoll_sim {
namespace scene {

namespace {

const char kGazeboPrefix[] = "Gazebo/";

const std::string* mappedName(const SurfaceRules& rules, const std::string& link) {
  if (!rules.link_materials) return nullptr;
  const std::string* any = nullptr;
  for (const auto& [name, material] : *rules.link_materials) {
    if (name == link) return &material;
    if (name == "*" && !any) any = &material;
  }
  return any;
}

}  // namespace

int findMaterial(const MaterialTable& table, const std::string& name, bool* unknown) {
  *unknown = false;
  if (name.empty()) return -1;
  const int id = table.find(name);
  if (id >= 1) return id;
  const size_t n = sizeof(kGazeboPrefix) - 1;
  if (name.compare(0, n, kGazeboPrefix) == 0) {
    // Gazebo's visual script names are about looks: only a table entry of the same word counts.
    std::string lower = name.substr(n);
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const int g = table.find(lower);
    return g >= 1 ? g : -1;
  }
  *unknown = true;
  return -1;
}

std::vector<std::string> resolveSurfaces(RagdollDef* def, const SurfaceRules& rules,
                                         const std::vector<std::vector<uint8_t>>& written) {
  std::vector<std::string> warnings;
  const MaterialTable empty;
  const MaterialTable& table = rules.table ? *rules.table : empty;
  for (size_t l = 0; l < def->links.size(); ++l) {
    LinkDef& link = def->links[l];
    const std::string* mapped = mappedName(rules, link.name);
    std::vector<std::string> said;
    for (size_t k = 0; k < link.shapes.size(); ++k) {
      ShapeDef& shape = link.shapes[k];
      // The first name the table knows, of the shape's, the link's and the map's; a name it
      // does not know counts as none (a "Gazebo/..." look silently).
      const std::string* names[3] = {k < link.shape_materials.size() ? &link.shape_materials[k]
                                                                     : nullptr,
                                     &link.material, mapped};
      int id = -1;
      for (const std::string* name : names) {
        if (!name || name->empty() || id >= 1) continue;
        bool unknown = false;
        id = findMaterial(table, *name, &unknown);
        if (unknown && std::find(said.begin(), said.end(), *name) == said.end()) {
          said.push_back(*name);
          warnings.push_back("link '" + link.name + "' of '" + def->name + "': material '" +
                             *name + "' is not in the material table; ignored");
        }
      }
      Material m = id >= 1 ? table.material(id)
                   : shape.geometry.type == ShapeType::Plane ? rules.plane_fallback
                                                             : rules.fallback;
      const uint8_t w = l < written.size() && k < written[l].size() ? written[l][k] : 0;
      if (w & kWrittenFriction) {
        m.static_friction = m.kinetic_friction = shape.material.static_friction;
        m.id = 0;  // the file's own coefficient: no pair entry applies
      }
      if (w & kWrittenRestitution) {
        m.restitution = shape.material.restitution;
        m.id = 0;
      }
      if (k < link.shape_friction.size() && link.shape_friction[k] >= 0.0) {
        m.static_friction = m.kinetic_friction = link.shape_friction[k];
        m.id = 0;
      }
      shape.material = m;
    }
  }
  return warnings;
}

}  // namespace scene
}  // namespace ragdoll_sim
