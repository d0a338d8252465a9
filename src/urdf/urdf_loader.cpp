// URDF -> RagdollDef with urdfdom.
//
// Steps: a tinyxml2 pre-pass (urdf_xml.hpp: malformed files, capsules, spherical joints,
// <gazebo> tags), parse (urdfdom's console_bridge errors are captured into the result), group
// links joined by fixed joints (and moving joints that lead only to massless links) into one
// body (mass properties and shapes lumped into the top link), fold chains of 2-3 revolute
// joints through massless geometry-less links into ball joints, turn the remaining revolute /
// continuous joints into hinges, prismatic into sliders, spherical into free balls, and
// compute rest poses. Each joint's <dynamics> damping / friction goes to its axis
// (RagdollJointDef::damping, ::friction). Planar and (non-root) floating joints are refused.
//
// Ball chain frames. URDF gives child-in-parent = O1 R(x1,t1) O2 R(x2,t2) O3 R(x3,t3) with joint
// origins Ok and axes xk in each joint's child frame. When O2 = Q2 and O3 = Q3 are pure rotations,
// moving them to the right (Q R(x,t) = R(Q x,t) Q) gives
//   O1 R(a0,t1) R(a1,t2) R(a2,t3) Q2 Q3,  a0 = x1, a1 = Q2 x2, a2 = Q2 Q3 x3  (in O1's frame),
// i.e. frame_parent = O1 and frame_child = (Q2 Q3)^-1, matching RagdollJointDef's convention.
// A chain that cannot fold (offset or skew axes, > 3 joints) keeps its hinges; its massless
// links then get a small nominal mass (a body cannot be massless).
#include "ragdoll_sim/urdf_loader.hpp"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <stdexcept>

#include "ragdoll_sim/range_check.hpp"
#include "mesh_loader.hpp"
#include "urdf_xml.hpp"

namespace ragdoll_sim {
namespace {

constexpr double kDensity = 1000.0;     // kg/m^3 for links without <inertial>
constexpr double kDummyFraction = 0.01; // chain links lighter than this share of a neighbour
constexpr double kCoincident = 1e-9;    // m, ball chain inner origins
constexpr double kOrthogonal = 1e-6;    // |cos| between ball chain axes
constexpr double kMinDensity = 50.0;   // kg/m^3, plausible range of a box fitted to an inertia
constexpr double kMaxDensity = 25000.0;
constexpr double kTinyMass = 1e-4;      // kg; lighter links are massless (placeholder masses)
constexpr double kNominalFraction = 0.1;  // a bridging massless link's share of its lighter neighbour
constexpr int kHullDirections = 64;     // support directions sampled from a mesh for its hull

struct LoadError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string quote(const std::string& s) { return "'" + s + "'"; }

std::string num(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

// Collects console_bridge messages (urdfdom reports parse errors only there) during a parse.
class LogCapture : public console_bridge::OutputHandler {
 public:
  LogCapture() : previous_(console_bridge::getOutputHandler()) {
    console_bridge::useOutputHandler(this);
  }
  ~LogCapture() override { console_bridge::useOutputHandler(previous_); }
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR)
      errors_ += (errors_.empty() ? "" : "; ") + text;
  }
  const std::string& errors() const { return errors_; }

