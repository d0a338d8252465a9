// libFuzzer target: arbitrary bytes decoded into impulse / force commands (and ragdoll names)
// for the node's ROS-free validation (src/scene/commands.*), on the bundled ragdoll standing on
// a ground plane. The verdict of checkImpulse / checkForce must match the "Command rules" of
// docs/interface.md computed here independently; an accepted command must respect the caps
// after conversion and, applied to the world and stepped as the Scene does (Scene::step), keep
// the state finite and the bodies within reach of the speed cap.
//
// Input: text lines of whitespace-separated tokens, so that a crash artifact reads as text:
//   impulse <link> <frame> px py pz  jx jy jz
//   force   <link> <frame> px py pz  fx fy fz  tx ty tz  duration
//   step    <n>          n physics steps (at most 5 per line, 12 per input), from the first
//                        accepted command on
//   name    <string>     ragdollNameError and splitQualifiedName
// Names and frames take percent escapes (%20 = space, %00 = NUL; a lone % is ""). Numbers go
// through strtod (nan, -inf, 1e999, 0x1p-1074 ...). A line that does not decode is skipped.
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "commands.hpp"
#include "ragdoll_sim/ragdoll.hpp"
#include "ragdoll_sim/urdf_loader.hpp"

#define FUZZ_TARGET_NAME "fuzz_commands"
#include "fuzz_check.hpp"

using namespace ragdoll_sim;
using namespace ragdoll_sim::scene;

namespace {

constexpr double kDt = 1e-3;          // the node's default step
// A step costs milliseconds under ASan + UBSan: few per input keep the search fast.
constexpr int kMaxStepsPerLine = 5;
constexpr int kMaxStepsPerInput = 12;
constexpr size_t kMaxActiveForces = 64;
constexpr double kRel = 1e-9;         // rounding of a rotation applied to a vector at the cap

const RagdollDef& ragdollDef() {
  static const RagdollDef def = [] {
    UrdfLoadResult r = loadUrdfFile(std::string(RAGDOLL_SIM_SOURCE_DIR) + "/urdf/ragdoll.urdf");
    if (!r.ok) {
      std::fprintf(stderr, "fuzz_commands: cannot load urdf/ragdoll.urdf: %s\n", r.error.c_str());
      std::abort();
    }
    return r.def;
  }();
  return def;
}

int hexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return c >= 'a' && c <= 'f' ? c - 'a' + 10 : -1;
}

std::string unescape(const std::string& token) {
  if (token == "%") return "";
  std::string out;
  for (size_t i = 0; i < token.size(); ++i) {
    if (token[i] == '%' && i + 2 < token.size() && hexDigit(token[i + 1]) >= 0 &&
        hexDigit(token[i + 2]) >= 0) {
      out += static_cast<char>(hexDigit(token[i + 1]) * 16 + hexDigit(token[i + 2]));
      i += 2;
    } else {
      out += token[i];
    }
  }
  return out;
}

bool number(const std::string& token, double* out) {
  if (token.empty()) return false;
  char* end = nullptr;
  *out = std::strtod(token.c_str(), &end);
  return end == token.c_str() + token.size();
}

// Reads n numbers from tokens[first..]; false when one is missing or not a number.
bool numbers(const std::vector<std::string>& tokens, size_t first, size_t n, double* out) {
  if (tokens.size() < first + n) return false;
  for (size_t i = 0; i < n; ++i)
    if (!number(tokens[first + i], &out[i])) return false;
  return true;
}

// How far a body may get from its spawn point in `steps` steps: the speed cap's distance plus
// generous room for the position projection (a few cm per sweep). A solver that has blown up
// jumps kilometres within a step or two, long before its numbers overflow to NaN.
double maxTravel(int steps) {
  const WorldDef d;
  return steps * (d.solver.max_linear_speed * kDt + 0.5) + 1.0;
}

bool allFiniteState(const World& world, const Ragdoll& r) {
  for (BodyId b : r.bodies) {
    const BodyState s = world.bodyState(b);
    if (!s.pose.p.allFinite() || !s.pose.q.coeffs().allFinite() ||
        !s.linear_velocity.allFinite() || !s.angular_velocity.allFinite())
      return false;
  }
  return true;
}

