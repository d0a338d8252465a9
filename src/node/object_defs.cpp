#include "object_defs.hpp"

#include <tinyxml2.h>

#include <cmath>
#include <filesystem>
#include <sstream>

#include "input_file.hpp"
#include "names.hpp"
#include "ragdoll_sim/urdf_loader.hpp"
#include "ragdoll_sim/world_file.hpp"

namespace ragdoll_sim {
namespace node {

namespace {

// Density of a static object's nominal mass: static bodies never use it, the def needs one.
constexpr double kStaticNominalDensity = 1000.0;  // kg/m^3

std::string num(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

Geometry primitiveGeometry(const std::string& shape, const std::vector<double>& d) {
  if (shape == "box") return Geometry::box(0.5 * Vec3(d[0], d[1], d[2]));
  if (shape == "sphere") return Geometry::sphere(d[0]);
  if (shape == "cylinder") return Geometry::cylinder(d[0], 0.5 * d[1]);
  return Geometry::capsule(d[0], 0.5 * d[1]);
}

// An SDF model document as a world the loader takes: <sdf version><world>MODEL</world></sdf>.
std::string wrapSdfModel(tinyxml2::XMLElement* root, std::string* wrapped) {
  const std::string name = root->Name();
  tinyxml2::XMLElement* model = nullptr;
  std::string version = "1.7";
  if (name == "model") {
    model = root;
  } else {
    if (const char* v = root->Attribute("version")) version = v;
    if (root->FirstChildElement("world"))
      return "<sdf> holds a <world>; ~spawn_model takes one <model> (a world file goes to "
             "~world_file)";
    model = root->FirstChildElement("model");
    if (!model) return "<sdf> holds no <model>";
    if (model->NextSiblingElement("model"))
      return "<sdf> holds several <model>s; ~spawn_model takes one";
  }
  tinyxml2::XMLPrinter printer(nullptr, true);
  model->Accept(&printer);
  std::string v;
  for (char c : version)  // the attribute goes back into XML: digits and dots only
    if ((c >= '0' && c <= '9') || c == '.') v += c;
  *wrapped = "<sdf version=\"" + (v.empty() ? std::string("1.7") : v) +
             "\"><world name=\"spawn_model\">" + printer.CStr() + "</world></sdf>";
  return "";
}

std::string loadSdfModel(tinyxml2::XMLElement* root, const std::string& base_dir,
                         LoadedModel* out) {
  std::string wrapped;
  std::string e = wrapSdfModel(root, &wrapped);
  if (!e.empty()) return e;
  WorldLoadOptions options;
  options.base_dir = base_dir;
  const WorldLoadResult r = loadWorldString(wrapped, options);
  if (!r.ok) return r.error;
  if (r.def.models.size() != 1)
    return "the SDF gave " + std::to_string(r.def.models.size()) + " models, expected one";
  const WorldModelDef& m = r.def.models[0];
  if (m.links.empty()) return "model " + scene::quoted(m.file_name) + " has no links";
  out->format = "SDF";
  out->def = modelRagdollDef(m);
  out->def.name = m.file_name;
  out->root_in_model = m.links[static_cast<size_t>(out->def.root)].pose;
  bool all_static = true;
  for (size_t i = 0; i < m.links.size(); ++i) {
    const WorldLinkDef& l = m.links[i];
    all_static = all_static && l.is_static;
    LinkDef& d = out->def.links[i];
    if (!d.has_color && l.has_color) {
      d.has_color = true;
      d.color = l.color;
    }
    if (d.shape_materials.empty())
      for (const WorldCollisionDef& c : l.collisions) d.shape_materials.push_back(c.material);
  }
  out->is_static = m.is_static || all_static;
  out->fixed_base = out->def.fixed_base;  // a weld to the world (modelRagdollDef's rule)
  for (const std::string& n : r.def.notes) out->def.notes.push_back(n);
  for (const std::string& w : r.def.warnings) out->def.warnings.push_back(w);
  return "";
}

}  // namespace

std::string primitiveObjectDef(const PrimitiveObject& o, RagdollDef* def) {
  const std::string& s = o.shape;
  const size_t want = s == "box" ? 3 : s == "sphere" ? 1 : (s == "cylinder" || s == "capsule") ? 2 : 0;
  if (want == 0)
    return "shape " + scene::quoted(s) + " is not one of box, sphere, cylinder, capsule";
  static const char* kNames[3][3] = {{"x", "y", "z"}, {"radius", "", ""}, {"radius", "length", ""}};
  const int row = want == 3 ? 0 : want == 1 ? 1 : 2;
  if (o.dimensions.size() != want) {
    std::string list;
    for (size_t i = 0; i < want; ++i) list += std::string(i ? ", " : "") + kNames[row][i];
    return s + " takes " + std::to_string(want) + " dimension(s) [" + list + "] (m), got " +
           std::to_string(o.dimensions.size());
  }
  for (size_t i = 0; i < want; ++i)
    if (!(std::isfinite(o.dimensions[i]) && o.dimensions[i] > 0))
      return s + " dimensions[" + std::to_string(i) + "] (" + kNames[row][i] +
             ") must be a finite number > 0 (m), got " + num(o.dimensions[i]);
  const Geometry g = primitiveGeometry(s, o.dimensions);
  std::string e = geometryError(g);
  if (!e.empty()) return e;
  if (!(std::isfinite(o.mass) && o.mass >= 0))
    return "mass must be a finite number > 0 (kg), or 0 to use density; got " + num(o.mass);
  if (!(std::isfinite(o.density) && o.density >= 0))
    return "density must be a finite number > 0 (kg/m^3), or 0 when mass is given; got " +
           num(o.density);
  if (!o.is_static && o.mass == 0 && o.density == 0)
    return "a dynamic object needs mass > 0 (kg) or density > 0 (kg/m^3); both are 0";
  for (double c : o.color)
    if (o.has_color && !(c >= 0 && c <= 1))
      return "color must be r, g, b, a in [0, 1]; got " + num(c);
  const double volume = g.volume();
  double mass = o.mass > 0 ? o.mass : o.density > 0 ? o.density * volume : kStaticNominalDensity * volume;
  if (!(std::isfinite(mass) && mass > 0))
    return "the mass (density " + num(o.density) + " kg/m^3 x volume " + num(volume) +
           " m^3) is " + num(mass) + " kg, not a finite number > 0";
  LinkDef link;
  link.name = kObjectLink;
  link.mass = mass;
  link.com = Vec3::Zero();
  link.inertia = g.unitInertia() * (mass / volume);
  ShapeDef shape;
  shape.geometry = g;
  link.shapes.push_back(shape);
  link.shape_sources.push_back(s);
  link.material = o.material;
  link.has_color = o.has_color;
  link.color = o.color;
  *def = RagdollDef();
  def->links.push_back(std::move(link));
  return "";
}

std::string loadModelText(const std::string& xml, const std::string& file, LoadedModel* out) {
  const std::string base_dir =
      file.empty() ? "" : std::filesystem::path(file).parent_path().string();
  tinyxml2::XMLDocument doc;
  if (xml.find_first_not_of(" \t\r\n") == std::string::npos) return "the model text is empty";
  if (doc.Parse(xml.c_str(), xml.size()) != tinyxml2::XML_SUCCESS)
    return std::string("the model is not well-formed XML: ") + doc.ErrorName() + " at line " +
           std::to_string(doc.ErrorLineNum());
  tinyxml2::XMLElement* root = doc.RootElement();
  const std::string name = root ? root->Name() : "";
  if (name == "robot") {
    UrdfLoadOptions options;
    options.base_dir = base_dir;
    UrdfLoadResult r = loadUrdfString(xml, options);
    if (!r.ok) return "URDF: " + r.error;
    out->format = "URDF";
    out->def = std::move(r.def);
    out->root_in_model = Transform();
    out->is_static = false;
    out->fixed_base = out->def.fixed_base;
    return "";
  }
  if (name == "sdf" || name == "model") {
    const std::string e = loadSdfModel(root, base_dir, out);
    return e.empty() ? e : "SDF: " + e;
  }
  return "the root element is <" + name + ">, expected <robot> (URDF), <sdf> or <model> (SDF)";
}

std::string readModelFile(const std::string& path, std::string* text) {
  std::string error;
  if (!readInputFile(path, "model file", text, &error)) return error;
  return "";
}

}  // namespace node
}  // namespace ragdoll_sim