 private:
  console_bridge::OutputHandler* previous_;
  std::string errors_;
};

Vec3 toVec(const urdf::Vector3& v) { return {v.x, v.y, v.z}; }

Transform toTransform(const urdf::Pose& p, const std::string& where) {
  Transform t(toVec(p.position), Quat(p.rotation.w, p.rotation.x, p.rotation.y, p.rotation.z));
  if (!t.p.allFinite() || !t.q.coeffs().allFinite()) throw LoadError(where + ": non-finite <origin>");
  const std::string far = worldPointError("<origin> xyz", t.p);  // the World's rule
  if (!far.empty()) throw LoadError(where + ": " + far);
  t.q.normalize();
  return t;
}

Mat3 rotated(const Mat3& I, const Quat& q) {
  const Mat3 R = q.toRotationMatrix();
  return R * I * R.transpose();
}

// Inertia of a point mass m at c about the origin: m (|c|^2 E - c c^T).
Mat3 pointInertia(double m, const Vec3& c) {
  return m * (c.squaredNorm() * Mat3::Identity() - c * c.transpose());
}

// A rigid body's principal moments are positive and each is at most the sum of the other two.
// Repairs I in place (eigenvalues floored at 1e-4 of the largest, or a 2 cm sphere of mass m
// when all vanish; the smaller two raised until they reach half the largest) and says why it
// was needed, or returns "" when I is physical.
std::string repairInertia(Mat3& I, double m) {
  Eigen::SelfAdjointEigenSolver<Mat3> es(0.5 * (I + I.transpose()));
  Vec3 l = es.eigenvalues();  // ascending
  const double tol = 1e-9 * std::max(l[2], 0.0);
  const bool positive = l[0] > 0;
  const bool triangle = l[0] + l[1] >= l[2] - tol;
  if (positive && triangle) return "";
  const std::string why = !positive ? "is not positive definite" : "violates the triangle inequality";
  if (!(l[2] > 0)) l = Vec3::Constant(0.4 * m * 0.02 * 0.02);
  for (int i = 0; i < 2; ++i) l[i] = std::max({l[i], 1e-4 * l[2], 0.5 * l[2]});
  I = es.eigenvectors() * l.asDiagonal() * es.eigenvectors().transpose();
  return why;
}

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
  std::vector<urdf::JointConstSharedPtr> child_joints;  // moving joints leaving it
  int def_index = -1;                                     // index in RagdollDef::links
};

bool movesAsChain(const urdf::Joint& j) {
  return j.type == urdf::Joint::REVOLUTE || j.type == urdf::Joint::CONTINUOUS;
}

class Loader {
 public:
  Loader(const urdf::ModelInterface& model, const urdf_xml::Extras& extras,
         const UrdfLoadOptions& options)
      : model_(model), extras_(extras), options_(options) {
    if (options_.package_paths.empty()) options_.package_paths = mesh::packagePathFromEnv();
  }

  RagdollDef run() {
    def_.name = model_.getName();
    urdf::LinkConstSharedPtr root = model_.getRoot();
    // A massless root ("world") floating-jointed to the robot: the robot is the free root.
    if (root->child_joints.size() == 1 && root->child_joints[0]->type == urdf::Joint::FLOATING &&
        !extras_.spherical_joints.count(root->child_joints[0]->name) && massless(*root)) {
      def_.notes.push_back("floating joint " + quote(root->child_joints[0]->name) +
                           " dropped: " + quote(root->child_joints[0]->child_link_name) +
                           " is the free root");
      root = model_.getLink(root->child_joints[0]->child_link_name);
    }
    addGroup(root);
    def_.root = 0;
    emitBody(0, Transform(), -1);
    excludeRestOverlaps();
    // Lumped links of bodies become fixed frames (links folded into ball chains have theirs).
    for (const auto& [name, placed] : placement_) {
      const Group& grp = groups_[size_t(placed.first)];
      if (grp.def_index >= 0 && grp.top->name != name)
        def_.fixed_frames.push_back({name, grp.def_index, placed.second});
    }
    if (folded_links_ > 0) {
      std::ostringstream os;
      os << folded_links_ << " massless chain links folded into ball joints (" << folded_mass_
         << " kg dropped)";
      def_.notes.push_back(os.str());
    }
    return std::move(def_);
  }

