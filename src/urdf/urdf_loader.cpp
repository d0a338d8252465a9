// URDF -> RagdollDef with urdfdom.
//
// Steps: a tinyxml2 pre-pass (urdf_xml.hpp: malformed files, capsules, spherical joints,
// <gazebo> tags), parse (urdfdom's console_bridge errors are captured into the result), group
// links joined by fixed joints (and moving joints that lead only to massless links) into one
// body (mass properties and shapes lumped into the top link), fold chains of 2-3 revolute
// joints through massless geometry-less links into ball joints, turn the remaining revolute /
// continuous joints into hinges, prismatic into sliders, spherical into free balls, and
// compute rest poses. Each joint's <dynamics> damping / friction goes to its axis
// (RagdollJointDef::damping, ::friction). Planar and (non-root) floating joints are refused.
// The pieces live in the files listed in loader.hpp.
#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <filesystem>
#include <mutex>
#include <set>
#include <sstream>

#include "input_file.hpp"
#include "loader.hpp"

namespace ragdoll_sim {

namespace {

// Collects console_bridge messages (urdfdom reports parse errors only there) during a parse.
class LogCapture : public console_bridge::OutputHandler {
 public:
  LogCapture() : previous_(console_bridge::getOutputHandler()) {
    console_bridge::useOutputHandler(this);
  }
  ~LogCapture() override { console_bridge::useOutputHandler(previous_); }
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR)
      errors_ += (errors_.empty() ? "" : "; ") + text;
  }
  const std::string& errors() const { return errors_; }

 private:
  console_bridge::OutputHandler* previous_;
  std::string errors_;
};

}  // namespace

namespace urdf_load {

RagdollDef Loader::run() {
  def_.name = model_.getName();
  urdf::LinkConstSharedPtr root = model_.getRoot();
  // A massless root ("world") floating-jointed to the robot: the robot is the free root.
  if (root->child_joints.size() == 1 && root->child_joints[0]->type == urdf::Joint::FLOATING &&
      !extras_.spherical_joints.count(root->child_joints[0]->name) && massless(*root)) {
    def_.notes.push_back("floating joint " + quote(root->child_joints[0]->name) +
                         " dropped: " + quote(root->child_joints[0]->child_link_name) +
                         " is the free root");
    root = model_.getLink(root->child_joints[0]->child_link_name);
  }
  // Gazebo's convention for a robot bolted down: a root link "world" fixed-jointed to it. The
  // robot's link is the root, pinned where it is spawned.
  if (root->name == "world" && root->child_joints.size() == 1 &&
      root->child_joints[0]->type == urdf::Joint::FIXED) {
    const urdf::JointConstSharedPtr& j = root->child_joints[0];
    std::string note = "link 'world' and fixed joint " + quote(j->name) + " dropped: " +
                       quote(j->child_link_name) + " is the root, pinned where it is spawned (a fixed base)";
    const Transform o = toTransform(j->parent_to_joint_origin_transform, "joint " + quote(j->name));
    if (o.p.norm() > 0 || o.q.vec().norm() > 0)
      note += "; the joint's <origin> is not applied (the spawn pose places " + quote(j->child_link_name) + ")";
    if (!root->collision_array.empty() || !root->visual_array.empty() || !massless(*root))
      note += "; the geometry and mass of link 'world' are ignored";
    def_.notes.push_back(note);
    def_.fixed_base = true;
    root = model_.getLink(j->child_link_name);
  }
  addGroup(root);
  def_.root = 0;
  emitBody(0, Transform(), -1);
  excludeRestOverlaps();
  if (std::all_of(def_.links.begin(), def_.links.end(), [](const LinkDef& l) { return l.shapes.empty(); }))
    def_.warnings.push_back(
        "no collision geometry on any link: the model will fall through the ground (give a link a "
        "<collision>; a <sphere radius=\"0\"/> is a contact point)");
  // Lumped links of bodies become fixed frames (links folded into ball chains have theirs).
  for (const auto& [name, placed] : placement_) {
    const Group& grp = groups_[size_t(placed.first)];
    if (grp.def_index >= 0 && grp.top->name != name)
      def_.fixed_frames.push_back({name, grp.def_index, placed.second});
  }
  if (folded_links_ > 0) {
    std::ostringstream os;
    os << folded_links_ << " massless chain links folded into ball joints (" << folded_mass_
       << " kg dropped)";
    def_.notes.push_back(os.str());
  }
  return std::move(def_);
}

// Links whose shapes already touch in the rest pose (fitted boxes, overlapping covers of a
// hip's motor stack) would push each other apart from the first step: they never collide
// (what an SRDF's "Default" pairs do). Found with one vanishing step in a world without
// gravity or ground.
void Loader::excludeRestOverlaps() {
  WorldDef wd;
  wd.gravity = Vec3::Zero();
  wd.sleep.enabled = false;
  World world(wd);
  const Ragdoll r = spawnRagdoll(world, def_, Transform());
  world.step(1e-9);
  std::set<std::pair<int, int>> pairs;
  for (const ContactInfo& c : world.contacts()) {
    if (c.separation >= 0) continue;
    int a = -1, b = -1;
    for (size_t i = 0; i < r.bodies.size(); ++i) {
      if (r.bodies[i] == c.body_a) a = int(i);
      if (r.bodies[i] == c.body_b) b = int(i);
    }
    if (a >= 0 && b >= 0) pairs.emplace(std::min(a, b), std::max(a, b));
  }
  std::string names;
  for (const auto& [a, b] : pairs) {
    if (std::find(def_.no_collide.begin(), def_.no_collide.end(), std::make_pair(a, b)) != def_.no_collide.end() ||
        std::find(def_.no_collide.begin(), def_.no_collide.end(), std::make_pair(b, a)) != def_.no_collide.end())
      continue;
    def_.no_collide.emplace_back(a, b);
    names += (names.empty() ? "" : ", ") + def_.links[a].name + "/" + def_.links[b].name;
  }
  if (!names.empty())
    def_.notes.push_back("links overlapping in the rest pose never collide: " + names);
}

}  // namespace urdf_load

