// What ~spawn_object and ~spawn_model add, built without ROS: a one-link RagdollDef for a
// primitive (shape, sizes, mass or density), and a model's RagdollDef from SDF or URDF text
// (the root element tells which; a bare SDF <model> is wrapped in a world for the loader).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "ragdoll_sim/ragdoll.hpp"

namespace ragdoll_sim {
namespace node {

// The link of a primitive object (TF <name>/<kObjectLink>).
constexpr const char* kObjectLink = "link";

struct PrimitiveObject {
  std::string shape;               // box | sphere | cylinder | capsule
  std::vector<double> dimensions;  // box: full x y z; sphere: r; cylinder, capsule: r, length
  bool is_static = false;
  double mass = 0.0;               // kg; 0 = density x volume
  double density = 0.0;            // kg/m^3
  std::string material;            // table name ("" = the objects' default surface)
  bool has_color = false;
  std::array<double, 4> color = {0.5, 0.5, 0.5, 1.0};
};

// The object's RagdollDef (one link, one shape, inertia of the solid), or "" replaced by the
// error naming the field and the rule ("box dimensions[1] must be a finite number > 0, got -1").
std::string primitiveObjectDef(const PrimitiveObject& o, RagdollDef* def);

struct LoadedModel {
  std::string format;           // "SDF" or "URDF"
  RagdollDef def;
  Transform root_in_model;      // SDF: the root link in the frame the spawn pose places; URDF: identity
  bool is_static = false;       // SDF <static>
  bool fixed_base = false;      // a weld to the world (SDF) or a URDF root link `world`
};

// `xml` read from `file` ("" = given as text; relative URIs and mesh paths from its folder).
// "" on success, else the error naming the element or the file.
std::string loadModelText(const std::string& xml, const std::string& file, LoadedModel* out);

// The whole regular file (bounded as the URDF loader reads), or the error naming it.
std::string readModelFile(const std::string& path, std::string* text);

}  // namespace node
}  // namespace ragdoll_sim