// docs/interface.md's "Command rules", written out again: link known (not a dummy), frame
// known, every number finite, magnitudes within the caps, point within the lever arm.
bool expectedOk(const std::string& link, const std::string& frame, const Vec3& point,
                const std::vector<std::pair<Vec3, double>>& capped, double duration,
                const LinkTable& links, const CommandLimits& lim, const World& world,
                const Ragdoll& r) {
  const int index = links.find(link);
  if (index < 0) return false;
  if (frame != "" && frame != "world" && frame != "link") return false;
  for (const auto& [v, cap] : capped)
    if (!v.allFinite() || v.norm() > cap) return false;
  if (!std::isfinite(duration) || !point.allFinite()) return false;
  const Vec3 origin = world.bodyPose(r.bodies[static_cast<size_t>(index)]).p;
  const double lever = frame == "link" ? point.norm() : (point - origin).norm();
  return lever <= lim.max_lever_arm;
}

struct Sim {
  World world;
  Ragdoll ragdoll;
  LinkTable links;
  CommandLimits limits;
  std::vector<ActiveForce> forces;
  int steps = 0;
  bool accepted = false;

  std::vector<Vec3> spawn;  // body origins at spawn

  explicit Sim(const RagdollDef& def) : world(WorldDef()), links(def) {
    BodyDef ground;
    ground.type = BodyType::Static;
    ground.name = "ground";
    ShapeDef plane;
    plane.geometry = Geometry::plane(Vec3::UnitZ(), 0.0);
    world.addShape(world.createBody(ground), plane);
    ragdoll = spawnRagdoll(world, def, Transform(Vec3(0, 0, 1.1), Quat::Identity()));
    for (BodyId b : ragdoll.bodies) spawn.push_back(world.bodyPose(b).p);
  }

  Transform pose(int link) const {
    return world.bodyPose(ragdoll.bodies[static_cast<size_t>(link)]);
  }

  // As Scene::step: active forces at their link points, then the step, then the count.
  // Only once a command was accepted: a ragdoll falling untouched is fuzz_urdf's drop, and
  // steps are what makes an input slow.
  void step(int n) {
    if (!accepted) return;
    for (int i = 0; i < n && steps < kMaxStepsPerInput; ++i, ++steps) {
      for (const ActiveForce& f : forces) {
        const BodyId body = ragdoll.bodies[static_cast<size_t>(f.link)];
        world.applyForce(body, f.force, world.bodyPose(body).apply(f.local_point));
        if (!f.torque.isZero(0.0)) world.applyTorque(body, f.torque);
      }
      world.step(kDt);
      for (ActiveForce& f : forces)
        if (f.steps_left > 0) --f.steps_left;
      forces.erase(std::remove_if(forces.begin(), forces.end(),
                                  [](const ActiveForce& f) { return f.steps_left == 0; }),
                   forces.end());
      FUZZ_CHECK(allFiniteState(world, ragdoll), "state not finite after step %d", steps + 1);
      for (size_t b = 0; b < spawn.size(); ++b) {
        const double d = (world.bodyPose(ragdoll.bodies[b]).p - spawn[b]).norm();
        FUZZ_CHECK(d <= maxTravel(steps + 1), "body %zu is %g m from its spawn point after %d steps",
                   b, d, steps + 1);
      }
    }
  }

  void checkVerdict(const char* kind, const CommandCheck& c, bool expected,
                    const std::string& link) {
    FUZZ_CHECK(c.ok == expected, "%s on '%s': validation said %s, the rules say %s (%s)", kind,
               link.c_str(), c.ok ? "ok" : "rejected", expected ? "ok" : "rejected",
               c.error.c_str());
    if (!c.ok) {
      FUZZ_CHECK(c.error.find("rejected") != std::string::npos, "%s: error '%s'", kind,
                 c.error.c_str());
      return;
    }
    FUZZ_CHECK(c.link == links.find(link), "%s: link index %d for '%s'", kind, c.link,
               link.c_str());
    accepted = true;
  }

  void impulse(const ImpulseCommand& cmd) {
    auto link_pose = [this](int link) { return pose(link); };
    const CommandCheck c = checkImpulse(cmd, links, limits, link_pose);
    checkVerdict("impulse", c,
                 expectedOk(cmd.link, cmd.frame, cmd.point, {{cmd.impulse, limits.max_impulse}},
                            0.0, links, limits, world, ragdoll),
                 cmd.link);
    if (!c.ok) return;
    const Transform p = pose(c.link);
    const WorldImpulse w = toWorldImpulse(cmd, c, p);
    FUZZ_CHECK(w.impulse.allFinite() && w.point.allFinite(), "impulse: world values not finite");
    FUZZ_CHECK(w.impulse.norm() <= limits.max_impulse * (1 + kRel), "impulse: |J| = %g",
               w.impulse.norm());
    FUZZ_CHECK((w.point - p.p).norm() <= limits.max_lever_arm * (1 + kRel) + kRel,
               "impulse: lever %g", (w.point - p.p).norm());
    world.applyLinearImpulse(ragdoll.bodies[static_cast<size_t>(w.link)], w.impulse, w.point);
  }

