// The pre-pass over one <model>: nested <include>s expanded, visuals reduced to their colour,
// sensors and plugins dropped, collisions SDFormat cannot give a shape to skipped, names that
// SDFormat 12 refuses (reserved, repeated, with spaces) changed, every <pose> checked.
#include <tinyxml2.h>

#include <cmath>
#include <cstring>

#include "world_load.hpp"

namespace ragdoll_sim {
namespace world_load {

using tinyxml2::XMLElement;

namespace {

std::string attr(const XMLElement* e, const char* name) {
  const char* v = e->Attribute(name);
  return v ? v : "";
}

bool oneOf(const std::string& s, std::initializer_list<const char*> names) {
  for (const char* n : names)
    if (s == n) return true;
  return false;
}

// SDFormat 12 reserves "world" and names of the form __x__ for its own frames.
bool reservedName(const std::string& n) {
  return n == "world" || (n.size() >= 4 && n.rfind("__", 0) == 0 && n.compare(n.size() - 2, 2, "__") == 0);
}

void fixReservedName(XMLElement* e, const char* suffix, PrepareContext& ctx) {
  const std::string n = attr(e, "name");
  if (!reservedName(n)) return;
  const std::string fixed = n + suffix;
  ctx.out->warnings.push_back(describe(e) + ": the name is reserved in SDF; renamed to " + quote(fixed));
  e->SetAttribute("name", fixed.c_str());
}

bool readColor(const XMLElement* material, Rgba* out) {
  for (const char* tag : {"diffuse", "ambient"}) {
    const XMLElement* c = material->FirstChildElement(tag);
    std::vector<double> v;
    std::istringstream is(c && c->GetText() ? c->GetText() : "");
    for (double d; is >> d;) v.push_back(d);
    if (v.size() < 3 || v.size() > 4) continue;
    bool ok = true;
    for (double d : v) ok &= std::isfinite(d) && d >= 0 && d <= 1;
    if (!ok) continue;
    *out = {v[0], v[1], v[2], v.size() == 4 ? v[3] : 1.0};
    return true;
  }
  return false;
}

// <script><name>Gazebo/Wood</name>, or SDF 1.4's bare <script>Gazebo/Wood</script>; "" if none.
std::string scriptName(const XMLElement* material) {
  const XMLElement* script = material->FirstChildElement("script");
  if (!script) return "";
  const XMLElement* name = script->FirstChildElement("name");
  const char* t = name ? name->GetText() : script->FirstChildElement() ? nullptr : script->GetText();
  std::string s = t ? t : "";
  const size_t b = s.find_first_not_of(" \t\r\n"), e = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

// One collision: false when it is skipped (removed here).
bool prepareCollision(XMLElement* c, PrepareContext& ctx) {
  XMLElement* geometry = c->FirstChildElement("geometry");
  XMLElement* shape = geometry ? geometry->FirstChildElement() : nullptr;
  if (!shape) throw LoadError(describe(c) + ": no <geometry> shape");
  const std::string kind = shape->Name();
  if (oneOf(kind, {"box", "sphere", "cylinder", "capsule", "ellipsoid", "plane", "mesh"})) return true;
  if (kind == "empty") {
    c->Parent()->DeleteChild(c);
    return false;
  }
  if (oneOf(kind, {"heightmap", "polyline", "image"})) {
    ctx.out->warnings.push_back(describe(c) + ": <" + kind + "> geometry is not simulated; skipped");
    ++ctx.out->skipped;
    c->Parent()->DeleteChild(c);
    return false;
  }
  throw LoadError(describe(shape) + ": unknown geometry <" + kind +
                  "> (box, sphere, cylinder, capsule, ellipsoid, plane, mesh, heightmap, polyline)");
}

void prepareLink(XMLElement* link, PrepareContext& ctx, const std::string& scope,
                 std::map<std::string, LinkLook>* looks) {
  fixReservedName(link, "_link", ctx);
  const std::string name = scope + attr(link, "name");
  for (XMLElement* e = link->FirstChildElement(); e;) {
    XMLElement* next = e->NextSiblingElement();
    const std::string n = e->Name();
    if (n == "visual") {
      XMLElement* m = e->FirstChildElement("material");
      if (m) {
        LinkLook& look = (*looks)[name];
        if (!look.has_color) look.has_color = readColor(m, &look.color);
        if (look.material.empty()) look.material = scriptName(m);
      }
      link->DeleteChild(e);  // drawn from the collisions, in its colour
    } else if (n == "collision") {
      prepareCollision(e, ctx);
    } else if (oneOf(n, {"sensor", "light", "projector", "audio_source", "audio_sink", "battery",
                         "particle_emitter", "plugin"})) {
      dropElement(e, ctx);
    }
    e = next;
  }
}

void checkPoses(XMLElement* root) {
  std::vector<XMLElement*> todo{root};
  while (!todo.empty()) {
    XMLElement* e = todo.back();
    todo.pop_back();
    for (XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) todo.push_back(c);
    if (std::strcmp(e->Name(), "pose") != 0) continue;
    std::vector<double> v;
    if (!parsePose(e->GetText(), &v))
      throw LoadError(describe(e) + ": " + quote(e->GetText() ? e->GetText() : "") +
                      " is not 6 finite numbers (x y z roll pitch yaw)");
  }
}

}  // namespace

bool prepareModel(XMLElement* model, PrepareContext& ctx, const std::string& scope,
                  std::map<std::string, LinkLook>* looks) {
  checkPoses(model);
  // First the model's own children: includes expanded, what is not simulated dropped.
  std::vector<std::pair<XMLElement*, std::string>> nested;  // models, and their include's file
  for (XMLElement* e = model->FirstChildElement(); e;) {
    XMLElement* next = e->NextSiblingElement();
    const std::string n = e->Name();
    if (n == "include") {
      std::string file;
      if (XMLElement* m = expandInclude(e, ctx, &file)) nested.emplace_back(m, file);
    } else if (n == "model") {
      nested.emplace_back(e, "");
    } else if (oneOf(n, {"plugin", "gripper", "actor", "light"})) {
      dropElement(e, ctx);
    }
    e = next;
  }
  uniqueModelNames(model, ctx);
  for (XMLElement* l = model->FirstChildElement("link"); l; l = l->NextSiblingElement("link"))
    prepareLink(l, ctx, scope, looks);
  // SDFormat 12 wants joint names apart from link, frame and nested model names.
  std::set<std::string> names;
  for (XMLElement* e = model->FirstChildElement(); e; e = e->NextSiblingElement())
    if (std::strcmp(e->Name(), "joint") != 0 && e->Attribute("name")) names.insert(attr(e, "name"));
  for (XMLElement* j = model->FirstChildElement("joint"); j; j = j->NextSiblingElement("joint")) {
    fixReservedName(j, "_joint", ctx);
    std::string n = attr(j, "name");
    if (names.count(n)) {
      while (names.count(n)) n += "_joint";
      ctx.out->warnings.push_back(describe(j) + ": the name is taken by a sibling; renamed to " + quote(n));
      j->SetAttribute("name", n.c_str());
    }
    names.insert(n);
    while (XMLElement* s = j->FirstChildElement("sensor")) dropElement(s, ctx);
  }
  bool physical = model->FirstChildElement("link") != nullptr;
  for (auto& [m, file] : nested) {
    if (!file.empty()) ctx.include_stack.push_back(file);
    const bool ok = prepareModel(m, ctx, scope + attr(m, "name") + "::", looks);
    if (!file.empty()) ctx.include_stack.pop_back();
    if (ok) {
      physical = true;
    } else {
      ctx.out->warnings.push_back(describe(m) + ": no link left in it; skipped");
      ++ctx.out->skipped;
      model->DeleteChild(m);
    }
  }
  return physical;
}

}  // namespace world_load
}  // namespace ragdoll_sim
