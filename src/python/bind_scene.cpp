// ragdoll_sim.Scene: construction, worlds and models in and out, stepping, the clock and the
// determinism hash. Commands and reports are in bind_commands.cpp and bind_reports.cpp.
#include <cmath>
#include <stdexcept>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "convert.hpp"
#include "py_model.hpp"
#include "py_scene.hpp"
#include "ragdoll_sim/state_hash.hpp"
#include "ragdoll_sim/world_file.hpp"

namespace py = pybind11;

namespace ragdoll_sim {
namespace python {

namespace {

SceneDef sceneDef(double dt, const py::handle& gravity, bool ground, bool sleep, int threads,
                  bool impacts, bool injury, const std::string& spawn_overlap, int lanes) {
  if (!(std::isfinite(dt) && dt > 0.0 && dt <= 1.0))
    throw std::invalid_argument("dt must be in (0, 1] s, got " + std::to_string(dt));
  SceneDef def;
  def.dt_ns = std::llround(dt * 1e9);
  def.world.gravity = toVec3(gravity, "gravity");
  def.ground = ground;
  def.world.sleep.enabled = sleep;
  def.world.threads = threads;
  def.world.solver.lanes = lanes;
  def.impacts.enabled = impacts;
  def.injury.enabled = injury;
  if (spawn_overlap == "lift")
    def.spawn_overlap = SpawnOverlap::Lift;
  else if (spawn_overlap == "refuse")
    def.spawn_overlap = SpawnOverlap::Refuse;
  else
    throw std::invalid_argument("spawn_overlap must be 'lift' or 'refuse', got '" +
                                spawn_overlap + "'");
  return def;
}

void spawn(PyScene& s, const std::string& name, const PyModel& model, const py::handle& position,
           const py::handle& orientation, const py::handle& rpy,
           const py::handle& linear_velocity, const py::handle& angular_velocity, bool object,
           bool is_static, bool fixed_base, bool balance) {
  SpawnDef spawn;
  spawn.name = name;
  spawn.def = *model.def;
  spawn.pose = toPose(position, orientation, rpy);
  spawn.object = object || is_static;
  spawn.is_static = is_static;
  spawn.fixed_base = fixed_base;
  spawn.balance = balance;
  const bool moving = !linear_velocity.is_none() || !angular_velocity.is_none();
  const Vec3 v =
      linear_velocity.is_none() ? Vec3::Zero() : toVec3(linear_velocity, "linear_velocity");
  const Vec3 w =
      angular_velocity.is_none() ? Vec3::Zero() : toVec3(angular_velocity, "angular_velocity");
  if (moving && (is_static || fixed_base))
    throw std::invalid_argument("a static or fixed-base model '" + name + "' takes no velocity");
  std::string error;
  const uint64_t mark = s.log().total;
  const SpawnResult result = spawn.object ? s.scene().addObject(std::move(spawn), &error)
                                          : s.scene().addRagdoll(std::move(spawn), &error);
  if (result != SpawnResult::Added) {
    if (error.empty()) error = s.log().problemsSince(mark);
    throw std::invalid_argument("cannot spawn '" + name + "': " + error);
  }
  if (moving) {
    const int k = s.index(name);
    s.scene().setRagdollState(k, s.scene().spawnPose(k), v, w);
  }
}

}  // namespace

void bindScene(py::module_& m) {
  bindModel(m);
  bindInjury(m);
  py::class_<PyScene> cls(m, "Scene", pydoc(R"doc(
The ROS-free simulation: ragdolls and objects by name, pushes, a fixed-step clock, contact,
impact and injury reports. The same engine and rules as ragdoll_sim_node, without ROS.

Deterministic: the same calls in the same order give the same states bit for bit (state_hash()),
on any number of threads. Not thread-safe: use one Scene per thread.

    scene = ragdoll_sim.Scene(dt=0.001)
    scene.spawn("ragdoll", ragdoll_sim.Model.from_file("urdf/ragdoll.urdf"), position=(0, 0, 1.2))
    scene.apply_impulse("ragdoll", "head", (30, 0, 0))
    scene.step(1000)
    print(scene.injury("ragdoll").hic15)

Errors: ValueError for bad arguments (unknown ragdoll, link or joint, a bad pose, a name in
use), RuntimeError for files that do not load; the message names what is wrong.
)doc"));
  cls.def(py::init([](double dt, const py::object& gravity, bool ground, bool sleep, int threads,
                      bool impacts, bool injury, const std::string& spawn_overlap, int lanes) {
            return std::make_unique<PyScene>(sceneDef(dt, gravity, ground, sleep, threads, impacts,
                                                      injury, spawn_overlap, lanes));
          }),
          py::arg("dt") = 0.001, py::arg("gravity") = py::make_tuple(0.0, 0.0, -9.81),
          py::arg("ground") = true, py::arg("sleep") = true, py::arg("threads") = 1,
          py::arg("impacts") = false, py::arg("injury") = true,
          py::arg("spawn_overlap") = "lift", py::arg("lanes") = SolverSettings().lanes, pydoc(R"doc(
dt: the fixed step, s. gravity: (x, y, z), m/s^2. ground: a static plane z = 0. sleep: resting
islands sleep (cheaper; off: every body is solved every step). threads: islands solved in
parallel (0: all cores); the result does not depend on it. impacts: record impact events
(impacts()). injury: keep each ragdoll's head injury record. spawn_overlap: 'lift' a model
spawned into static geometry out of it, or 'refuse' it. lanes: 1 solves every constraint row
alone in double; 0 solves contacts and joint anchors in float lanes, many at once, the widest
the CPU runs (faster; lane_width says which), once 24 bodies are awake (fewer take the double
rows, faster there); 4 or 8 force a width at any size, with the same result as 0 from 24 bodies.
)doc"));
  cls.def(
      "load_world",
      [](PyScene& s, const py::object& world, bool strict) {
        const PyWorldFile loaded = py::isinstance<PyWorldFile>(world)
                                       ? world.cast<PyWorldFile>()
                                       : loadWorldFileOrThrow(world.cast<std::string>(), strict);
        std::string error;
        if (!s.scene().loadWorld(*loaded.def, &error))
          throw std::runtime_error(loaded.def->name + ": " + error);
        return worldSummaryLine(*loaded.def);
      },
      py::arg("world"), py::arg("strict") = false, pydoc(R"doc(
Loads a Gazebo SDF world: a path (worlds/stairs.world) or a WorldFile read once. Static models
become static objects, dynamic ones objects, its gravity the scene's, a plane in it replaces the
ground. strict (a path only): an unresolved <include> is an error. Returns the loader's summary
line. RuntimeError naming the file and the element when it does not load.
)doc"));
  cls.def("spawn", &spawn, py::arg("name"), py::arg("model"),
          py::arg("position") = py::make_tuple(0.0, 0.0, 0.0), py::arg("orientation") = py::none(),
          py::arg("rpy") = py::none(), py::arg("linear_velocity") = py::none(),
          py::arg("angular_velocity") = py::none(), py::arg("object") = false,
          py::arg("static") = false, py::arg("fixed_base") = false, py::arg("balance") = false,
          pydoc(R"doc(
Places `model` (a Model) as `name` with its root link at `position` (m) turned by `orientation`
(quaternion x, y, z, w) or `rpy` (roll, pitch, yaw, rad), moving at linear_velocity (m/s, of the
root link origin) and angular_velocity (rad/s). object: a crate or a door rather than a ragdoll
(no injury record, no balance); static: an object that never moves; fixed_base: the root link
pinned; balance: the balance controller on. ValueError naming the problem (a name in use, a bad
pose, a pose the engine cannot simulate).
)doc"));
  cls.def(
      "remove",
      [](PyScene& s, const std::string& name) {
        std::string error;
        if (!s.scene().remove(name, &error))
          throw std::invalid_argument("cannot remove '" + name + "': " + error);
      },
      py::arg("name"), "Removes the ragdoll or object `name`; ValueError when there is none.");
  cls.def(
      "reset",
      [](PyScene& s) {
        std::string error;
        if (!s.scene().reset(&error)) throw std::runtime_error("reset: " + error);
      },
      "Every ragdoll back at its spawn pose with its joints whole; forces and efforts end.");
  cls.def("step", &PyScene::step, py::arg("n") = 1, pydoc(R"doc(
Advances n fixed steps in C++ (the GIL released). impacts(), ended_falls() and broken_joints()
then hold what happened in these n steps.
)doc"));
  cls.def_property_readonly("time", [](const PyScene& s) { return s.scene().time(); },
                            "Sim time, s.");
  cls.def_property_readonly("steps", [](const PyScene& s) { return s.scene().steps(); },
                            "Steps taken.");
  cls.def_property_readonly("dt", [](const PyScene& s) { return s.scene().dt(); },
                            "The fixed step, s.");
  cls.def_property_readonly(
      "lane_width", [](const PyScene& s) { return s.scene().world().laneWidth(); },
      "The width the solver's rows run at on this CPU: 1 (double rows), 4 or 8 (float lanes).");
  cls.def_property_readonly(
      "names",
      [](const PyScene& s) {
        std::vector<std::string> out;
        for (size_t k = 0; k < s.scene().ragdollCount(); ++k)
          out.push_back(s.scene().name(static_cast<int>(k)));
        return out;
      },
      "Ragdolls and dynamic objects, in spawn order.");
  cls.def(
      "is_object",
      [](const PyScene& s, const std::string& name) { return s.scene().isObject(s.index(name)); },
      py::arg("name"), "True for a dynamic object, False for a ragdoll.");
  cls.def(
      "state_hash",
      [](const PyScene& s, const py::object& seed) {
        uint64_t h = kFnvOffsetBasis;
        if (!seed.is_none()) {
          if (!py::isinstance<py::int_>(seed) || seed < py::int_(0) ||
              seed.attr("bit_length")().cast<int>() > 64)
            throw std::invalid_argument("seed must be an int in [0, 2**64), got " +
                                        std::string(py::str(py::repr(seed))));
          h = seed.cast<uint64_t>();
        }
        return hashStates(s.scene().world(), h);
      },
      py::arg("seed") = py::none(), pydoc(R"doc(
The determinism hash: FNV-1a over the bits of every body's pose (x y z, qw qx qy qz) and
linear and angular velocity, in body order, folded into seed (None: the FNV offset basis). The
same function as bench_ragdoll's state_hash, which folds it after every step (h =
scene.state_hash(h)). Equal hashes: the same state bit for bit.
)doc"));
  cls.def(
      "messages",
      [](PyScene& s, bool clear) {
        py::list out;
        static const char* levels[] = {"debug", "info", "warn", "error"};
        for (const SceneMessage& msg : s.log().messages)
          out.append(py::make_tuple(levels[static_cast<int>(msg.level)], msg.text));
        if (clear) s.log().messages.clear();
        return out;
      },
      py::arg("clear") = true,
      "The scene's log (level, text), oldest first, the last 1000 at most; clear empties it.");
  cls.def("__repr__", [](const PyScene& s) {
    std::string names;
    for (size_t k = 0; k < s.scene().ragdollCount(); ++k)
      names += (k ? ", '" : "'") + s.scene().name(static_cast<int>(k)) + "'";
    return "<ragdoll_sim.Scene time=" + std::to_string(s.scene().time()) +
           " steps=" + std::to_string(s.scene().steps()) + " [" + names + "]>";
  });
  bindSceneCommands(cls);
  bindSceneReports(cls);
}

}  // namespace python
}  // namespace ragdoll_sim