using urdf_load::LoadError;
using urdf_load::Loader;
using urdf_load::quote;

UrdfLoadResult loadUrdfString(const std::string& xml, const UrdfLoadOptions& options) {
  UrdfLoadResult result;
  urdf_xml::Extras extras;
  result.error = urdf_xml::preprocess(xml, &extras);
  if (!result.error.empty()) return result;
  urdf::ModelInterfaceSharedPtr model;
  {
    static std::mutex mutex;  // the console_bridge output handler is global
    std::lock_guard<std::mutex> lock(mutex);
    LogCapture capture;
    model = urdf::parseURDF(extras.text);
    if (!model || !model->getRoot()) {
      result.error = "URDF <robot> could not be parsed: " +
                     (capture.errors().empty() ? std::string("unknown error") : capture.errors());
      return result;
    }
  }
  try {
    result.def = Loader(*model, extras, options).run();
    result.def.notes.insert(result.def.notes.begin(), extras.notes.begin(), extras.notes.end());
    result.ok = true;
  } catch (const LoadError& e) {
    result.error = e.what();
  }
  return result;
}

UrdfLoadResult loadUrdfFile(const std::string& path, UrdfLoadOptions options, std::string* text) {
  std::string xml;
  std::string error;
  if (!readInputFile(path, "URDF file", &xml, &error)) {
    UrdfLoadResult result;
    result.error = error;
    return result;
  }
  if (options.base_dir.empty())
    options.base_dir = std::filesystem::path(path).parent_path().string();
  UrdfLoadResult result = loadUrdfString(xml, options);
  if (!result.ok) result.error = path + ": " + result.error;
  if (text) *text = std::move(xml);
  return result;
}

}  // namespace ragdoll_sim
