// The fall recorder's binding (ragdoll_sim.batch): FallRecordDef, FallRecord, FallRecorder on a
// Scene, and run_fall, one whole run in C++.
#include <cmath>
#include <memory>
#include <stdexcept>

#include <pybind11/stl.h>

#include "bindings.hpp"
#include "convert.hpp"
#include "py_model.hpp"
#include "py_scene.hpp"
#include "ragdoll_sim/fall_record.hpp"
#include "ragdoll_sim/fall_run.hpp"
#include "ragdoll_sim/world.hpp"

namespace py = pybind11;

namespace ragdoll_sim {
namespace python {

namespace {

double finiteArg(double v, const char* name) {
  if (!std::isfinite(v))
    throw std::invalid_argument(std::string(name) + " must be a finite number, got " +
                                std::to_string(v));
  return v;
}

FallRecord runOne(const PyModel& model, const py::object& world, const std::string& name,
                  const py::handle& position, const py::handle& rpy,
                  const py::handle& linear_velocity, const py::handle& angular_velocity,
                  const std::string& push_link, const py::handle& push_impulse, double friction,
                  double restitution, double contact_hertz, double dt, long steps,
                  const FallRecordDef& record, int lanes) {
  FallRunDef d;
  if (!(std::isfinite(dt) && dt > 0.0 && dt <= 1.0))
    throw std::invalid_argument("dt must be in (0, 1] s, got " + std::to_string(dt));
  d.scene.dt_ns = std::llround(dt * 1e9);
  d.scene.world.solver.lanes = lanes;
  Material surface = defaultSurface();
  surface.static_friction = surface.kinetic_friction = finiteArg(friction, "friction");
  surface.restitution = finiteArg(restitution, "restitution");
  surface.contact_hertz = finiteArg(contact_hertz, "contact_hertz");
  const std::string bad = materialError(surface);
  if (!bad.empty()) throw std::invalid_argument("material: " + bad);
  d.scene.material = d.scene.ragdoll_surface = d.scene.ground_surface = d.scene.object_surface =
      surface;
  if (!world.is_none()) d.world = world.cast<const PyWorldFile&>().def;
  d.model = model.def;
  d.name = name;
  d.pose = toPose(position, py::none(), rpy);
  d.linear_velocity = toVec3(linear_velocity, "linear_velocity");
  d.angular_velocity = toVec3(angular_velocity, "angular_velocity");
  d.push_link = push_link;
  d.push_impulse = toVec3(push_impulse, "push_impulse");
  d.steps = steps;
  d.record = record;
  py::gil_scoped_release release;
  return runFall(d);
}

}  // namespace

void bindFall(py::module_& m) {
  py::class_<FallRecordDef>(m, "FallRecordDef", R"doc(
How a FallRecorder judges a fall. At rest: every body of the ragdoll asleep, or slower than
rest_speed (m/s, centre of mass) and rest_angular_speed (rad/s); a rest shorter than min_rest
(s) at the end is none. torso_link ("" = "torso", else the root link) gives the rest class by
its up and forward axes (link axes), upright within upright_angle (rad) of vertical, lying
within lying_angle of horizontal.
)doc")
      .def(py::init<>())
      .def_readwrite("rest_speed", &FallRecordDef::rest_speed)
      .def_readwrite("rest_angular_speed", &FallRecordDef::rest_angular_speed)
      .def_readwrite("min_rest", &FallRecordDef::min_rest)
      .def_readwrite("torso_link", &FallRecordDef::torso_link)
      .def_property(
          "up",
          [](const FallRecordDef& d) { return std::vector<double>{d.up.x(), d.up.y(), d.up.z()}; },
          [](FallRecordDef& d, const py::handle& v) { d.up = toVec3(v, "up"); })
      .def_property(
          "forward",
          [](const FallRecordDef& d) {
            return std::vector<double>{d.forward.x(), d.forward.y(), d.forward.z()};
          },
          [](FallRecordDef& d, const py::handle& v) { d.forward = toVec3(v, "forward"); })
      .def_readwrite("upright_angle", &FallRecordDef::upright_angle)
      .def_readwrite("lying_angle", &FallRecordDef::lying_angle);

  py::class_<FallRecord>(m, "FallRecord", R"doc(
One fall: per-link peak contact force (N), the head's peak g and HIC15, the joints that broke,
the time to rest (s, NaN when not at rest at the end), the NaN flag (a body went non-finite),
the rest pose (root position, roll / pitch / yaw, class).
)doc")
      .def_readonly("ragdoll", &FallRecord::ragdoll)
      .def_readonly("links", &FallRecord::links)
      .def_readonly("peak_contact_force", &FallRecord::peak_contact_force,
                    "N per link, in `links` order.")
      .def_readonly("head_peak_g", &FallRecord::head_peak_g)
      .def_readonly("hic15", &FallRecord::hic15)
      .def_readonly("head_link", &FallRecord::head_link)
      .def_readonly("broken_joints", &FallRecord::broken_joints)
      .def_readonly("time_to_rest", &FallRecord::time_to_rest)
      .def_readonly("nan", &FallRecord::nan)
      .def_readonly("body_faults", &FallRecord::body_faults)
      .def_property_readonly("root_position",
                             [](const FallRecord& r) {
                               return std::vector<double>{r.root_position.x(), r.root_position.y(),
                                                          r.root_position.z()};
                             })
      .def_readonly("roll", &FallRecord::roll)
      .def_readonly("pitch", &FallRecord::pitch)
      .def_readonly("yaw", &FallRecord::yaw)
      .def_property_readonly(
          "rest_class", [](const FallRecord& r) { return restClassName(r.rest); },
          "'upright', 'supine', 'prone', 'side' or 'other'.")
      .def_readonly("duration", &FallRecord::duration)
      .def_readonly("samples", &FallRecord::samples);

  py::class_<FallRecorder>(m, "FallRecorder", R"doc(
Records one ragdoll's fall in a Scene, sampled after every step (run() steps and samples in
C++). ValueError naming an unknown ragdoll or torso link.

    rec = ragdoll_sim.FallRecorder(scene, "ragdoll")
    rec.run(scene, 3000)
    print(rec.record(scene).hic15)
)doc")
      .def(py::init([](const PyScene& s, const std::string& ragdoll, const FallRecordDef& def) {
             return std::make_unique<FallRecorder>(s.scene(), ragdoll, def);
           }),
           py::arg("scene"), py::arg("ragdoll") = "", py::arg("record") = FallRecordDef())
      .def(
          "sample", [](FallRecorder& r, const PyScene& s) { r.sample(s.scene()); },
          py::arg("scene"), "Samples the scene's last step (call after each Scene.step(1)).")
      .def(
          "run",
          [](FallRecorder& r, PyScene& s, long steps) {
            if (steps < 0) throw std::invalid_argument("steps must be >= 0");
            py::gil_scoped_release release;
            r.run(s.scene(), steps);
          },
          py::arg("scene"), py::arg("steps"), "`steps` steps of the scene, each sampled.")
      .def(
          "record", [](const FallRecorder& r, const PyScene& s) { return r.record(s.scene()); },
          py::arg("scene"), "The fall so far (FallRecord).");

