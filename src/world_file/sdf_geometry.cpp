// <collision> -> shape: SDF primitives map one to one, an ellipsoid becomes the hull of points on
// its surface, a mesh the convex hull of its vertices (the URDF loader's mesh reader); a mesh
// that cannot be read is reported to the caller (sdf_model.cpp puts a stand-in or skips it).
#include <sdf/sdf.hh>

#include <cmath>
#include <filesystem>

#include "loader.hpp"  // urdf_load::kHullDirections
#include "ragdoll_sim/material.hpp"
#include "mesh_loader.hpp"
#include "world_load.hpp"

namespace ragdoll_sim {
namespace world_load {
namespace {

// A closed mesh enclosing less than this share of its convex hull's volume is clearly concave.
constexpr double kConcaveRatio = 0.6;

Vec3 vec(const ignition::math::Vector3d& v) { return Vec3(v.X(), v.Y(), v.Z()); }

// Points on an ellipsoid's surface (latitude / longitude rings and the poles).
std::vector<Vec3> ellipsoidPoints(const Vec3& radii) {
  constexpr int kRings = 8, kSegments = 16;
  std::vector<Vec3> pts{Vec3(0, 0, radii.z()), Vec3(0, 0, -radii.z())};
  for (int i = 1; i < kRings; ++i) {
    const double theta = M_PI * i / kRings;
    for (int k = 0; k < kSegments; ++k) {
      const double phi = 2 * M_PI * k / kSegments;
      pts.emplace_back(radii.x() * std::sin(theta) * std::cos(phi),
                       radii.y() * std::sin(theta) * std::sin(phi), radii.z() * std::cos(theta));
    }
  }
  return pts;
}

// <surface> coefficients as written (the element tree: SDFormat 12 has no accessor for them).
void readSurface(const sdf::Collision& c, const std::string& where, WorldCollisionDef* def) {
  const sdf::ElementPtr e = c.Element();
  if (!e || !e->HasElement("surface")) return;
  const sdf::ElementPtr surface = e->GetElement("surface");
  if (surface->HasElement("ragdoll_sim:material")) {
    const sdf::ParamPtr v = surface->GetElement("ragdoll_sim:material")->GetValue();
    std::string name = v ? v->GetAsString() : "";
    const size_t b = name.find_first_not_of(" \t\r\n"), end = name.find_last_not_of(" \t\r\n");
    def->material = b == std::string::npos ? "" : name.substr(b, end - b + 1);
  }
  if (surface->HasElement("friction") && surface->GetElement("friction")->HasElement("ode")) {
    const sdf::ElementPtr ode = surface->GetElement("friction")->GetElement("ode");
    if (ode->HasElement("mu") || ode->HasElement("mu2")) {
      def->has_friction = true;
      def->mu = ode->Get<double>("mu");
      def->mu2 = ode->HasElement("mu2") ? ode->Get<double>("mu2") : def->mu;
      if (!ode->HasElement("mu")) def->mu = def->mu2;
      const double mean = 0.5 * (def->mu + def->mu2);
      def->shape.material.static_friction = def->shape.material.kinetic_friction = mean;
    }
  }
  if (surface->HasElement("bounce") &&
      surface->GetElement("bounce")->HasElement("restitution_coefficient")) {
    def->has_restitution = true;
    def->shape.material.restitution = surface->GetElement("bounce")->Get<double>("restitution_coefficient");
  }
  const std::string bad = materialError(def->shape.material);
  if (!bad.empty()) throw LoadError(where + " <surface>: " + bad);
}

// Sizes as SDF names them: finite and > 0 (a capsule's length may be 0).
void checkSizes(const std::string& where, const std::string& element, std::initializer_list<double> sizes,
                bool zero_ok_last = false) {
  int k = 0;
  const int n = int(sizes.size());
  std::string text;
  bool ok = true;
  for (double v : sizes) {
    text += (text.empty() ? "" : " ") + num(v);
    const bool last = ++k == n;
    ok &= std::isfinite(v) && (v > 0 || (last && zero_ok_last && v == 0));
  }
  if (!ok) throw LoadError(where + " " + element + ": must be finite and > 0, got " + text);
}

}  // namespace

bool collisionShape(const sdf::Collision& c, const std::string& where, const std::string& link_frame,
                    WalkContext& ctx, WorldCollisionDef* def, std::string* mesh_failure) {
  def->name = c.Name();
  ignition::math::Pose3d p;
  const sdf::Errors errs = c.SemanticPose().Resolve(p, link_frame);
  if (!errs.empty()) throw LoadError(where + " <pose>: " + errs[0].Message());
  def->shape.local = Transform(vec(p.Pos()), Quat(p.Rot().W(), p.Rot().X(), p.Rot().Y(), p.Rot().Z()));
  const sdf::Geometry* g = c.Geom();
  Geometry& out = def->shape.geometry;
  auto skip = [&](const std::string& why) {
    ctx.warnings->push_back(where + ": " + why + "; skipped");
    ++*ctx.skipped;
    return false;
  };
  switch (g ? g->Type() : sdf::GeometryType::EMPTY) {
    case sdf::GeometryType::BOX: {
      const auto v = g->BoxShape()->Size();
      checkSizes(where, "<box><size>", {v.X(), v.Y(), v.Z()});
      out = Geometry::box(0.5 * vec(g->BoxShape()->Size()));
      def->source = "box";
      break;
    }
    case sdf::GeometryType::SPHERE:
      checkSizes(where, "<sphere><radius>", {g->SphereShape()->Radius()});
      out = Geometry::sphere(g->SphereShape()->Radius());
      def->source = "sphere";
      break;
    case sdf::GeometryType::CYLINDER:
      checkSizes(where, "<cylinder><radius> <length>", {g->CylinderShape()->Radius(), g->CylinderShape()->Length()});
      out = Geometry::cylinder(g->CylinderShape()->Radius(), 0.5 * g->CylinderShape()->Length());
      def->source = "cylinder";
      break;
    case sdf::GeometryType::CAPSULE:
      checkSizes(where, "<capsule><radius> <length>", {g->CapsuleShape()->Radius(), g->CapsuleShape()->Length()},
                 true);
      out = Geometry::capsule(g->CapsuleShape()->Radius(), 0.5 * g->CapsuleShape()->Length());
      def->source = "capsule";
      break;
    case sdf::GeometryType::ELLIPSOID: {
      const Vec3 r = vec(g->EllipsoidShape()->Radii());
      if (!(r.allFinite() && r.minCoeff() > 0))
        throw LoadError(where + " <ellipsoid><radii>: must be three finite numbers > 0");
      out = Geometry::convexHull(ellipsoidPoints(r));
      def->source = "convex hull of an ellipsoid";
      break;
    }
    case sdf::GeometryType::PLANE: {
      const Vec3 n = vec(g->PlaneShape()->Normal());
      const auto size = g->PlaneShape()->Size();
      if (!(n.allFinite() && n.norm() > 1e-9))
        throw LoadError(where + " <plane><normal>: must be a finite non-zero vector");
      if (!(std::isfinite(size.X()) && std::isfinite(size.Y()) && size.X() >= 0 && size.Y() >= 0))
        throw LoadError(where + " <plane><size>: must be two finite numbers >= 0");
      out = Geometry::plane(n.normalized(), 0.0);
      def->plane_size[0] = size.X();
      def->plane_size[1] = size.Y();
      def->source = "plane";
      break;
    }
    case sdf::GeometryType::MESH: {
      const sdf::Mesh& m = *g->MeshShape();
      std::string why, path;
      std::vector<Vec3> points;
      double volume = 0;
      if (!ctx.options->load_meshes) {
        why = "mesh loading is off";
      } else {
        const std::string base = m.FilePath().empty() ? ctx.options->base_dir
                                                      : std::filesystem::path(m.FilePath()).parent_path().string();
        path = ctx.resolver->resource(m.Uri(), base, &why);
        if (!path.empty()) mesh::readVertices(path, vec(m.Scale()), &points, &why, &volume);
      }
      if (!points.empty()) {
        out = Geometry::convexHull(mesh::supportPoints(points, urdf_load::kHullDirections));
        if (out.hull) {
          def->source = "convex hull of " + m.Uri() + " (" + std::to_string(out.hull->vertices.size()) +
                        " of " + std::to_string(points.size()) + " vertices)";
          // An open mesh encloses no definite volume; a closed one well inside its hull is a
          // shape the hull fills in (a bowl, a chair, stairs).
          const double hull = out.volume();
          if (volume > 0 && hull > 0 && volume < kConcaveRatio * hull)
            ctx.warnings->push_back(where + ": mesh " + m.Uri() + " is clearly concave (it encloses " +
                                    std::to_string(int(std::lround(100 * volume / hull))) +
                                    " % of its convex hull); collisions use the hull");
          break;
        }
        why = path + " is flat (no volume)";
      }
      *mesh_failure = "mesh " + m.Uri() + " unusable (" + why + ")";
      return false;  // the caller skips it or puts one box for the link in its place
    }
    default:
      return skip("geometry not simulated");
  }
  const std::string bad = geometryError(out);
  if (!bad.empty()) throw LoadError(where + " <geometry>: " + bad);
  readSurface(c, where, def);
  return true;
}

}  // namespace world_load
}  // namespace ragdoll_sim
