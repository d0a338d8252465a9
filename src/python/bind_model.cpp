// ragdoll_sim.Model: a model read by the URDF loader (RagdollDef), spawned by Scene.spawn any
// number of times under different names; ragdoll_sim.WorldFile: an SDF world read once, loaded
// into any number of scenes (Scene.load_world, run_fall).
#include <memory>
#include <stdexcept>

#include <pybind11/stl.h>

#include "py_model.hpp"
#include "bindings.hpp"
#include "py_scene.hpp"
#include "ragdoll_sim/urdf_loader.hpp"
#include "ragdoll_sim/world_file.hpp"

namespace py = pybind11;

namespace ragdoll_sim {
namespace python {

namespace {

PyModel loaded(UrdfLoadResult result, const std::string& what) {
  if (!result.ok) throw std::runtime_error(what + ": " + result.error);
  return PyModel{std::make_shared<const RagdollDef>(std::move(result.def))};
}

}  // namespace

PyWorldFile loadWorldFileOrThrow(const std::string& path, bool strict) {
  WorldLoadOptions options;
  options.strict = strict;
  WorldLoadResult r = loadWorldFile(path, options);
  if (!r.ok) throw std::runtime_error(path + ": " + r.error);
  return PyWorldFile{std::make_shared<const WorldFileDef>(std::move(r.def))};
}

void bindModel(py::module_& m) {
  py::class_<PyWorldFile>(m, "WorldFile", pydoc(R"doc(
A Gazebo SDF world file read once (its models, their shapes and joints, gravity); load it into
any number of scenes (Scene.load_world, run_fall) without parsing it again.

    stairs = ragdoll_sim.WorldFile.from_file("worlds/stairs.world")
)doc"))
      .def_static("from_file", &loadWorldFileOrThrow, py::arg("path"), py::arg("strict") = false,
                  "Reads an SDF world file; strict: an unresolved <include> is an error. "
                  "RuntimeError naming the file and the element when it does not load.")
      .def_property_readonly("name", [](const PyWorldFile& w) { return w.def->name; })
      .def_property_readonly(
          "summary", [](const PyWorldFile& w) { return worldSummaryLine(*w.def); },
          "The loader's summary line (models, links, what was skipped).");

  py::class_<PyModel>(m, "Model", pydoc(R"doc(
A model (robot or ragdoll) read from URDF: links, joints, shapes, masses. Immutable; spawn it
into a Scene as many times as you like under different names (Scene.spawn).

    model = ragdoll_sim.Model.from_file("urdf/ragdoll.urdf")
)doc"))
      .def_static(
          "from_file",
          [](const std::string& path, bool load_meshes) {
            UrdfLoadOptions options;
            options.load_meshes = load_meshes;
            return loaded(loadUrdfFile(path, options), path);
          },
          py::arg("path"), py::arg("load_meshes") = true,
          "Reads a URDF file (meshes relative to its folder, package:// through "
          "$ROS_PACKAGE_PATH). RuntimeError naming the file and the offending element.")
      .def_static(
          "from_string",
          [](const std::string& xml, const std::string& base_dir, bool load_meshes) {
            UrdfLoadOptions options;
            options.base_dir = base_dir;
            options.load_meshes = load_meshes;
            return loaded(loadUrdfString(xml, options), "URDF string");
          },
          py::arg("xml"), py::arg("base_dir") = "", py::arg("load_meshes") = true,
          "Reads URDF text; relative mesh paths resolve against base_dir. RuntimeError naming "
          "the offending element.")
      .def_property_readonly("name", [](const PyModel& s) { return s.def->name; },
                             "The URDF <robot> name.")
      .def_property_readonly(
          "link_names",
          [](const PyModel& s) {
            std::vector<std::string> out;
            for (const LinkDef& l : s.def->links) out.push_back(l.name);
            return out;
          },
          "Link names in the order of Scene.link_poses rows (fixed joints lumped into their "
          "parents).")
      .def_property_readonly(
          "joint_names",
          [](const PyModel& s) {
            std::vector<std::string> out;
            for (const RagdollJointDef& j : s.def->joints) out.push_back(j.name);
            return out;
          },
          "The simulated joints (a ball joint folds a revolute chain: \"a+b+c\").")
      .def_property_readonly("mass", [](const PyModel& s) { return s.def->totalMass(); },
                             "Total mass, kg.")
      .def_property_readonly("notes", [](const PyModel& s) { return s.def->notes; },
                             "What the loader merged or mapped.")
      .def_property_readonly("warnings", [](const PyModel& s) { return s.def->warnings; },
                             "What the loader approximated, repaired or ignored.")
      .def("__repr__", [](const PyModel& s) {
        return "<ragdoll_sim.Model '" + s.def->name + "': " + std::to_string(s.def->links.size()) +
               " links, " + std::to_string(s.def->joints.size()) + " joints>";
      });
}

}  // namespace python
}  // namespace ragdoll_sim
