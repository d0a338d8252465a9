// See world_file.hpp. SDFormat 12 spends milliseconds and megabytes on every model it loads, so
// models that differ only in name and pose (generated worlds: thousands of boxes) are handed to
// it once and the others placed from their own pose.
#include <console_bridge/console.h>
#include <sdf/sdf.hh>

#include <cstdio>
#include <filesystem>

#include "input_file.hpp"
#include "world_load.hpp"

namespace ragdoll_sim {
namespace world_load {
namespace {

// SDFormat retries a document it cannot read as URDF, whose parser (urdfdom) writes its errors
// to console_bridge: swallowed while SDFormat runs, the error returned is SDFormat's own.
class QuietConsole : public console_bridge::OutputHandler {
 public:
  QuietConsole() : previous_(console_bridge::getOutputHandler()) { console_bridge::useOutputHandler(this); }
  ~QuietConsole() override { console_bridge::useOutputHandler(previous_); }
  void log(const std::string&, console_bridge::LogLevel, const char*, int) override {}

 private:
  console_bridge::OutputHandler* previous_;
};

// "SDF: model 'm' link 'l' <inertial> <mass>: <message>": SDFormat's XML path in our words.
std::string errorText(const sdf::Error& e) {
  std::string where;
  const std::string path = e.XmlPath().value_or("");
  size_t start = 0;
  while (start < path.size()) {
    size_t end = path.find('/', start);
    // A name may hold a '/': the part ends at a '/' outside [@name="..."].
    const size_t bracket = path.find('[', start);
    if (bracket != std::string::npos && bracket < end) {
      const size_t close = path.find("\"]", bracket);
      end = close == std::string::npos ? std::string::npos : path.find('/', close);
    }
    const std::string part = path.substr(start, end == std::string::npos ? std::string::npos : end - start);
    start = end == std::string::npos ? path.size() : end + 1;
    if (part.empty() || part == "sdf" || part.rfind("world[", 0) == 0) continue;
    const size_t b = part.find("[@name=\"");
    if (b == std::string::npos) {
      where += (where.empty() ? "<" : " <") + part + ">";
    } else {
      const std::string name = part.substr(b + 8, part.size() - b - 8 - 2);
      where += (where.empty() ? "" : " ") + part.substr(0, b) + " " + quote(name);
    }
  }
  return "SDF: " + (where.empty() ? "" : where + ": ") + e.Message();
}

// SDFormat 12 throws sdf::Exception (not a std::exception) where a check of its own fails, e.g.
// converting a SDF 1.7 joint named "a::b": its "Error: ..." line, on one line.
std::string exceptionText(const sdf::Exception& e) {
  const std::string text = e.GetErrorStr();
  const size_t error = text.find("Error: ");
  const size_t begin = error == std::string::npos ? text.find_first_not_of(" \n") : error + 7;
  if (begin == std::string::npos) return "SDF: SDFormat 12 refused the document";
  std::string line = text.substr(begin, text.find('\n', begin) - begin);
  line.erase(line.find_last_not_of(' ') + 1);
  return "SDF: SDFormat 12 refused the document: " + line;
}

Transform transform(const ignition::math::Pose3d& p) {
  return Transform(Vec3(p.Pos().X(), p.Pos().Y(), p.Pos().Z()),
                   Quat(p.Rot().W(), p.Rot().X(), p.Rot().Y(), p.Rot().Z()).normalized());
}

// Model `from` (walked, its <pose> `from_pose`) moved to another model's name, pose and looks.
// The shift between the two <pose>s moves every frame of the model, whatever its placement.
WorldModelDef placed(const WorldModelDef& from, const Transform& from_pose, const PreparedModel& pm) {
  WorldModelDef m = from;
  m.name = pm.name;
  m.file_name = pm.file_name;
  const Transform shift = pm.pose * from_pose.inverse();
  m.pose = shift * from.pose;
  for (WorldLinkDef& l : m.links) {
    l.pose = shift * l.pose;
    const auto look = pm.looks.find(l.name);
    const LinkLook none;
    const LinkLook& k = look == pm.looks.end() ? none : look->second;
    l.has_color = k.has_color;
    l.color = k.has_color ? k.color : WorldLinkDef().color;
    l.visual_material = k.material;
  }
  for (RagdollJointDef& j : m.joints)
    if (j.parent < 0) j.frame_parent = shift * j.frame_parent;
  return m;
}

std::string versionText(double v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "%.1f", v);
  return buf;
}

WorldLoadResult load(const std::string& text, const std::string& file, const WorldLoadOptions& options) {
  WorldLoadResult r;
  try {
    const Resolver resolver(options);
    PreparedWorld pw;
    prepareWorld(text, file, options, resolver, &pw);

    // Models parsed by SDFormat: one per key where the others can be placed from their pose.
    const size_t n = pw.models.size();
    std::vector<size_t> template_of(n);
    std::vector<size_t> parsed;
    std::map<std::string, size_t> by_key;
    for (size_t i = 0; i < n; ++i) {
      const PreparedModel& m = pw.models[i];
      if (pw.models_independent && m.plain_pose) {
        const auto [it, fresh] = by_key.emplace(m.key, i);
        template_of[i] = it->second;
        if (!fresh) continue;
      } else {
        template_of[i] = i;
      }
      parsed.push_back(i);
    }
    // SDFormat's memory grows with every element it instantiates; refuse before it runs.
    int models = 0, links = 0, collisions = 0;
    for (size_t i : parsed) {
      models += pw.models[i].models;
      links += pw.models[i].links;
      collisions += pw.models[i].collisions;
    }
    const double megabytes = kSdfModelMb * models + kSdfLinkMb * links + kSdfCollisionMb * collisions;
    if (megabytes > options.max_sdf_megabytes)
      throw LoadError("the world needs SDFormat 12 to hold about " + std::to_string(int(megabytes)) + " MB (" +
                      std::to_string(models) + " distinct models, " + std::to_string(links) + " links, " +
                      std::to_string(collisions) + " collisions), more than max_sdf_megabytes " +
                      num(options.max_sdf_megabytes) + "; many collisions in few links cost least");
    std::string doc = "<?xml version=\"1.0\"?>\n<sdf version=\"" + versionText(pw.version) +
                      "\"><world name=\"w\">" + pw.frames_xml;
    for (size_t i : parsed) doc += pw.models[i].xml;
    doc += "</world></sdf>";

    sdf::Console::Instance()->SetQuiet(true);  // its errors come back here; warnings are ours
    sdf::Root root;
    sdf::Errors errs;
    {
      QuietConsole quiet;
      errs = root.LoadSdfString(doc);
    }
    if (!errs.empty()) throw LoadError(errorText(errs[0]));
    const sdf::World* world = root.WorldCount() ? root.WorldByIndex(0) : nullptr;
    if (!world) throw LoadError("SDF: no world loaded");

    WorldFileDef& def = r.def;
    def.name = pw.name;
    def.gravity = pw.gravity;
    def.has_max_step_size = pw.has_max_step_size;
    def.max_step_size = pw.max_step_size;
    def.notes = pw.notes;
    def.warnings = pw.warnings;
    if (def.has_max_step_size)
      def.notes.push_back("<physics><max_step_size> " + num(def.max_step_size) +
                          " s is reported, not obeyed (the simulator's own time step is used)");
    int skipped = 0;
    WalkContext ctx{&options, &resolver, &def.warnings, &skipped};
    std::map<size_t, WorldModelDef> walked;
    std::map<size_t, int> skipped_in;  // per parsed model: collisions skipped while walking it
    for (size_t i : parsed) {
      const PreparedModel& pm = pw.models[i];
      const sdf::Model* m = world->ModelByName(pm.name);
      if (!m) throw LoadError("SDF: model " + quote(pm.name) + " not loaded");
      ignition::math::Pose3d p;
      const sdf::Errors perr = m->SemanticPose().Resolve(p, "world");
      if (!perr.empty()) throw LoadError("model " + quote(pm.name) + " <pose>: " + perr[0].Message());
      WorldModelDef& md = walked[i];
      md.name = pm.name;
      md.file_name = pm.file_name;
      const int before = skipped;
      walkModel(*m, transform(p), pm.looks, ctx, &md);
      skipped_in[i] = skipped - before;
    }
    def.models.reserve(n);
    WorldCounts& c = def.counts;
    for (size_t i = 0; i < n; ++i) {
      const size_t t = template_of[i];
      def.models.push_back(t == i ? std::move(walked[i]) : placed(def.models[t], pw.models[t].pose, pw.models[i]));
      const WorldModelDef& m = def.models.back();
      c.skipped += skipped_in[t];
      for (const WorldLinkDef& l : m.links) {
        if (l.is_static) c.static_shapes += int(l.collisions.size());
        else ++c.dynamic_bodies;
      }
    }
    // A collision without its own <ragdoll_sim:material> takes the link's visual material name;
    // here, after the copies of identical models took their own visuals.
    for (WorldModelDef& m : def.models)
      for (WorldLinkDef& l : m.links)
        for (WorldCollisionDef& col : l.collisions)
          if (col.material.empty()) col.material = l.visual_material;
    c.models = int(def.models.size());
    c.skipped += pw.skipped;
    c.unresolved = pw.unresolved;
    r.ok = true;
  } catch (const LoadError& e) {
    r.error = e.what();
  } catch (const sdf::Exception& e) {
    r.error = exceptionText(e);
  }
  if (!r.ok) {
    // One line whatever the file (or SDFormat) put in it.
    for (char& c : r.error)
      if (c == '\n' || c == '\r') c = ' ';
    r.def = WorldFileDef();
  }
  return r;
}

}  // namespace
}  // namespace world_load

WorldLoadResult loadWorldString(const std::string& xml, const WorldLoadOptions& options) {
  return world_load::load(xml, "", options);
}

WorldLoadResult loadWorldFile(const std::string& path, WorldLoadOptions options) {
  WorldLoadResult r;
  std::string text;
  if (!readInputFile(path, "world file", &text, &r.error)) return r;
  if (options.base_dir.empty()) options.base_dir = std::filesystem::path(path).parent_path().string();
  return world_load::load(text, path, options);
}

std::string worldSummaryLine(const WorldFileDef& d) {
  const WorldCounts& c = d.counts;
  return "world=" + d.name + " status=ok models=" + std::to_string(c.models) +
         " static_shapes=" + std::to_string(c.static_shapes) + " dynamic_bodies=" +
         std::to_string(c.dynamic_bodies) + " skipped=" + std::to_string(c.skipped) +
         " unresolved=" + std::to_string(c.unresolved);
}

}  // namespace ragdoll_sim
