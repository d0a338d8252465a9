// Scene pushes: impulses, timed forces, joint efforts and joint targets, applied at the current
// sim time through the Scene's command checks (its refusal becomes a ValueError).
#include <pybind11/stl.h>

#include "convert.hpp"
#include "bindings.hpp"
#include "py_scene.hpp"

namespace py = pybind11;

namespace ragdoll_sim {
namespace python {

namespace {

// The point given, or the link's centre of mass in `frame` ("world" or "link").
Vec3 pointOrCom(PyScene& s, int k, int link, const py::object& point, const std::string& frame) {
  if (!point.is_none()) return toVec3(point, "point");
  if (frame == "link") return s.scene().def(k).links[static_cast<size_t>(link)].com;
  return s.scene().linkState(k, link).com;
}

}  // namespace

void bindSceneCommands(py::class_<PyScene>& cls) {
  cls.def(
      "apply_impulse",
      [](PyScene& s, const std::string& name, const std::string& link, const py::object& impulse,
         const py::object& point, const std::string& frame) {
        const int k = s.index(name);
        const int i = s.link(k, link);
        ImpulseCommand c;
        c.link = link;
        c.frame = frame;
        c.impulse = toVec3(impulse, "impulse");
        c.point = pointOrCom(s, k, i, point, frame);
        s.command(name, c);
      },
      py::arg("name"), py::arg("link"), py::arg("impulse"),
      py::arg("point") = py::none(), py::arg("frame") = "world", pydoc(R"doc(
An impulse (N s) on `link` of ragdoll `name`, now: the link's velocity changes by impulse / mass
(and its spin by the moment about its centre of mass). frame 'world': point and impulse in world
coordinates; 'link': point relative to the link origin, impulse in link axes. point None: the
link's centre of mass (no spin). Capped as the node's are (1000 N s, lever arm 10 m): ValueError
naming the limit, the link or the ragdoll.
)doc"));
  cls.def(
      "apply_force",
      [](PyScene& s, const std::string& name, const std::string& link, const py::object& force,
         const py::object& torque, const py::object& point, const std::string& frame,
         double duration) {
        const int k = s.index(name);
        const int i = s.link(k, link);
        ForceCommand c;
        c.link = link;
        c.frame = frame;
        c.force = toVec3(force, "force");
        c.torque = toVec3(torque, "torque");
        c.point = pointOrCom(s, k, i, point, frame);
        c.duration = duration;
        s.command(name, c);
      },
      py::arg("name"), py::arg("link"), py::arg("force"),
      py::arg("torque") = py::make_tuple(0.0, 0.0, 0.0),
      py::arg("point") = py::none(), py::arg("frame") = "world",
      py::arg("duration") = 0.0, pydoc(R"doc(
A force (N) and torque (N m) on `link` of ragdoll `name`, applied every step for `duration` s of
sim time (0: one step; < 0: until clear_forces()). Frames as apply_impulse (point None: the
centre of mass); the point stays fixed in the link, the vectors in world axes. ValueError when
refused.
)doc"));
  cls.def(
      "apply_joint_efforts",
      [](PyScene& s, const std::string& name, const py::object& efforts, double duration) {
        JointEffortCommand c;
        for (const auto& [joint, effort] : toNumberMap(efforts, "efforts")) {
          c.names.push_back(joint);
          c.efforts.push_back(effort);
        }
        c.duration = duration;
        s.command(name, c);
      },
      py::arg("name"), py::arg("efforts"), py::arg("duration") = -1.0, pydoc(R"doc(
Torques (N m; N for a prismatic axis) about joint axes, {joint_states name: effort}, equal and
opposite on the joint's two links, every step for `duration` s (< 0: until replaced or cleared).
Names as joint_names(name). ValueError naming an unknown joint.
)doc"));
  cls.def(
      "set_joint_targets",
      [](PyScene& s, const std::string& name, const py::object& positions) {
        TargetPoseCommand c;
        for (const auto& [joint, position] : toNumberMap(positions, "positions")) {
          c.names.push_back(joint);
          c.position.push_back(position);
        }
        s.command(name, c);
      },
      py::arg("name"), py::arg("positions"), pydoc(R"doc(
Position targets (rad; m for a prismatic axis), {joint_states name: position}, for the joint
motors of ragdoll `name`. ValueError naming an unknown joint.
)doc"));
  cls.def(
      "clear_forces", [](PyScene& s) { return s.scene().clearForces(); },
      "Ends every active force and joint effort; returns how many ended.");
}

}  // namespace python
}  // namespace ragdoll_sim
