// See urdf_xml.hpp. The checks run in document order, so the first problem is the one reported.
#include "urdf_xml.hpp"

#include "anatomy_xml.hpp"

#include <tinyxml2.h>

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <sstream>

namespace ragdoll_sim {
namespace urdf_xml {
namespace {

using tinyxml2::XMLElement;

std::string quote(const std::string& s) { return "'" + s + "'"; }

std::string attr(const XMLElement* e, const char* name) {
  const char* v = e->Attribute(name);
  return v ? v : "";
}

std::string lineOf(const XMLElement* e) { return " (line " + std::to_string(e->GetLineNum()) + ")"; }

// "link 'a' <collision> <origin>": the element and the named link / joint it sits in.
std::string describe(const XMLElement* e) {
  std::string path;
  for (const XMLElement* p = e; p; p = p->Parent() ? p->Parent()->ToElement() : nullptr) {
    const std::string n = p->Name();
    if (n == "robot") break;
    if ((n == "link" || n == "joint") && p->Attribute("name")) {
      path = n + " " + quote(attr(p, "name")) + (path.empty() ? "" : " " + path);
      break;
    }
    path = "<" + n + ">" + (path.empty() ? "" : " " + path);
  }
  return path;
}

// Three finite numbers separated by spaces (what URDF's xyz / rpy hold).
bool threeFinite(const std::string& s) {
  const char* p = s.c_str();
  for (int i = 0; i < 3; ++i) {
    char* end = nullptr;
    const double v = std::strtod(p, &end);
    if (end == p || !std::isfinite(v)) return false;
    p = end;
  }
  while (std::isspace(static_cast<unsigned char>(*p))) ++p;
  return *p == '\0';
}

std::string checkOrigins(const XMLElement* e) {
  for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) {
    if (std::strcmp(c->Name(), "origin") == 0) {
      for (const char* a : {"xyz", "rpy"}) {
        if (c->Attribute(a) && !threeFinite(attr(c, a)))
          return describe(c) + lineOf(c) + ": " + a + "=" + quote(attr(c, a)) +
                 " is not three finite numbers";
      }
    }
    const std::string err = checkOrigins(c);
    if (!err.empty()) return err;
  }
  return "";
}

// Ordinals of <capsule> geometries among the `kind` elements of a link; renames them.
void capsules(XMLElement* link, const char* kind, std::set<int>* out) {
  int k = 0;
  for (XMLElement* c = link->FirstChildElement(kind); c; c = c->NextSiblingElement(kind), ++k) {
    XMLElement* g = c->FirstChildElement("geometry");
    XMLElement* cap = g ? g->FirstChildElement("capsule") : nullptr;
    if (!cap) continue;
    cap->SetName("cylinder");
    out->insert(k);
  }
}

bool parseDouble(const char* text, double* v) {
  if (!text) return false;
  char* end = nullptr;
  *v = std::strtod(text, &end);
  while (end && std::isspace(static_cast<unsigned char>(*end))) ++end;
  return end != text && end && *end == '\0' && std::isfinite(*v);
}

// <color rgba="r g b a">: four finite numbers in [0, 1].
bool readRgba(const XMLElement* material, std::array<double, 4>* out) {
  const XMLElement* c = material ? material->FirstChildElement("color") : nullptr;
  if (!c || !c->Attribute("rgba")) return false;
  std::istringstream in(attr(c, "rgba"));
  std::array<double, 4> v;
  for (double& x : v)
    if (!(in >> x) || !(x >= 0 && x <= 1)) return false;
  std::string rest;
  if (in >> rest) return false;
  *out = v;
  return true;
}

// The first <visual> of a link with a colour, given there or by a named robot-level material.
bool visualColor(const XMLElement* link, const std::map<std::string, std::array<double, 4>>& named,
                 std::array<double, 4>* out) {
  for (const XMLElement* v = link->FirstChildElement("visual"); v; v = v->NextSiblingElement("visual")) {
    const XMLElement* m = v->FirstChildElement("material");
    if (!m) continue;
    if (readRgba(m, out)) return true;
    const auto it = named.find(attr(m, "name"));
    if (it != named.end()) {
      *out = it->second;
      return true;
    }
  }
  return false;
}

std::string trimmed(const char* text) {
  std::string s = text ? text : "";
  const size_t a = s.find_first_not_of(" \t\r\n"), b = s.find_last_not_of(" \t\r\n");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

}  // namespace

std::string preprocess(const std::string& xml, Extras* out) {
  *out = Extras();
  if (xml.find_first_not_of(" \t\r\n") == std::string::npos) return "the URDF is empty";
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS) {
    return "the URDF is not well-formed XML: " + std::string(doc.ErrorName()) + " at line " +
           std::to_string(doc.ErrorLineNum());
  }
  XMLElement* robot = doc.RootElement();
  if (!robot) return "the URDF has no root element, expected <robot>";
  if (std::strcmp(robot->Name(), "robot") != 0)
    return "the URDF's root element is <" + std::string(robot->Name()) + ">, expected <robot>";

