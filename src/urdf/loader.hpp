// The URDF loader's internal pieces, shared by its source files: the Loader that turns a parsed
// urdfdom model into a RagdollDef, the body groups it builds, and small conversions.
//   urdf_loader.cpp    entry points, the run order, rest-pose overlaps
//   link_lumping.cpp   links joined by fixed joints (or leading only to massless links) -> one body
//   link_geometry.cpp  <collision> / <visual> geometry -> shapes (meshes as convex hulls)
//   link_mass.cpp      <inertial> -> mass properties, inertia repair, boxes for unresolved meshes
//   joints.cpp         moving joints -> RagdollJointDefs (limits, dynamics) and the body tree
//   ball_chain.cpp     when a chain of revolute joints folds into one ball joint
#pragma once

#include <urdf_model/model.h>

#include <array>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "ragdoll_sim/range_check.hpp"
#include "mesh_loader.hpp"
#include "ragdoll_sim/urdf_loader.hpp"
#include "urdf_xml.hpp"

namespace ragdoll_sim {
namespace urdf_load {

constexpr double kDensity = 1000.0;     // kg/m^3 for links without <inertial>
constexpr double kDummyFraction = 0.01; // chain links lighter than this share of a neighbour
constexpr double kCoincident = 1e-9;    // m, ball chain inner origins
constexpr double kOrthogonal = 1e-6;    // |cos| between ball chain axes
constexpr double kMinDensity = 50.0;   // kg/m^3, plausible range of a box fitted to an inertia
constexpr double kMaxDensity = 25000.0;
constexpr double kTinyMass = 1e-4;      // kg; lighter links are massless (placeholder masses)
constexpr double kNominalFraction = 0.1;  // a bridging massless link's share of its lighter neighbour
constexpr double kPointRadius = 1e-3;   // m; smaller collision spheres are contact points (Drake's)
constexpr int kHullDirections = 64;     // support directions sampled from a mesh for its hull

// Thrown with the message that becomes UrdfLoadResult::error.
struct LoadError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

inline std::string quote(const std::string& s) { return "'" + s + "'"; }

inline std::string num(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

inline Vec3 toVec(const urdf::Vector3& v) { return {v.x, v.y, v.z}; }

inline Transform toTransform(const urdf::Pose& p, const std::string& where) {
  Transform t(toVec(p.position), Quat(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z));
  if (!t.p.allFinite() || !t.q.coeffs().allFinite()) throw LoadError(where + ": non-finite <origin>");
  const std::string far = worldPointError("<origin> xyz", t.p);  // the World's rule
  if (!far.empty()) throw LoadError(where + ": " + far);
  t.q.normalize();
  return t;
}

inline Mat3 rotated(const Mat3& I, const Quat& q) {
  const Mat3 R = q.toRotationMatrix();
  return R * I * R.transpose();
}

// Inertia of a point mass m at c about the origin: m (|c|^2 E - c c^T).
inline Mat3 pointInertia(double m, const Vec3& c) {
  return m * (c.squaredNorm() * Mat3::Identity() - c * c.transpose());
}

// A rigid body's principal moments are positive and each is at most the sum of the other two.
// Repairs I in place (eigenvalues floored at 1e-4 of the largest, or a 2 cm sphere of mass m
// when all vanish; the smaller two raised until they reach half the largest) and says why it
// was needed, or returns "" when I is physical.
std::string repairInertia(Mat3& I, double m);

// Mass properties accumulated about a body origin: mass, first moment, inertia about the origin.
struct MassAccumulator {
  double mass = 0;
  Vec3 first = Vec3::Zero();
  Mat3 second = Mat3::Zero();

  void add(double m, const Vec3& com, const Mat3& inertia_about_com) {
    mass += m;
    first += m * com;
    second += inertia_about_com + pointInertia(m, com);
  }
  Vec3 com() const { return mass > 0 ? Vec3(first / mass) : Vec3::Zero(); }
  Mat3 inertia() const { return second - pointInertia(mass, com()); }
};

// A body: a URDF link plus everything attached below it by fixed joints.
struct Group {
  urdf::LinkConstSharedPtr top;
  MassAccumulator mass;
  std::vector<ShapeDef> shapes;
  std::vector<std::string> sources;   // per shape
  std::vector<double> friction;       // per shape, < 0: none
  std::vector<std::string> materials; // per shape: its URDF link's material name, "" none
  bool has_color = false;             // the top link's visual colour, else a lumped link's
  std::array<double, 4> color{};
  std::vector<urdf::JointConstSharedPtr> child_joints;  // moving joints leaving it
  int def_index = -1;                                     // index in RagdollDef::links
};

inline bool movesAsChain(const urdf::Joint& j) {
  return j.type == urdf::Joint::REVOLUTE || j.type == urdf::Joint::CONTINUOUS;
}

// Builds one RagdollDef from a parsed model; run() once per Loader.
class Loader {
 public:
  Loader(const urdf::ModelInterface& model, const urdf_xml::Extras& extras,
         const UrdfLoadOptions& options)
      : model_(model), extras_(extras), options_(options) {
    if (options_.package_paths.empty()) options_.package_paths = mesh::packagePathFromEnv();
  }

  RagdollDef run();

 private:
  void excludeRestOverlaps();

  // Mass and massless links (link_lumping.cpp).
  static double ownMass(const urdf::Link& l);
  static bool massless(const urdf::Link& l);
  bool subtreeMassless(const urdf::Link& l) const;
  // Links and fixed-joint lumping (link_lumping.cpp).
  void addGroup(const urdf::LinkConstSharedPtr& link);
  void addLink(int g, const urdf::LinkConstSharedPtr& link, const Transform& T);

  // Shapes (link_geometry.cpp).
  bool primitive(const urdf::Geometry& geom, bool capsule, Geometry* out) const;
  bool meshHull(const urdf::Mesh& m, Geometry* out, std::string* source, std::string* why) const;
  void addShape(int g, const ShapeDef& s, const std::string& source, const std::string& link);
  MassAccumulator addGeometry(int g, const urdf::Link& link, const Transform& T, bool visual,
                              std::string* mesh_failure, int* added);

  // Mass properties (link_mass.cpp).
  void addMassAndShapes(int g, const urdf::Link& link, const Transform& T);
  static ShapeDef fittedBox(double m, const Vec3& com, const Mat3& I);

  // Joints and the body tree (joints.cpp).
  Transform origin(const urdf::Joint& j) const;
  int groupOf(const std::string& link) const { return placement_.at(link).first; }
  static Vec3 unitAxis(const urdf::Joint& j);
  static bool limits(const urdf::Joint& j, double& lo, double& hi, std::vector<std::string>* warnings);
  static void dynamics(const urdf::Joint& j, double& damping, double& friction);
  void emitBody(int g, const Transform& rest, int neighbour);
  void emitJoint(int parent, const urdf::JointConstSharedPtr& first, const Transform& parent_rest);

  // Ball chains (ball_chain.cpp).
  bool isChainLink(const Group& g, double parent_mass) const;
  std::string foldProblem(const std::vector<urdf::JointConstSharedPtr>& chain,
                          const std::vector<std::string>& dummies, int child) const;

  const urdf::ModelInterface& model_;
  const urdf_xml::Extras& extras_;
  UrdfLoadOptions options_;
  RagdollDef def_;
  std::vector<Group> groups_;
  std::map<std::string, std::pair<int, Transform>> placement_;  // link -> (group, frame in group)
  size_t folded_links_ = 0;
  double folded_mass_ = 0;
};

}  // namespace urdf_load
}  // namespace ragdoll_sim
