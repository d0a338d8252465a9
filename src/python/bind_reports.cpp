// Scene reads: link states as NumPy arrays, joint efforts, contacts and impacts as dicts of
// arrays, the injury record (InjuryReport), broken joints and the command counters.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "py_scene.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace ragdoll_sim {
namespace python {

namespace {

using Array = py::array_t<double>;

Array rows(size_t n, size_t columns) {
  return Array(std::vector<py::ssize_t>{static_cast<py::ssize_t>(n),
                                        static_cast<py::ssize_t>(columns)});
}

void put(py::detail::unchecked_mutable_reference<double, 2>& a, size_t row, size_t col,
         const Vec3& v) {
  const auto r = static_cast<py::ssize_t>(row), c = static_cast<py::ssize_t>(col);
  for (int i = 0; i < 3; ++i) a(r, c + i) = v[i];
}

py::object strings(const std::vector<std::string>& v) {
  return py::module_::import("numpy").attr("array")(py::cast(v), "dtype"_a = "str");
}

}  // namespace

void bindInjury(py::module_& m) {
  py::class_<InjuryReport>(m, "InjuryReport", pydoc(R"doc(
One fall's head injury metrics (docs/injury.md): peak proper acceleration of the head (g), HIC
over 15 and 36 ms windows, peak angular acceleration, the neck's peak force and torque. Times
are s of sim time. to_dict() gives every field.
)doc"))
      .def_readonly("ragdoll", &InjuryReport::ragdoll)
      .def_readonly("head_link", &InjuryReport::head_link)
      .def_readonly("neck_joint", &InjuryReport::neck_joint)
      .def_readonly("reason", &InjuryReport::reason,
                    "'' (still running), 'rest', 'reset' or 'removed'")
      .def_readonly("start_time", &InjuryReport::start_time)
      .def_readonly("end_time", &InjuryReport::end_time)
      .def_readonly("peak_g", &InjuryReport::peak_g, "head peak acceleration, g")
      .def_readonly("peak_time", &InjuryReport::peak_time)
      .def_readonly("hic15", &InjuryReport::hic15)
      .def_readonly("hic15_t1", &InjuryReport::hic15_t1)
      .def_readonly("hic15_t2", &InjuryReport::hic15_t2)
      .def_readonly("hic36", &InjuryReport::hic36)
      .def_readonly("hic36_t1", &InjuryReport::hic36_t1)
      .def_readonly("hic36_t2", &InjuryReport::hic36_t2)
      .def_readonly("peak_angular_acceleration", &InjuryReport::peak_angular_acceleration,
                    "rad/s^2")
      .def_readonly("peak_neck_force", &InjuryReport::peak_neck_force, "N")
      .def_readonly("peak_neck_torque", &InjuryReport::peak_neck_torque, "N m")
      .def(
          "to_dict",
          [](const InjuryReport& r) {
            return py::dict("ragdoll"_a = r.ragdoll, "head_link"_a = r.head_link,
                            "neck_joint"_a = r.neck_joint, "reason"_a = r.reason,
                            "start_time"_a = r.start_time, "end_time"_a = r.end_time,
                            "peak_g"_a = r.peak_g, "peak_time"_a = r.peak_time,
                            "hic15"_a = r.hic15, "hic15_t1"_a = r.hic15_t1,
                            "hic15_t2"_a = r.hic15_t2, "hic36"_a = r.hic36,
                            "hic36_t1"_a = r.hic36_t1, "hic36_t2"_a = r.hic36_t2,
                            "peak_angular_acceleration"_a = r.peak_angular_acceleration,
                            "peak_neck_force"_a = r.peak_neck_force,
                            "peak_neck_torque"_a = r.peak_neck_torque);
          },
          "Every field by name.")
      .def("__repr__", [](const InjuryReport& r) {
        return "<ragdoll_sim.InjuryReport '" + r.ragdoll + "' peak_g=" + std::to_string(r.peak_g) +
               " hic15=" + std::to_string(r.hic15) + " hic36=" + std::to_string(r.hic36) + ">";
      });
}

void bindSceneReports(py::class_<PyScene>& cls) {
  cls.def(
      "link_names",
      [](const PyScene& s, const std::string& name) {
        std::vector<std::string> out;
        for (const LinkDef& l : s.scene().def(s.index(name)).links) out.push_back(l.name);
        return out;
      },
      py::arg("name"), "Link names of ragdoll `name`: the rows of link_poses / link_velocities.");
  cls.def(
      "link_poses",
      [](const PyScene& s, const std::string& name) {
        const int k = s.index(name);
        const size_t n = s.scene().def(k).links.size();
        Array out = rows(n, 7);
        auto a = out.mutable_unchecked<2>();
        for (size_t i = 0; i < n; ++i) {
          const Transform p = s.scene().linkState(k, static_cast<int>(i)).pose;
          put(a, i, 0, p.p);
          a(i, 3) = p.q.x(), a(i, 4) = p.q.y(), a(i, 5) = p.q.z(), a(i, 6) = p.q.w();
        }
        return out;
      },
      py::arg("name"),
      "Link frames of ragdoll `name` in the world: float64 array (links, 7) of x y z qx qy qz qw.");
  cls.def(
      "link_velocities",
      [](const PyScene& s, const std::string& name) {
        const int k = s.index(name);
        const size_t n = s.scene().def(k).links.size();
        Array out = rows(n, 6);
        auto a = out.mutable_unchecked<2>();
        for (size_t i = 0; i < n; ++i) {
          const LinkState st = s.scene().linkState(k, static_cast<int>(i));
          put(a, i, 0, st.linear_velocity);
          put(a, i, 3, st.angular_velocity);
        }
        return out;
      },
      py::arg("name"), pydoc(R"doc(
Link velocities of ragdoll `name`, world axes: float64 array (links, 6) of vx vy vz (of the link
origin, m/s) wx wy wz (rad/s).
)doc"));
  cls.def(
      "link_coms",
      [](const PyScene& s, const std::string& name) {
        const int k = s.index(name);
        const size_t n = s.scene().def(k).links.size();
        Array out = rows(n, 3);
        auto a = out.mutable_unchecked<2>();
        for (size_t i = 0; i < n; ++i)
          put(a, i, 0, s.scene().linkState(k, static_cast<int>(i)).com);
        return out;
      },
      py::arg("name"), "Link centres of mass of ragdoll `name` in the world: array (links, 3), m.");
  cls.def(
      "joint_names",
      [](const PyScene& s, const std::string& name) { return s.scene().axisNames(s.index(name)); },
      py::arg("name"), "Joint axis names (joint_states order) of ragdoll `name`.");
  cls.def(
      "joint_efforts",
      [](const PyScene& s, const std::string& name) {
        std::vector<double> e;
        s.scene().jointEfforts(s.index(name), e);
        return Array(static_cast<py::ssize_t>(e.size()), e.data());
      },
      py::arg("name"), pydoc(R"doc(
Axis efforts of ragdoll `name` in the last step (motor + limit + commanded effort), N m or N, in
joint_names order: float64 array.
)doc"));
  cls.def(
      "contacts",
      [](const PyScene& s) {
        std::vector<SceneContact> pairs;
        s.scene().contacts(pairs);
        std::vector<std::string> a_names, b_names;
        size_t n = 0;
        for (const SceneContact& c : pairs) n += static_cast<size_t>(c.report.count);
        Array point = rows(n, 3), normal = rows(n, 3), force = rows(n, 3);
        Array normal_force(static_cast<py::ssize_t>(n)), depth(static_cast<py::ssize_t>(n));
        auto p = point.mutable_unchecked<2>(), nr = normal.mutable_unchecked<2>(),
             f = force.mutable_unchecked<2>();
        auto nf = normal_force.mutable_unchecked<1>();
        auto d = depth.mutable_unchecked<1>();
        size_t row = 0;
        for (const SceneContact& c : pairs) {
          const std::string a = s.scene().bodyName(c.a), b = s.scene().bodyName(c.b);
          for (int i = 0; i < c.report.count; ++i, ++row) {
            const ContactPointReport& q = c.report.points[static_cast<size_t>(i)];
            a_names.push_back(a);
            b_names.push_back(b);
            put(p, row, 0, q.point);
            put(nr, row, 0, c.report.normal);
            put(f, row, 0, q.normal_force * c.report.normal + q.friction_force);
            nf(static_cast<py::ssize_t>(row)) = q.normal_force;
            d(static_cast<py::ssize_t>(row)) = q.depth;
          }
        }
        return py::dict("body_a"_a = strings(a_names), "body_b"_a = strings(b_names),
                        "point"_a = point, "normal"_a = normal, "force"_a = force,
                        "normal_force"_a = normal_force, "depth"_a = depth);
      },
      pydoc(R"doc(
Contact points after the last step, one row each, as a dict of NumPy arrays: body_a, body_b
(names "ragdoll/link", "object/link", "ground"), point (n, 3) m, normal (n, 3) unit from A to B,
force (n, 3) N on B (normal + friction; A takes the opposite), normal_force (n,) N, depth (n,) m
(> 0: overlapping).
)doc"));
  cls.def(
      "impacts",
      [](const PyScene& s) {
        const std::vector<ImpactEvent>& e = s.impacts;
        const size_t n = e.size();
        std::vector<std::string> ragdoll, link, other;
        Array time(static_cast<py::ssize_t>(n)), point = rows(n, 3), normal = rows(n, 3);
        Array closing(static_cast<py::ssize_t>(n)), separating(static_cast<py::ssize_t>(n));
        Array impulse(static_cast<py::ssize_t>(n)), peak(static_cast<py::ssize_t>(n));
        auto p = point.mutable_unchecked<2>(), nr = normal.mutable_unchecked<2>();
        for (size_t i = 0; i < n; ++i) {
          ragdoll.push_back(e[i].ragdoll);
          link.push_back(e[i].link);
          other.push_back(e[i].other);
          time.mutable_at(i) = e[i].time;
          put(p, i, 0, e[i].point);
          put(nr, i, 0, e[i].normal);
          closing.mutable_at(i) = e[i].closing_speed;
          separating.mutable_at(i) = e[i].separating_speed;
          impulse.mutable_at(i) = e[i].impulse;
          peak.mutable_at(i) = e[i].peak_force;
        }
        return py::dict("ragdoll"_a = strings(ragdoll), "link"_a = strings(link),
                        "other"_a = strings(other), "time"_a = time, "point"_a = point,
                        "normal"_a = normal, "closing_speed"_a = closing,
                        "separating_speed"_a = separating, "impulse"_a = impulse,
                        "peak_force"_a = peak);
      },
      pydoc(R"doc(
Impact events of the last step(n) call (Scene(impacts=True)), as a dict of NumPy arrays:
ragdoll, link (the link hit), other (the body it hit), time s, point (n, 3), normal (n, 3) into
the link, closing_speed and separating_speed m/s, impulse N s, peak_force N.
)doc"));
  cls.def(
      "injury",
      [](const PyScene& s, const std::string& name) {
        const int k = s.index(name);
        if (s.scene().headLink(k).empty())
          throw std::invalid_argument("ragdoll '" + name +
                                      "' has no head link: it keeps no injury record");
        return s.scene().injury(k);
      },
      py::arg("name"), pydoc(R"doc(
The injury record of ragdoll `name` so far (reason ''): an InjuryReport. A record starts when a
link moves faster than 0.5 m/s and ends at rest (then listed by ended_falls()). ValueError when
the ragdoll has no head link (injury=False, or an object).
)doc"));
  cls.def(
      "reset_injury",
      [](PyScene& s, const std::string& name) {
        const int k = s.index(name);
        if (s.scene().headLink(k).empty())
          throw std::invalid_argument("ragdoll '" + name +
                                      "' has no head link: it keeps no injury record");
        return s.scene().resetInjury(k);
      },
      py::arg("name"), "Ends the record of ragdoll `name` now (reason 'reset') and returns it.");
  cls.def(
      "ended_falls", [](const PyScene& s) { return s.ended_falls; },
      "InjuryReports of the falls that ended (at rest) during the last step(n) call.");
  cls.def(
      "broken_joints",
      [](const PyScene& s) {
        py::list out;
        for (const BrokenJointReport& b : s.broken)
          out.append(py::dict("ragdoll"_a = b.ragdoll, "joint"_a = b.joint,
                              "parent_link"_a = b.parent_link, "child_link"_a = b.child_link,
                              "force"_a = b.force, "torque"_a = b.torque));
        return out;
      },
      "Joints that broke during the last step(n) call: dicts ragdoll, joint, parent_link, "
      "child_link, force N, torque N m.");
  cls.def(
      "counters",
      [](const PyScene& s) {
        const SceneCounters c = s.scene().counters();
        return py::dict("received"_a = c.received, "applied"_a = c.applied,
                        "rejected"_a = c.rejected, "dropped"_a = c.dropped,
                        "body_faults"_a = c.body_faults, "impulses"_a = c.impulses,
                        "forces"_a = c.forces, "active_forces"_a = c.active_forces);
      },
      "Command counters: received = applied + rejected + dropped; body faults undone.");
}

}  // namespace python
}  // namespace ragdoll_sim