  // Colours named at the robot level (<robot><material name><color>), for visuals that refer
  // to them by name.
  std::map<std::string, std::array<double, 4>> named_colors;
  for (const XMLElement* m = robot->FirstChildElement("material"); m; m = m->NextSiblingElement("material")) {
    std::array<double, 4> rgba;
    if (!attr(m, "name").empty() && readRgba(m, &rgba)) named_colors[attr(m, "name")] = rgba;
  }

  // ---- links and joints: names, parents, children
  std::map<std::string, const XMLElement*> links, joints;
  std::map<std::string, std::string> parent_joint;  // child link -> joint
  std::map<std::string, std::string> joint_parent;  // joint -> parent link
  for (XMLElement* l = robot->FirstChildElement("link"); l; l = l->NextSiblingElement("link")) {
    const std::string name = attr(l, "name");
    if (name.empty()) return "a <link> has no name" + lineOf(l);
    if (!links.emplace(name, l).second)
      return "duplicate link name " + quote(name) + " (lines " +
             std::to_string(links[name]->GetLineNum()) + " and " + std::to_string(l->GetLineNum()) + ")";
    const std::string err = checkOrigins(l);
    if (!err.empty()) return err;
    capsules(l, "collision", &out->capsule_collisions[name]);
    capsules(l, "visual", &out->capsule_visuals[name]);
    std::array<double, 4> rgba;
    if (visualColor(l, named_colors, &rgba)) out->link_color[name] = rgba;
  }
  if (links.empty()) return "the <robot> has no <link>";
  for (XMLElement* j = robot->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
    const std::string name = attr(j, "name");
    if (name.empty()) return "a <joint> has no name" + lineOf(j);
    const std::string jn = "joint " + quote(name);
    if (!joints.emplace(name, j).second)
      return "duplicate joint name " + quote(name) + " (lines " +
             std::to_string(joints[name]->GetLineNum()) + " and " + std::to_string(j->GetLineNum()) + ")";
    std::string ends[2];
    const char* tags[2] = {"parent", "child"};
    for (int k = 0; k < 2; ++k) {
      const XMLElement* e = j->FirstChildElement(tags[k]);
      if (!e || attr(e, "link").empty())
        return jn + lineOf(j) + ": no <" + tags[k] + " link=\"...\"/>";
      ends[k] = attr(e, "link");
      if (!links.count(ends[k]))
        return jn + ": " + tags[k] + " link " + quote(ends[k]) + " is not defined by a <link>";
    }
    if (ends[0] == ends[1]) return jn + ": joins link " + quote(ends[0]) + " to itself (a cycle)";
    auto [it, fresh] = parent_joint.emplace(ends[1], name);
    if (!fresh)
      return "link " + quote(ends[1]) + " is the child of two joints, " + quote(it->second) +
             " and " + quote(name) + " (the links must form a tree)";
    joint_parent[name] = ends[0];
    const std::string err = checkOrigins(j);
    if (!err.empty()) return err;
    if (attr(j, "type") == "spherical") {
      j->SetAttribute("type", "floating");
      out->spherical_joints.insert(name);
      const std::string limit_error = readSphericalLimit(j, name, out);
      if (!limit_error.empty()) return limit_error;
    }
    // <dynamics/> without damping or friction: both 0 (URDF's default; urdfdom rejects it).
    if (XMLElement* d = j->FirstChildElement("dynamics")) {
      bool has = false;
      for (const tinyxml2::XMLAttribute* a = d->FirstAttribute(); a; a = a->Next()) {
        const std::string an = a->Name();
        if (an == "damping" || an == "friction") has = true;
        else out->notes.push_back(jn + ": <dynamics> attribute " + quote(an) +
                                  " ignored (only damping and friction are used)");
      }
      if (!has) {
        d->SetAttribute("damping", "0");
        out->notes.push_back(jn + ": <dynamics> without damping or friction, both taken as 0");
      }
    }
  }
  // Cycles: walk up from every link; a walk longer than the joint count loops.
  for (const auto& [link, _] : links) {
    std::string at = link, path;
    for (size_t steps = 0; parent_joint.count(at); ++steps) {
      const std::string& j = parent_joint.at(at);
      if (steps > joints.size())
        return "joint " + quote(j) + " is part of a cycle through link " + quote(at) +
               " (the links must form a tree)";
      at = joint_parent.at(j);
    }
  }
  std::vector<std::string> roots;
  for (const auto& [link, _] : links)
    if (!parent_joint.count(link)) roots.push_back(link);
  if (roots.size() > 1) {
    std::string names;
    for (const auto& r : roots) names += (names.empty() ? "" : ", ") + quote(r);
    return "several links have no parent joint (" + names + "); a URDF has one root link";
  }

