// The pre-pass over a world document (tinyxml2): one clear error for what is not a world,
// <include>s expanded here (SDFormat 12 neither detects a cycle of them nor forgives a missing
// one), and the world-level elements that are not simulated dropped with one note per kind.
#include <tinyxml2.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "input_file.hpp"
#include "world_load.hpp"

namespace ragdoll_sim {
namespace world_load {

using tinyxml2::XMLElement;
namespace fs = std::filesystem;

namespace {

std::string attr(const XMLElement* e, const char* name) {
  const char* v = e->Attribute(name);
  return v ? v : "";
}

std::string text(const XMLElement* e) {
  const char* t = e ? e->GetText() : nullptr;
  std::string s = t ? t : "";
  const size_t b = s.find_first_not_of(" \t\r\n"), end = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? "" : s.substr(b, end - b + 1);
}

XMLElement* child(XMLElement* e, const char* name) { return e ? e->FirstChildElement(name) : nullptr; }

// "1.6" -> 1.6; unparsable -> 0.
double versionOf(const XMLElement* sdf) {
  const std::string v = attr(sdf, "version");
  char* end = nullptr;
  const double d = std::strtod(v.c_str(), &end);
  return end == v.c_str() ? 0.0 : d;
}

bool threeFinite(const std::string& s, Vec3* v) {
  std::istringstream is(s);
  double x, y, z;
  if (!(is >> x >> y >> z)) return false;
  std::string extra;
  if (is >> extra) return false;
  *v = Vec3(x, y, z);
  return v->allFinite();
}

std::string printed(const XMLElement* e) {
  tinyxml2::XMLPrinter printer(nullptr, true);  // compact
  e->Accept(&printer);
  return printer.CStr();
}

// The world's gravity and step size; <physics> itself is not handed to SDFormat.
void readPhysics(XMLElement* world, PreparedWorld* out) {
  XMLElement* physics = child(world, "physics");
  XMLElement* g = child(world, "gravity");
  if (!g) g = child(physics, "gravity");  // before SDF 1.6
  if (g) {
    Vec3 v = Vec3::Zero();
    if (!threeFinite(text(g), &v))
      throw LoadError(describe(g) + ": " + quote(text(g)) + " is not three finite numbers");
    out->gravity = v;
  }
  if (XMLElement* s = child(physics, "max_step_size")) {
    char* end = nullptr;
    const std::string t = text(s);
    const double v = std::strtod(t.c_str(), &end);
    if (end == t.c_str() || !std::isfinite(v) || v <= 0)
      throw LoadError(describe(s) + ": " + quote(t) + " is not a finite number > 0");
    out->has_max_step_size = true;
    out->max_step_size = v;
  }
}

// Poses of a top-level model: six numbers relative to the world, else not plain.
void topLevelPose(XMLElement* model, PreparedModel* m) {
  XMLElement* pose = child(model, "pose");
  if (!pose) {
    m->plain_pose = true;
    return;
  }
  const std::string rel = attr(pose, "relative_to");
  if (pose->FirstAttribute() && !(rel == "world" && !pose->FirstAttribute()->Next())) return;
  std::vector<double> v;
  if (!parsePose(pose->GetText(), &v) || v.size() != 6) return;
  m->plain_pose = true;
  m->pose = Transform(Vec3(v[0], v[1], v[2]), quatFromRpy(v[3], v[4], v[5]));
}

// Models (itself and nested ones), links and collisions in a prepared model.
void countElements(const XMLElement* model, PreparedModel* pm) {
  std::vector<const XMLElement*> todo{model};
  while (!todo.empty()) {
    const XMLElement* e = todo.back();
    todo.pop_back();
    const char* n = e->Name();
    pm->models += std::strcmp(n, "model") == 0;
    pm->links += std::strcmp(n, "link") == 0;
    pm->collisions += std::strcmp(n, "collision") == 0;
    if (std::strcmp(n, "model") == 0 || std::strcmp(n, "link") == 0)
      for (const XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) todo.push_back(c);
  }
}

}  // namespace

std::string describe(const XMLElement* e) {
  std::string path;
  for (const XMLElement* p = e; p; p = p->Parent() ? p->Parent()->ToElement() : nullptr) {
    const std::string n = p->Name();
    if (n == "sdf") break;
    const std::string part = p->Attribute("name") ? n + " " + quote(attr(p, "name")) : "<" + n + ">";
    path = part + (path.empty() ? "" : " " + path);
    if (n == "world") break;
  }
  return path;
}

bool parsePose(const char* t, std::vector<double>* v) {
  v->clear();
  std::istringstream is(t ? t : "");
  std::string tok;
  while (is >> tok) {
    char* end = nullptr;
    const double d = std::strtod(tok.c_str(), &end);
    if (*end != '\0' || !std::isfinite(d)) return false;
    v->push_back(d);
  }
  return v->empty() || v->size() == 6 || v->size() == 7;
}

void normalizeVersion(XMLElement* root, double version) {
  std::vector<XMLElement*> todo{root};
  while (!todo.empty()) {
    XMLElement* e = todo.back();
    todo.pop_back();
    for (XMLElement* c = e->FirstChildElement(); c; c = c->NextSiblingElement()) todo.push_back(c);
    const std::string n = e->Name();
    if (n == "pose" && e->Attribute("frame")) {
      // SDF 1.7 renamed it; an empty one (what Gazebo 9 saves) means the default frame.
      const std::string f = attr(e, "frame");
      e->DeleteAttribute("frame");
      if (!f.empty() && !e->Attribute("relative_to")) e->SetAttribute("relative_to", f.c_str());
    } else if ((n == "axis" || n == "axis2") && e->Parent() && e->Parent()->ToElement() &&
               std::strcmp(e->Parent()->ToElement()->Name(), "joint") == 0) {
      // Before 1.5 an axis was in the model frame; 1.5 and 1.6 say so with
      // use_parent_model_frame; from 1.7 on, xyz@expressed_in.
      XMLElement* use = e->FirstChildElement("use_parent_model_frame");
      bool model_frame = version < 1.5 - 1e-9;
      if (use) {
        const std::string t = text(use);
        model_frame = t == "1" || t == "true" || t == "True" || t == "TRUE";
        e->DeleteChild(use);
      }
      XMLElement* xyz = e->FirstChildElement("xyz");
      if (model_frame && xyz && !xyz->Attribute("expressed_in")) xyz->SetAttribute("expressed_in", "__model__");
    }
  }
}

void dropElement(XMLElement* e, PrepareContext& ctx) {
  ++ctx.dropped_kinds[e->Name()];
  e->Parent()->DeleteChild(e);
}

void uniqueModelNames(XMLElement* parent, PrepareContext& ctx) {
  std::set<std::string> taken;
  std::vector<XMLElement*> models;
  for (XMLElement* m = parent->FirstChildElement("model"); m; m = m->NextSiblingElement("model")) {
    models.push_back(m);
    taken.insert(attr(m, "name"));
  }
  std::set<std::string> used;
  for (XMLElement* m : models) {
    const std::string name = attr(m, "name");
    std::string fixed = name;
    std::replace(fixed.begin(), fixed.end(), ' ', '_');
    if (fixed.empty()) fixed = "model";
    if (used.count(fixed) || (fixed != name && taken.count(fixed))) {
      int k = 2;
      while (used.count(fixed + "_" + std::to_string(k)) || taken.count(fixed + "_" + std::to_string(k))) ++k;
      fixed += "_" + std::to_string(k);
    }
    used.insert(fixed);
    if (fixed != name) {
      ctx.out->warnings.push_back(describe(m) + ": renamed to " + quote(fixed) +
                                  (name.find(' ') != std::string::npos ? " (spaces in the name)"
                                                                       : " (the name is taken)"));
      m->SetAttribute("name", fixed.c_str());
    }
  }
}

XMLElement* expandInclude(XMLElement* inc, PrepareContext& ctx, std::string* included) {
  const std::string uri = text(child(inc, "uri"));
  const std::string where = describe(inc) + " " + (uri.empty() ? "without <uri>" : oneLine(uri));
  auto unresolved = [&](const std::string& why) -> XMLElement* {
    const std::string msg = "<include> " + where + ": " + why;
    if (ctx.options->strict) throw LoadError(msg + " (strict: unresolved includes are errors)");
    ctx.out->warnings.push_back(msg + "; skipped");
    ++ctx.out->unresolved;
    inc->Parent()->DeleteChild(inc);
    return nullptr;
  };
  if (uri.empty()) return unresolved("no <uri>");
  if (int(ctx.include_stack.size()) > ctx.options->max_include_depth)
    throw LoadError("<include> " + where + ": includes nested deeper than " +
                    std::to_string(ctx.options->max_include_depth));
  const std::string base = ctx.include_stack.empty() ? ctx.options->base_dir
                                                     : fs::path(ctx.include_stack.back()).parent_path().string();
  std::string why, mapped;
  const std::string file = ctx.resolver->modelFile(uri, base, &why, &mapped);
  if (file.empty()) return unresolved(why);
  if (!mapped.empty()) ctx.out->warnings.push_back("<include> " + where + ": " + mapped);
  std::error_code ec;
  const std::string canon = fs::weakly_canonical(file, ec).string();
  if (std::find(ctx.include_stack.begin(), ctx.include_stack.end(), canon) != ctx.include_stack.end())
    throw LoadError("<include> " + where + ": a cycle of includes (" + canon + " includes itself)");
  std::string content, error;
  if (!readInputFile(file, "included model", &content, &error)) return unresolved(error);
  ctx.included_bytes += content.size();
  if (++ctx.includes > kMaxIncludes || ctx.included_bytes > kMaxIncludedBytes)
    throw LoadError("<include> " + where + ": the world's includes expand to more than " +
                    std::to_string(kMaxIncludes) + " models or " + std::to_string(kMaxIncludedBytes >> 20) +
                    " MiB");
  tinyxml2::XMLDocument piece;
  if (piece.Parse(content.data(), content.size()) != tinyxml2::XML_SUCCESS)
    return unresolved(file + " is not well-formed XML: " + piece.ErrorName() + " at line " +
                      std::to_string(piece.ErrorLineNum()));
  XMLElement* sdf = piece.RootElement();
  XMLElement* model = sdf && std::strcmp(sdf->Name(), "sdf") == 0 ? sdf->FirstChildElement("model") : nullptr;
  if (!model) {
    // model://sun and the like: a light (or an actor) in a model folder.
    XMLElement* other = sdf ? sdf->FirstChildElement() : nullptr;
    if (other && (std::strcmp(other->Name(), "light") == 0 || std::strcmp(other->Name(), "actor") == 0)) {
      ++ctx.dropped_kinds[other->Name()];
      inc->Parent()->DeleteChild(inc);
      return nullptr;
    }
    return unresolved(file + " holds no <sdf><model>");
  }
  const double version = versionOf(sdf);
  normalizeVersion(model, version);
  ctx.out->version = std::max(ctx.out->version, std::min(version, kNewestSdfVersion));

  // The overrides Gazebo applies: <name>, <pose> (replaces the model's), <static>.
  if (XMLElement* n = child(inc, "name")) model->SetAttribute("name", text(n).c_str());
  if (XMLElement* p = child(inc, "pose")) {
    if (XMLElement* own = child(model, "pose")) model->DeleteChild(own);
    model->InsertFirstChild(p->DeepClone(model->GetDocument()));
  }
  if (XMLElement* s = child(inc, "static")) {
    if (XMLElement* own = child(model, "static")) model->DeleteChild(own);
    model->InsertEndChild(s->DeepClone(model->GetDocument()));
  }
  // SDF 1.8 moved <include><placement_frame> onto the model; it changes what <pose> places.
  if (XMLElement* pf = child(inc, "placement_frame")) {
    model->SetAttribute("placement_frame", text(pf).c_str());
    ctx.out->version = std::max(ctx.out->version, 1.8);
  }
  while (XMLElement* e = child(inc, "plugin")) dropElement(e, ctx);
  XMLElement* copy = model->DeepClone(inc->GetDocument())->ToElement();
  inc->Parent()->InsertAfterChild(inc, copy);
  inc->Parent()->DeleteChild(inc);
  *included = canon;
  return copy;
}

void prepareWorld(const std::string& content, const std::string& file, const WorldLoadOptions& options,
                  const Resolver& resolver, PreparedWorld* out) {
  *out = PreparedWorld();
  if (content.find_first_not_of(" \t\r\n") == std::string::npos) throw LoadError("the world file is empty");
  tinyxml2::XMLDocument doc;
  if (doc.Parse(content.data(), content.size()) != tinyxml2::XML_SUCCESS)
    throw LoadError("the world file is not well-formed XML: " + std::string(doc.ErrorName()) +
                    " at line " + std::to_string(doc.ErrorLineNum()));
  XMLElement* sdf = doc.RootElement();
  if (!sdf || std::strcmp(sdf->Name(), "sdf") != 0)
    throw LoadError("the world file's root element is <" + std::string(sdf ? sdf->Name() : "") +
                    ">, expected <sdf>");
  const double version = versionOf(sdf);
  if (!(version >= 1.0))
    throw LoadError("<sdf version=" + quote(attr(sdf, "version")) + ">: not an SDF version");
  XMLElement* world = sdf->FirstChildElement("world");
  if (!world) throw LoadError("<sdf> holds no <world> (a model file is not a world)");
  if (world->NextSiblingElement("world"))
    out->warnings.push_back("<sdf> holds several <world>s; only the first, " + quote(attr(world, "name")) +
                            ", is loaded");
  if (version > kNewestSdfVersion + 1e-9)
    out->notes.push_back("SDF " + attr(sdf, "version") + " read as " + num(kNewestSdfVersion) +
                         " (the newest SDFormat 12 knows)");
  out->name = attr(world, "name");
  if (out->name.empty()) throw LoadError("<world> has no name");
  out->version = std::max(1.7, std::min(version, kNewestSdfVersion));
  normalizeVersion(world, version);
  readPhysics(world, out);

  PrepareContext ctx{&options, &resolver, out, {}, {}, {}, 0, 0};
  if (!file.empty()) {
    std::error_code ec;
    ctx.include_stack.push_back(fs::weakly_canonical(file, ec).string());
  }
  // Expand the world's own includes first, so that renaming sees every model.
  for (XMLElement* e = world->FirstChildElement(); e;) {
    XMLElement* next = e->NextSiblingElement();
    const std::string n = e->Name();
    if (n == "include") {
      std::string included;
      if (XMLElement* m = expandInclude(e, ctx, &included)) ctx.included_from[m] = included;
    } else if (n == "model" || n == "frame") {
      if (n == "frame") out->models_independent = false;
    } else if (n != "physics" && n != "gravity") {
      dropElement(e, ctx);
    }
    e = next;
  }
  std::map<const XMLElement*, std::string> written;
  for (XMLElement* m = world->FirstChildElement("model"); m; m = m->NextSiblingElement("model"))
    written[m] = attr(m, "name");
  uniqueModelNames(world, ctx);
  for (XMLElement* m = world->FirstChildElement("model"); m; m = m->NextSiblingElement("model")) {
    // A top-level include's own file is on the stack while its model is prepared.
    const auto from = ctx.included_from.find(m);
    if (from != ctx.included_from.end()) ctx.include_stack.push_back(from->second);
    PreparedModel pm;
    pm.file_name = written[m];
    pm.name = attr(m, "name");
    const bool physical = prepareModel(m, ctx, "", &pm.looks);
    if (from != ctx.included_from.end()) ctx.include_stack.pop_back();
    if (!physical) {
      out->warnings.push_back(describe(m) + ": nothing to simulate left in it (no link); skipped");
      ++out->skipped;
      continue;
    }
    topLevelPose(m, &pm);
    if (XMLElement* p = child(m, "pose"))
      if (p->Attribute("relative_to") && attr(p, "relative_to") != "world") out->models_independent = false;
    pm.xml = printed(m);
    countElements(m, &pm);
    tinyxml2::XMLDocument scratch;
    XMLElement* bare = m->DeepClone(&scratch)->ToElement();
    bare->DeleteAttribute("name");
    if (XMLElement* p = child(bare, "pose")) bare->DeleteChild(p);
    pm.key = printed(bare);
    out->models.push_back(std::move(pm));
  }
  for (XMLElement* f = world->FirstChildElement("frame"); f; f = f->NextSiblingElement("frame"))
    out->frames_xml += printed(f);
  for (const auto& [kind, n] : ctx.dropped_kinds)
    out->notes.push_back(std::to_string(n) + " <" + kind + "> not simulated" +
                         (kind == "plugin" ? " (plugins are not run)" : ""));
}

}  // namespace world_load
}  // namespace ragdoll_sim
