// Link geometry -> shapes: URDF primitives map one to one (a capsule is a cylinder the pre-pass
// marked), meshes become convex hulls of sampled support points.
#include "loader.hpp"

#include <algorithm>
#include <cmath>

#include "mesh_loader.hpp"

namespace ragdoll_sim {
namespace urdf_load {

// A primitive URDF geometry (capsule: a cylinder the pre-pass renamed), or false.
bool Loader::primitive(const urdf::Geometry& geom, bool capsule, Geometry* out) const {
  switch (geom.type) {
    case urdf::Geometry::SPHERE:
      *out = Geometry::sphere(static_cast<const urdf::Sphere&>(geom).radius);
      return true;
    case urdf::Geometry::BOX:
      *out = Geometry::box(0.5 * toVec(static_cast<const urdf::Box&>(geom).dim));
      return true;
    case urdf::Geometry::CYLINDER: {
      const auto& cyl = static_cast<const urdf::Cylinder&>(geom);
      *out = capsule ? Geometry::capsule(cyl.radius, 0.5 * cyl.length)
                     : Geometry::cylinder(cyl.radius, 0.5 * cyl.length);
      return true;
    }
    default:
      return false;
  }
}

// Convex hull of a mesh file, or false with *why.
bool Loader::meshHull(const urdf::Mesh& m, Geometry* out, std::string* source, std::string* why) const {
  if (!options_.load_meshes) {
    *why = "mesh loading is off";
    return false;
  }
  const std::string path = mesh::resolveUri(m.filename, options_.base_dir, options_.package_paths, why);
  if (path.empty()) return false;
  std::vector<Vec3> points;
  if (!mesh::readVertices(path, toVec(m.scale), &points, why)) return false;
  const std::vector<Vec3> support = mesh::supportPoints(points, kHullDirections);
  *out = Geometry::convexHull(support);
  if (!out->hull) {
    *why = path + " is flat (no volume)";
    return false;
  }
  *source = "convex hull of " + m.filename + " (" + std::to_string(out->hull->vertices.size()) +
            " of " + std::to_string(points.size()) + " vertices)";
  return true;
}

void Loader::addShape(int g, const ShapeDef& s, const std::string& source, const std::string& link) {
  Group& grp = groups_[g];
  grp.shapes.push_back(s);
  grp.sources.push_back(source);
  auto f = extras_.link_friction.find(link);
  grp.friction.push_back(f == extras_.link_friction.end() ? -1.0 : f->second);
  auto m = extras_.link_material.find(link);
  grp.materials.push_back(m == extras_.link_material.end() ? "" : m->second);
}

// Geometry of a <collision> / <visual> list as shapes (meshes as hulls); sets *mesh_failure
// to the first mesh that did not resolve. Returns the volume mass accumulator.
MassAccumulator Loader::addGeometry(int g, const urdf::Link& link, const Transform& T, bool visual,
                                     std::string* mesh_failure, int* added) {
  const std::string ln = "link " + quote(link.name);
  const std::string what = visual ? "<visual>" : "<collision>";
  const auto& caps = visual ? extras_.capsule_visuals : extras_.capsule_collisions;
  const auto cap_it = caps.find(link.name);
  MassAccumulator volume;
  const size_t n = visual ? link.visual_array.size() : link.collision_array.size();
  for (size_t k = 0; k < n; ++k) {
    const urdf::GeometrySharedPtr geom =
        visual ? link.visual_array[k]->geometry : link.collision_array[k]->geometry;
    const urdf::Pose& origin = visual ? link.visual_array[k]->origin : link.collision_array[k]->origin;
    if (!geom) throw LoadError(ln + ": " + what + " without <geometry>");
    ShapeDef s;
    s.local = T * toTransform(origin, ln + " " + what);
    const bool capsule = cap_it != caps.end() && cap_it->second.count(int(k));
    std::string source;
    if (primitive(*geom, capsule, &s.geometry)) {
      source = shapeTypeName(s.geometry.type);
      if (s.geometry.type == ShapeType::Sphere && s.geometry.radius >= 0 &&
          s.geometry.radius < kPointRadius) {
        // Drake's contact points: a sphere of radius 0 in the core, massless, which touches
        // what the point does.
        source = "point (sphere r=" + num(s.geometry.radius) + ")";
        s.geometry.radius = 0;
      }
      if (visual) source += " from <visual>";
    } else if (geom->type == urdf::Geometry::MESH) {
      std::string why;
      if (!meshHull(static_cast<const urdf::Mesh&>(*geom), &s.geometry, &source, &why)) {
        if (mesh_failure->empty())
          *mesh_failure = static_cast<const urdf::Mesh&>(*geom).filename + ": " + why;
        continue;
      }
      if (visual) source += " from <visual>";
    } else {
      continue;
    }
    const double v = s.geometry.volume();
    if (!std::isfinite(v)) throw LoadError(ln + ": " + what + " geometry has a non-finite size");
    if (v == 0 && !(s.geometry.type == ShapeType::Sphere && s.geometry.radius == 0)) {
      def_.warnings.push_back(ln + ": " + what + " geometry of zero size ignored");
      continue;
    }
    // A negative size (a cylinder's radius, two of a box's sizes) can still give a positive
    // volume: the core's rule refuses it, and the file with it.
    const std::string bad = geometryError(s.geometry);
    if (!bad.empty()) throw LoadError(ln + ": " + what + " " + bad);
    // Hulls: the vertex mean stands in for the volume centroid (only used without <inertial>).
    const Vec3 c = s.geometry.hull ? s.geometry.hull->centroid : Vec3::Zero();
    const Mat3 Ic = kDensity * (s.geometry.unitInertia() - pointInertia(v, c));
    volume.add(kDensity * v, s.local.apply(c), rotated(Ic, s.local.q));
    addShape(g, s, source, link.name);
    ++*added;
  }
  return volume;
}

}  // namespace urdf_load
}  // namespace ragdoll_sim