  // ---- <gazebo reference="..."> extensions
  std::set<std::string> own_material;  // links with a <ragdoll_sim:material>
  for (XMLElement* g = robot->FirstChildElement("gazebo"); g; g = g->NextSiblingElement("gazebo")) {
    const std::string ref = attr(g, "reference");
    if (ref.empty()) continue;
    if (joints.count(ref)) {
      const XMLElement* p = g->FirstChildElement("preserveFixedJoint");
      if (p && p->GetText() && std::string(p->GetText()).find("true") != std::string::npos)
        out->preserved_fixed.insert(ref);
      continue;
    }
    if (!links.count(ref)) {
      out->notes.push_back("<gazebo reference=" + quote(ref) + "> names no link or joint; ignored");
      continue;
    }
    readDampingFactor(g, ref, out);
    const std::string own = trimmed(g->FirstChildElement("ragdoll_sim:material")
                                        ? g->FirstChildElement("ragdoll_sim:material")->GetText()
                                        : nullptr);
    const std::string script = trimmed(g->FirstChildElement("material")
                                           ? g->FirstChildElement("material")->GetText()
                                           : nullptr);
    if (!own.empty()) {
      out->link_material[ref] = own;
      own_material.insert(ref);
    } else if (!script.empty() && !own_material.count(ref)) {
      out->link_material[ref] = script;  // the named material wins, in whichever block it is
    }
    double mu[2];
    int n = 0;
    for (const char* tag : {"mu1", "mu2"}) {
      const XMLElement* e = g->FirstChildElement(tag);
      if (!e) continue;
      double v;
      if (parseDouble(e->GetText(), &v) && v >= 0) mu[n++] = v;
      else out->notes.push_back("<gazebo reference=" + quote(ref) + "> <" + tag +
                                "> is not a number >= 0; ignored");
    }
    if (n == 0) continue;
    const double m = n == 2 ? 0.5 * (mu[0] + mu[1]) : mu[0];
    out->link_friction[ref] = m;
    if (n == 2 && mu[0] != mu[1]) {
      std::ostringstream os;
      os << "link " << quote(ref) << ": <gazebo> mu1 " << mu[0] << " and mu2 " << mu[1]
         << " (anisotropic) replaced by their mean " << m;
      out->notes.push_back(os.str());
    }
  }

  tinyxml2::XMLPrinter printer;
  doc.Print(&printer);
  out->text = printer.CStr();
  return "";
}

}  // namespace urdf_xml
}  // namespace ragdoll_sim