  m.def("run_fall", &runOne, py::arg("model"), py::arg("world") = py::none(),
        py::arg("name") = "ragdoll", py::arg("position") = py::make_tuple(0.0, 0.0, 1.1),
        py::arg("rpy") = py::make_tuple(0.0, 0.0, 0.0),
        py::arg("linear_velocity") = py::make_tuple(0.0, 0.0, 0.0),
        py::arg("angular_velocity") = py::make_tuple(0.0, 0.0, 0.0), py::arg("push_link") = "",
        py::arg("push_impulse") = py::make_tuple(0.0, 0.0, 0.0), py::arg("friction") = 0.8,
        py::arg("restitution") = 0.0, py::arg("contact_hertz") = 0.0, py::arg("dt") = 0.001,
        py::arg("steps") = 3000,
        py::arg("record") = FallRecordDef(), py::arg("lanes") = SolverSettings().lanes, R"doc(
One fall in C++ (the GIL released): a Scene of step dt (s) with `world` (a WorldFile, or None:
the ground plane), every surface of friction (static = kinetic), restitution and contact_hertz
(Hz, the contact's spring-damper at damping ratio 1; 0 = rigid), `model` (a
Model) spawned as `name` at position (m) and rpy (rad) moving at linear_velocity (m/s) and
angular_velocity (rad/s), pushed by push_impulse (N s, world axes) at the centre of mass of
push_link ("" = no push), then `steps` steps, its rows solved as Scene's `lanes` says. Returns
its FallRecord. ValueError naming what the scene refused.
)doc");
}

}  // namespace python
}  // namespace ragdoll_sim
