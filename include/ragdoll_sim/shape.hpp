// Collision shapes: geometry in a shape-local frame, placed on a body by ShapeDef::local.
// Conventions: capsule and cylinder axes are the local z axis (as URDF cylinders);
// the plane is {x : n . x = offset} in the body frame, solid on the side opposite n.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "ragdoll_sim/math.hpp"

namespace ragdoll_sim {

enum class ShapeType : uint8_t { Sphere, Capsule, Box, Cylinder, ConvexHull, Plane };

const char* shapeTypeName(ShapeType t);

// Convex hull data built once from a point set (faces with outward normals, unique edges).
struct HullData {
  std::vector<Vec3> vertices;
  struct Face {
    Vec3 normal;
    double offset;             // normal . x = offset on the face
    std::vector<int> verts;    // counter-clockwise seen from outside
  };
  std::vector<Face> faces;
  std::vector<std::pair<int, int>> edges;
  std::vector<std::pair<int, int>> edge_faces;  // the two faces on either side of edges[i]
  Vec3 centroid = Vec3::Zero();                 // mean of the vertices: an interior point
  // Build the convex hull of `points` (quickhull). Returns nullptr for degenerate input
  // (fewer than 4 non-coplanar points).
  static std::shared_ptr<const HullData> build(const std::vector<Vec3>& points);
};

struct Geometry {
  ShapeType type = ShapeType::Sphere;
  double radius = 0.1;                       // sphere, capsule, cylinder
  double half_height = 0.1;                  // capsule (segment half length), cylinder
  Vec3 half_extents = Vec3(0.1, 0.1, 0.1);   // box
  Vec3 normal = Vec3::UnitZ();               // plane
  double offset = 0.0;                       // plane
  std::shared_ptr<const HullData> hull;      // convex hull

  // A sphere of radius 0 is a contact point (Drake's convention): it touches every other
  // shape where the point enters it, and has no volume.
  static Geometry sphere(double r);
  static Geometry capsule(double r, double half_height);
  static Geometry box(const Vec3& half_extents);
  static Geometry cylinder(double r, double half_height);
  static Geometry plane(const Vec3& n, double offset);
  static Geometry convexHull(const std::vector<Vec3>& points);  // hull==nullptr if degenerate

  double volume() const;                      // 0 for a plane
  // Inertia about the shape origin, in the shape frame, for unit density.
  Mat3 unitInertia() const;
};

// "" when the World can collide the geometry, else what is wrong, naming the shape and the
// field ("cylinder radius must be a finite number > 0 and <= 1048576 (m, kWorldRange), got
// -0.05"): sizes finite, > 0 and within kWorldRange (a capsule's half_height may be 0: a
// sphere; a sphere's radius may be 0: a point), a unit plane normal with an offset within kWorldRange, a hull that was built
// (convexHull of degenerate points has none) with finite vertices within kWorldRange.
std::string geometryError(const Geometry& g);

// Contact coefficients of one surface. A pair of surfaces uses the coefficients listed for
// the pair of material ids in WorldDef::materials, else combines the two (material.hpp).
struct Material {
  double static_friction = 0.8;
  double kinetic_friction = 0.8;
  double restitution = 0.0;
  // Rolling resistance: a round shape (sphere, capsule, cylinder) touching at a point rolls
  // against a torque of at most rolling_resistance * radius * normal force, the flattened
  // contact patch of soft bodies such as limbs and heads (Box2D v3's rollingResistance).
  // Dimensionless; pairs combine with max. Boxes and hulls roll on their edges, not radii.
  double rolling_resistance = 0.0;
  // Contact compliance (a padded mat, soft ground): with contact_hertz > 0 the normal of a
  // contact is a spring-damper of this natural frequency (Hz) and damping ratio while the
  // bodies approach as well as while they push apart, so an impact is stopped over a time of
  // about 1/(4 contact_hertz) instead of one substep. 0 = rigid (the solver's contact_hertz
  // then softens only the push-out). A pair takes the softer surface's (the lower hertz > 0)
  // pair of values. Peak accelerations and HIC of a rigid-body model depend on it
  // (docs/injury.md).
  double contact_hertz = 0.0;
  double contact_damping_ratio = 1.0;
  int id = 0;  // index in the material table; 0 = unnamed
};

struct ShapeDef {
  Geometry geometry;
  Transform local;     // shape frame in the body (link) frame
  Material material;
};

}  // namespace ragdoll_sim