 private:
  // Links whose shapes already touch in the rest pose (fitted boxes, overlapping covers of a
  // hip's motor stack) would push each other apart from the first step: they never collide
  // (what an SRDF's "Default" pairs do). Found with one vanishing step in a world without
  // gravity or ground.
  void excludeRestOverlaps() {
    WorldDef wd;
    wd.gravity = Vec3::Zero();
    wd.sleep.enabled = false;
    World world(wd);
    const Ragdoll r = spawnRagdoll(world, def_, Transform());
    world.step(1e-9);
    std::set<std::pair<int, int>> pairs;
    for (const ContactInfo& c : world.contacts()) {
      if (c.separation >= 0) continue;
      int a = -1, b = -1;
      for (size_t i = 0; i < r.bodies.size(); ++i) {
        if (r.bodies[i] == c.body_a) a = int(i);
        if (r.bodies[i] == c.body_b) b = int(i);
      }
      if (a >= 0 && b >= 0) pairs.emplace(std::min(a, b), std::max(a, b));
    }
    std::string names;
    for (const auto& [a, b] : pairs) {
      if (std::find(def_.no_collide.begin(), def_.no_collide.end(), std::make_pair(a, b)) != def_.no_collide.end() ||
          std::find(def_.no_collide.begin(), def_.no_collide.end(), std::make_pair(b, a)) != def_.no_collide.end())
        continue;
      def_.no_collide.emplace_back(a, b);
      names += (names.empty() ? "" : ", ") + def_.links[a].name + "/" + def_.links[b].name;
    }
    if (!names.empty())
      def_.notes.push_back("links overlapping in the rest pose never collide: " + names);
  }

  // ---- mass and massless links --------------------------------------------------------
  // The link's own mass (<inertial>, tiny placeholder masses read as 0) or, without an
  // <inertial>, whether it has collision geometry to take a volume mass from.
  static double ownMass(const urdf::Link& l) {
    if (l.inertial) return std::isfinite(l.inertial->mass) && l.inertial->mass >= kTinyMass ? l.inertial->mass : 0.0;
    return l.collision_array.empty() ? 0.0 : 1.0;  // volume mass follows
  }
  static bool massless(const urdf::Link& l) { return !(ownMass(l) > 0); }
  // No mass anywhere in the subtree of `l` (a sensor frame, a tool tip, an empty gripper link).
  bool subtreeMassless(const urdf::Link& l) const {
    if (!massless(l)) return false;
    for (const auto& j : l.child_joints)
      if (!subtreeMassless(*model_.getLink(j->child_link_name))) return false;
    return true;
  }

  // ---- links and fixed-joint lumping ---------------------------------------------------
  void addGroup(const urdf::LinkConstSharedPtr& link) {
    groups_.emplace_back();
    groups_.back().top = link;
    addLink(int(groups_.size()) - 1, link, Transform());
  }

  // Adds `link` (frame T in the group's frame) and its fixed descendants to group g.
  void addLink(int g, const urdf::LinkConstSharedPtr& link, const Transform& T) {
    placement_[link->name] = {g, T};
    addMassAndShapes(g, *link, T);
    for (const auto& j : link->child_joints) {
      const urdf::LinkConstSharedPtr child = model_.getLink(j->child_link_name);
      const std::string jn = "joint " + quote(j->name);
      const bool spherical = extras_.spherical_joints.count(j->name) > 0;
      const bool keep_fixed = extras_.preserved_fixed.count(j->name) > 0;
      if (j->type == urdf::Joint::PLANAR)
        throw LoadError(jn + ": planar joints are not supported (use a prismatic pair)");
      if (j->type == urdf::Joint::FLOATING && !spherical)
        throw LoadError(jn + ": floating joints are supported only from a massless root link");
      if (j->type == urdf::Joint::UNKNOWN) throw LoadError(jn + ": unknown joint type");
      const bool moving = j->type != urdf::Joint::FIXED || keep_fixed;
      if (moving && subtreeMassless(*child)) {
        def_.notes.push_back(jn + ": leads only to massless links, lumped like a fixed joint (" +
                             quote(child->name) + " into " + quote(groups_[g].top->name) + ")");
      } else if (moving) {
        if (j->mimic)
          def_.warnings.push_back(jn + ": <mimic> of " + quote(j->mimic->joint_name) +
                                  " not enforced (the joint moves freely)");
        groups_[g].child_joints.push_back(j);
        addGroup(child);
        continue;
      } else {
        def_.notes.push_back(jn + ": link " + quote(child->name) + " lumped into " +
                             quote(groups_[g].top->name));
      }
      addLink(g, child, T * toTransform(j->parent_to_joint_origin_transform, jn));
    }
  }