  void force(const ForceCommand& cmd) {
    auto link_pose = [this](int link) { return pose(link); };
    const CommandCheck c = checkForce(cmd, links, limits, link_pose);
    checkVerdict("force", c,
                 expectedOk(cmd.link, cmd.frame, cmd.point,
                            {{cmd.force, limits.max_force}, {cmd.torque, limits.max_torque}},
                            cmd.duration, links, limits, world, ragdoll),
                 cmd.link);
    if (!c.ok) return;
    const ActiveForce f = toActiveForce(cmd, c, pose(c.link), kDt);
    FUZZ_CHECK(f.force.allFinite() && f.torque.allFinite() && f.local_point.allFinite(),
               "force: converted values not finite");
    FUZZ_CHECK(f.force.norm() <= limits.max_force * (1 + kRel), "force: |F| = %g", f.force.norm());
    FUZZ_CHECK(f.torque.norm() <= limits.max_torque * (1 + kRel), "force: |T| = %g",
               f.torque.norm());
    FUZZ_CHECK(f.local_point.norm() <= limits.max_lever_arm * (1 + kRel) + kRel,
               "force: lever %g", f.local_point.norm());
    FUZZ_CHECK(f.steps_left >= 1 || f.steps_left == -1, "force: %lld steps",
               static_cast<long long>(f.steps_left));
    FUZZ_CHECK((cmd.duration < 0) <= (f.steps_left == -1), "force: duration %g gave %lld steps",
               cmd.duration, static_cast<long long>(f.steps_left));
    if (forces.size() < kMaxActiveForces) forces.push_back(f);
  }
};

void checkName(const std::string& name) {
  bool valid = !name.empty() && name.size() <= kMaxNameLength &&
               std::isalpha(static_cast<unsigned char>(name[0]));
  for (char ch : name) valid = valid && (std::isalnum(static_cast<unsigned char>(ch)) || ch == '_');
  const std::string err = ragdollNameError(name);
  FUZZ_CHECK(err.empty() == valid, "name '%s': '%s'", name.c_str(), err.c_str());
  FUZZ_CHECK(err.size() < 512, "name of %zu characters: a message of %zu", name.size(), err.size());
  std::string ragdoll, rest;
  splitQualifiedName(name, [](const std::string& n) { return n == "ragdoll" || n == "bob"; },
                     &ragdoll, &rest);
  FUZZ_CHECK(ragdoll.empty() ? rest == name : ragdoll + "/" + rest == name,
             "split '%s' into '%s' + '%s'", name.c_str(), ragdoll.c_str(), rest.c_str());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const RagdollDef& def = ragdollDef();
  Sim sim(def);
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::vector<std::string> t;
    for (std::string tok; ls >> tok;) t.push_back(tok);
    if (t.empty()) continue;
    double v[10];
    if (t[0] == "impulse" && numbers(t, 3, 6, v)) {
      ImpulseCommand c;
      c.link = unescape(t[1]);
      c.frame = unescape(t[2]);
      c.point = Vec3(v[0], v[1], v[2]);
      c.impulse = Vec3(v[3], v[4], v[5]);
      sim.impulse(c);
    } else if (t[0] == "force" && numbers(t, 3, 10, v)) {
      ForceCommand c;
      c.link = unescape(t[1]);
      c.frame = unescape(t[2]);
      c.point = Vec3(v[0], v[1], v[2]);
      c.force = Vec3(v[3], v[4], v[5]);
      c.torque = Vec3(v[6], v[7], v[8]);
      c.duration = v[9];
      sim.force(c);
    } else if (t[0] == "step" && numbers(t, 1, 1, v)) {
      if (v[0] >= 1) sim.step(static_cast<int>(std::min<double>(v[0], kMaxStepsPerLine)));
    } else if (t[0] == "name" && t.size() >= 2) {
      checkName(unescape(t[1]));
    }
  }
  if (sim.accepted) sim.step(2);  // an accepted command always meets the solver
  return 0;
}