  // A primitive URDF geometry (capsule: a cylinder the pre-pass renamed), or false.
  bool primitive(const urdf::Geometry& geom, bool capsule, Geometry* out) const {
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
  bool meshHull(const urdf::Mesh& m, Geometry* out, std::string* source, std::string* why) const {
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

  void addShape(int g, const ShapeDef& s, const std::string& source, const std::string& link) {
    Group& grp = groups_[g];
    grp.shapes.push_back(s);
    grp.sources.push_back(source);
    auto f = extras_.link_friction.find(link);
    grp.friction.push_back(f == extras_.link_friction.end() ? -1.0 : f->second);
  }

  // Geometry of a <collision> / <visual> list as shapes (meshes as hulls); sets *mesh_failure
  // to the first mesh that did not resolve. Returns the volume mass accumulator.
  MassAccumulator addGeometry(int g, const urdf::Link& link, const Transform& T, bool visual,
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
      if (v == 0) {
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

  void addMassAndShapes(int g, const urdf::Link& link, const Transform& T) {
    const std::string ln = "link " + quote(link.name);
    Group& grp = groups_[g];
    std::string mesh_failure;
    int added = 0;
    MassAccumulator from_volume = addGeometry(g, link, T, false, &mesh_failure, &added);
    bool has_mass = false;
    double m = 0;
    Transform F;
    Mat3 I = Mat3::Zero();
    if (link.inertial) {
      const urdf::Inertial& in = *link.inertial;
      m = in.mass;
      if (!std::isfinite(m)) throw LoadError(ln + ": <mass> is not a finite number");
      if (m < 0) throw LoadError(ln + ": negative <mass> " + num(m) + " kg");
      F = T * toTransform(in.origin, ln + " <inertial>");
      I << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
      if (!I.allFinite()) throw LoadError(ln + ": <inertia> is not finite");
      if (m > 0 && m < kTinyMass) {
        def_.notes.push_back(ln + ": mass " + num(m) + " kg taken as massless");
        m = 0;
      }
      if (m > 0) {
        const std::string why = repairInertia(I, m);
        if (!why.empty()) {
          const Vec3 l = Eigen::SelfAdjointEigenSolver<Mat3>(I).eigenvalues();
          def_.warnings.push_back(ln + ": <inertia> " + why + "; repaired to principal moments " +
                                  num(l[0]) + ", " + num(l[1]) + ", " + num(l[2]) + " kg m^2");
        }
        grp.mass.add(m, F.p, rotated(I, F.q));
        has_mass = true;
      }
    }
    if (!mesh_failure.empty()) {
      // A mesh did not resolve: the visual geometry (when no collision shape did either), else
      // a box fitted to the inertia.
      std::string visual_failure;
      int from_visual = 0;
      MassAccumulator vis;
      if (added == 0) vis = addGeometry(g, link, T, true, &visual_failure, &from_visual);
      if (from_visual > 0) {
        def_.warnings.push_back(ln + ": collision mesh " + mesh_failure + "; the <visual> geometry used instead");
        if (!link.inertial) from_volume = vis;
      } else if (has_mass) {
        ShapeDef box = fittedBox(m, F.p, rotated(I, F.q));
        Vec3& h = box.geometry.half_extents;
        // Placeholder inertias (ixx=1 on a 0.1 kg part) give boxes metres wide: past a density
        // range no real part has, a cube of water density stands in.
        const double density = m / (8 * h.prod());
        std::string how = "fitted to its inertia";
        if (density < kMinDensity || density > kMaxDensity) {
          h = Vec3::Constant(0.5 * std::cbrt(m / kDensity));
          box.local.q = Quat::Identity();
          how = "of water density (its inertia gives an implausible " + num(density) + " kg/m^3)";
        }
        addShape(g, box, "box " + how + " (mesh unresolved)", link.name);
        def_.warnings.push_back(ln + ": collision mesh " + mesh_failure + "; replaced by a " +
                                num(2 * h.x()) + " x " + num(2 * h.y()) + " x " + num(2 * h.z()) +
                                " m box " + how);
      } else {
        def_.warnings.push_back(ln + ": collision mesh " + mesh_failure +
                                "; no <visual> or mass to size a replacement: no collision shape");
      }
    }
    if (!link.inertial && from_volume.mass > 0) {
      grp.mass.add(from_volume.mass, from_volume.com(), from_volume.inertia());
      def_.notes.push_back(ln + ": no <inertial>, mass " + num(from_volume.mass) +
                           " kg from the collision volume at 1000 kg/m^3");
    }
  }

  // Solid box with the same mass and principal moments, placed on the principal axes at the COM:
  // I1 = m/3 (b^2 + c^2) etc. for half extents (a, b, c)  =>  a^2 = 3/(2m) (I2 + I3 - I1).
  static ShapeDef fittedBox(double m, const Vec3& com, const Mat3& I) {
    Eigen::SelfAdjointEigenSolver<Mat3> es(I);
    const Vec3 l = es.eigenvalues();
    Mat3 R = es.eigenvectors();
    if (R.determinant() < 0) R.col(2) = -R.col(2);
    Vec3 h;
    for (int i = 0; i < 3; ++i)
      h[i] = std::sqrt(std::max(1.5 / m * (l.sum() - 2 * l[i]), 0.005 * 0.005));
    ShapeDef s;
    s.geometry = Geometry::box(h);
    s.local = Transform(com, Quat(R));
    return s;
  }

  // ---- joints ---------------------------------------------------------------------------
  // Joint origin in the frame of the group holding its parent link.
  Transform origin(const urdf::Joint& j) const {
    return placement_.at(j.parent_link_name).second *
           toTransform(j.parent_to_joint_origin_transform, "joint " + quote(j.name));
  }
  int groupOf(const std::string& link) const { return placement_.at(link).first; }

  static Vec3 unitAxis(const urdf::Joint& j) {
    const Vec3 a = toVec(j.axis);
    if (!a.allFinite() || a.norm() < 1e-9) throw LoadError("joint " + quote(j.name) + ": zero <axis>");
    return a.normalized();
  }

  // Limits of one joint (continuous and without <limit>: +-pi, not limited).
  static bool limits(const urdf::Joint& j, double& lo, double& hi, std::vector<std::string>* warnings) {
    if (j.type == urdf::Joint::CONTINUOUS || !j.limits) {
      lo = -M_PI;
      hi = M_PI;
      return false;
    }
    lo = j.limits->lower;
    hi = j.limits->upper;
    if (!std::isfinite(lo) || !std::isfinite(hi))
      throw LoadError("joint " + quote(j.name) + ": <limit> lower / upper not finite");
    if (lo > hi)
      throw LoadError("joint " + quote(j.name) + ": <limit> lower " + num(lo) + " > upper " + num(hi));
    if (j.type == urdf::Joint::PRISMATIC) return true;
    // Angles are measured in (-pi, pi]: a range reaching past +-pi would put a limit at the
    // wrap, where the angle jumps by 2 pi and the limit kicks. Clip it short of the wrap.
    const double kWrap = M_PI - 0.05;
    if (hi - lo >= 2 * M_PI - 1e-9) {
      warnings->push_back("joint " + quote(j.name) + ": <limit> range " + num(lo) + ".." + num(hi) +
                          " covers a full turn; unlimited");
      lo = -M_PI;
      hi = M_PI;
      return false;
    }
    if (lo < -kWrap || hi > kWrap) {
      warnings->push_back("joint " + quote(j.name) + ": <limit> " + num(lo) + ".." + num(hi) +
                          " rad clipped to +-" + num(kWrap) + " (angles wrap at +-pi)");
      lo = std::max(lo, -kWrap);
      hi = std::min(hi, kWrap);
      if (lo > hi) lo = hi = std::abs(lo) < std::abs(hi) ? lo : hi;
    }
    return true;
  }

  // <dynamics damping friction> of one joint (0 without the element).
  static void dynamics(const urdf::Joint& j, double& damping, double& friction) {
    damping = j.dynamics ? j.dynamics->damping : 0.0;
    friction = j.dynamics ? j.dynamics->friction : 0.0;
    if (!std::isfinite(damping) || damping < 0 || !std::isfinite(friction) || friction < 0)
      throw LoadError("joint " + quote(j.name) +
                      ": <dynamics> damping and friction must be finite and >= 0");
  }

  bool isChainLink(const Group& g, double parent_mass) const {
    return g.shapes.empty() && g.child_joints.size() == 1 && movesAsChain(*g.child_joints[0]) &&
           !extras_.preserved_fixed.count(g.child_joints[0]->name) &&
           g.mass.mass < kDummyFraction * parent_mass;
  }

  // Creates the LinkDef of group g at rest pose `rest`, then its joints and child bodies.
  // A group without mass gets a nominal one (`neighbour`: the parent group, -1 at the root).
  void emitBody(int g, const Transform& rest, int neighbour) {
    Group& grp = groups_[g];
    const std::string ln = "link " + quote(grp.top->name);
    if (!(grp.mass.mass > 0)) {
      double ref = neighbour >= 0 ? groups_[neighbour].mass.mass : 0.0;
      for (const auto& j : grp.child_joints) {
        const double c = groups_[groupOf(j->child_link_name)].mass.mass;
        if (c > 0 && (!(ref > 0) || c < ref)) ref = c;
      }
      const double m = std::max(kNominalFraction * ref, 1e-3);
      const double r = 0.03;
      grp.mass.add(m, Vec3::Zero(), 0.4 * m * r * r * Mat3::Identity());
      def_.warnings.push_back(ln + ": massless but joined by moving joints on both sides (" +
                              std::string(neighbour < 0 ? "the root" : "not foldable into a ball") +
                              "); given " + num(m) + " kg");
    }
    LinkDef link;
    link.name = grp.top->name;
    link.mass = grp.mass.mass;
    link.com = grp.mass.com();
    link.inertia = grp.mass.inertia();
    if (!repairInertia(link.inertia, link.mass).empty())
      def_.warnings.push_back(ln + ": lumped inertia repaired (not physical)");
    link.shapes = grp.shapes;
    link.shape_sources = grp.sources;
    link.shape_friction = grp.friction;
    link.rest_pose = rest;
    grp.def_index = int(def_.links.size());
    def_.links.push_back(std::move(link));
    for (const auto& j : grp.child_joints) emitJoint(g, j, rest);
  }

  // A chain of joints through massless links, or why it cannot be one ball joint.
  std::string foldProblem(const std::vector<urdf::JointConstSharedPtr>& chain,
                          const std::vector<std::string>& dummies, int child) const {
    if (chain.size() > 3) return "more than 3 joints through massless links";
    for (const auto& d : dummies)
      if (!(groups_[groupOf(d)].mass.mass < kDummyFraction * groups_[child].mass.mass))
        return "link " + quote(d) + " is not negligible next to " + quote(groups_[child].top->name);
    std::vector<Vec3> axes;
    Quat Q = Quat::Identity();
    for (size_t k = 0; k < chain.size(); ++k) {
      if (k > 0) {
        const Transform O = origin(*chain[k]);
        if (O.p.norm() > kCoincident)
          return "joint " + quote(chain[k]->name) + " has a translated origin (" + num(O.p.norm()) + " m)";
        Q = Q * O.q;
      }
      axes.push_back(Q * unitAxis(*chain[k]));
    }
    for (size_t a = 0; a < axes.size(); ++a)
      for (size_t b = a + 1; b < axes.size(); ++b)
        if (std::abs(axes[a].dot(axes[b])) > kOrthogonal) return "axes are not orthogonal";
    return "";
  }

  void emitJoint(int parent, const urdf::JointConstSharedPtr& first, const Transform& parent_rest) {
    // Follow the chain through massless geometry-less links with a single moving child.
    std::vector<urdf::JointConstSharedPtr> chain{first};
    std::vector<std::string> dummies;
    const double parent_mass = groups_[parent].mass.mass;
    int child = groupOf(first->child_link_name);
    const bool spherical = extras_.spherical_joints.count(first->name) > 0;
    const bool fixed = first->type == urdf::Joint::FIXED;
    const bool prismatic = first->type == urdf::Joint::PRISMATIC;
    if (movesAsChain(*first) && !spherical) {
      while (isChainLink(groups_[child], parent_mass)) {
        dummies.push_back(groups_[child].top->name);
        chain.push_back(groups_[child].child_joints[0]);
        child = groupOf(chain.back()->child_link_name);
      }
    }
    std::string names;
    for (const auto& j : chain) names += (names.empty() ? "" : "+") + j->name;
    if (chain.size() > 1) {
      const std::string problem = foldProblem(chain, dummies, child);
      if (!problem.empty()) {
        // Keep the first joint as a hinge; its massless child becomes a (nominal) body and the
        // rest of the chain is tried again from there.
        def_.warnings.push_back("joint chain " + quote(names) + ": not a ball joint (" + problem +
                                "); kept as separate hinges");
        // The first massless link becomes a body: a nominal share of the chain's lighter end.
        Group& mid = groups_[groupOf(first->child_link_name)];
        const double m = kNominalFraction * std::min(parent_mass, groups_[child].mass.mass);
        const double r = 0.03;
        mid.mass.add(m, Vec3::Zero(), 0.4 * m * r * r * Mat3::Identity());
        def_.warnings.push_back("link " + quote(mid.top->name) + ": massless link between hinges given " +
                                num(m) + " kg");
        chain.resize(1);
        dummies.clear();
        child = groupOf(first->child_link_name);
        names = first->name;
      }
    }

    RagdollJointDef jd;
    jd.name = names;
    jd.parent = groups_[parent].def_index;
    jd.frame_parent = origin(*first);
    jd.chain_links = dummies;
    if (spherical || fixed) {
      jd.kind = spherical ? RagdollJointKind::Ball : RagdollJointKind::Fixed;
      if (spherical) {
        double damping, friction;
        dynamics(*first, damping, friction);
        jd.axes = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
        jd.lower.assign(3, -M_PI);
        jd.upper.assign(3, M_PI);
        jd.damping.assign(3, damping);
        jd.friction.assign(3, friction);
        jd.source_joints = {first->name};
        def_.notes.push_back("joint " + quote(first->name) + ": spherical, a ball joint without limits");
      } else {
        jd.source_joints = {first->name};
        def_.notes.push_back("joint " + quote(first->name) + ": fixed, kept as a weld (<preserveFixedJoint>)");
      }
      jd.frame_child = Transform();
    } else {
      Quat Q = Quat::Identity();  // Q2 Q3 ... accumulated (see the derivation at the top)
      for (size_t k = 0; k < chain.size(); ++k) {
        const urdf::Joint& j = *chain[k];
        if (k > 0) Q = Q * origin(j).q;
        double lo, hi;
        jd.limited |= limits(j, lo, hi, &def_.warnings);
        double damping, friction;
        dynamics(j, damping, friction);
        jd.damping.push_back(damping);
        jd.friction.push_back(friction);
        jd.axes.push_back(Q * unitAxis(j));
        jd.lower.push_back(lo);
        jd.upper.push_back(hi);
        jd.source_joints.push_back(j.name);
        if (k < dummies.size()) jd.chain_offsets.emplace_back(Vec3::Zero(), Q);  // dummy k's frame
      }
      jd.frame_child = Transform(Vec3::Zero(), Q.conjugate());
      if (prismatic) {
        jd.kind = RagdollJointKind::Prismatic;
        if (!first->limits) jd.limited = false;
      } else if (chain.size() == 1) {
        jd.kind = RagdollJointKind::Hinge;
      } else {
        jd.kind = RagdollJointKind::Ball;
        const std::string where = "joint chain " + quote(names);
        // The Euler decomposition of the chain is singular where the middle angle reaches
        // +-pi/2; keep its range clear of that (the solver cannot hold a limit through it).
        const double kMiddleMax = M_PI / 2 - 0.05;
        if (jd.axes.size() == 3 && (jd.lower[1] < -kMiddleMax || jd.upper[1] > kMiddleMax)) {
          jd.lower[1] = std::max(jd.lower[1], -kMiddleMax);
          jd.upper[1] = std::min(jd.upper[1], kMiddleMax);
          jd.limited = true;
          def_.notes.push_back(where + ": middle axis range clamped to +-" + std::to_string(kMiddleMax) +
                               " rad (the chain is singular at +-pi/2)");
        }
        if (chain.size() == 2) {
          jd.axes.push_back(jd.axes[0].cross(jd.axes[1]).normalized());
          jd.lower.push_back(0.0);
          jd.upper.push_back(0.0);
          jd.damping.push_back(0.0);
          jd.friction.push_back(0.0);
          jd.limited = true;
          def_.notes.push_back(where + ": 2-joint chain, ball joint with the third axis locked");
        }
      }
    }
    jd.child = int(def_.links.size());  // emitBody appends the child next
    const Transform rest = parent_rest * jd.frame_parent * jd.frame_child.inverse();
    def_.no_collide.emplace_back(jd.parent, jd.child);
    def_.joints.push_back(std::move(jd));
    folded_links_ += dummies.size();
    for (const auto& d : dummies) folded_mass_ += groups_[groupOf(d)].mass.mass;
    emitBody(child, rest, parent);
  }

  const urdf::ModelInterface& model_;
  const urdf_xml::Extras& extras_;
  UrdfLoadOptions options_;
  RagdollDef def_;
  std::vector<Group> groups_;
  std::map<std::string, std::pair<int, Transform>> placement_;  // link -> (group, frame in group)
  size_t folded_links_ = 0;
  double folded_mass_ = 0;
};

}  // namespace

UrdfLoadResult loadUrdfString(const std::string& xml, const UrdfLoadOptions& options) {
  UrdfLoadResult result;
  urdf_xml::Extras extras;
  result.error = urdf_xml::preprocess(xml, &extras);
  if (!result.error.empty()) return result;
  urdf::ModelInterfaceSharedPtr model;
  {
    static std::mutex mutex;  // the console_bridge output handler is global
    std::lock_guard<std::mutex> lock(mutex);
    LogCapture capture;
    model = urdf::parseURDF(extras.text);
    if (!model || !model->getRoot()) {
      result.error = "URDF <robot> could not be parsed: " +
                     (capture.errors().empty() ? std::string("unknown error") : capture.errors());
      return result;
    }
  }
  try {
    result.def = Loader(*model, extras, options).run();
    result.def.notes.insert(result.def.notes.begin(), extras.notes.begin(), extras.notes.end());
    result.ok = true;
  } catch (const LoadError& e) {
    result.error = e.what();
  }
  return result;
}

UrdfLoadResult loadUrdfFile(const std::string& path, UrdfLoadOptions options) {
  std::ifstream in(path);
  if (!in) {
    UrdfLoadResult result;
    result.error = "cannot open URDF file " + quote(path);
    return result;
  }
  std::stringstream ss;
  ss << in.rdbuf();
  if (options.base_dir.empty())
    options.base_dir = std::filesystem::path(path).parent_path().string();
  UrdfLoadResult result = loadUrdfString(ss.str(), options);
  if (!result.ok) result.error = path + ": " + result.error;
  return result;
}

}  // namespace ragdoll_sim
