// URDF -> RagdollDef with urdfdom.
//
// Steps: parse (urdfdom's console_bridge errors are captured into the result), group links
// joined by fixed joints into one body (mass properties and shapes lumped into the top link),
// fold chains of 2-3 revolute joints through massless geometry-less links into ball joints,
// turn the remaining revolute/continuous joints into hinges, and compute rest poses. Each
// revolute joint's <dynamics> damping / friction goes to its axis (RagdollJointDef::damping,
// ::friction); an empty <dynamics/> (which urdfdom alone rejects) means both 0.
// Prismatic, planar and (non-root) floating joints are rejected for now.
//
// Ball chain frames. URDF gives child-in-parent = O1 R(x1,t1) O2 R(x2,t2) O3 R(x3,t3) with joint
// origins Ok and axes xk in each joint's child frame. When O2 = Q2 and O3 = Q3 are pure rotations,
// moving them to the right (Q R(x,t) = R(Q x,t) Q) gives
//   O1 R(a0,t1) R(a1,t2) R(a2,t3) Q2 Q3,  a0 = x1, a1 = Q2 x2, a2 = Q2 Q3 x3  (in O1's frame),
// i.e. frame_parent = O1 and frame_child = (Q2 Q3)^-1, matching RagdollJointDef's convention.
#include "ragdoll_sim/urdf_loader.hpp"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>

namespace ragdoll_sim {
namespace {

constexpr double kDensity = 1000.0;     // kg/m^3 for links without <inertial>
constexpr double kDummyFraction = 0.01; // chain links lighter than this share of a neighbour
constexpr double kCoincident = 1e-9;    // m, ball chain inner origins
constexpr double kOrthogonal = 1e-6;    // |cos| between ball chain axes

struct LoadError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

std::string quoted(const std::string& s) { return "'" + s + "'"; }

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

bool positiveDefinite(const Mat3& I) {
  return I.allFinite() && Eigen::SelfAdjointEigenSolver<Mat3>(I).eigenvalues().minCoeff() > 0;
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
  std::vector<urdf::JointConstSharedPtr> child_joints;  // revolute / continuous, leaving it
  int def_index = -1;                                     // index in RagdollDef::links
};

class Loader {
 public:
  explicit Loader(const urdf::ModelInterface& model) : model_(model) {}

  RagdollDef run() {
    def_.name = model_.getName();
    urdf::LinkConstSharedPtr root = model_.getRoot();
    // A massless root ("world") floating-jointed to the robot: the robot is the free root.
    if (root->child_joints.size() == 1 && root->child_joints[0]->type == urdf::Joint::FLOATING &&
        !root->inertial && root->collision_array.empty()) {
      def_.notes.push_back("floating joint " + quoted(root->child_joints[0]->name) +
                           " dropped: " + quoted(root->child_joints[0]->child_link_name) +
                           " is the free root");
      root = model_.getLink(root->child_joints[0]->child_link_name);
    }
    addGroup(root);
    def_.root = 0;
    emitBody(0, Transform());
    if (folded_links_ > 0) {
      std::ostringstream os;
      os << folded_links_ << " massless chain links folded into ball joints (" << folded_mass_
         << " kg dropped)";
      def_.notes.push_back(os.str());
    }
    return std::move(def_);
  }

 private:
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
      const std::string jn = "joint " + quoted(j->name);
      switch (j->type) {
        case urdf::Joint::FIXED:
          def_.notes.push_back(jn + ": link " + quoted(child->name) + " lumped into " +
                               quoted(groups_[g].top->name));
          addLink(g, child, T * toTransform(j->parent_to_joint_origin_transform, jn));
          break;
        case urdf::Joint::REVOLUTE:
        case urdf::Joint::CONTINUOUS:
          groups_[g].child_joints.push_back(j);
          addGroup(child);
          break;
        case urdf::Joint::PRISMATIC:
          throw LoadError(jn + ": prismatic joints are not supported");
        case urdf::Joint::PLANAR:
          throw LoadError(jn + ": planar joints are not supported");
        case urdf::Joint::FLOATING:
          throw LoadError(jn + ": floating joints below the root are not supported");
        default:
          throw LoadError(jn + ": unknown joint type");
      }
      if (j->mimic) def_.notes.push_back(jn + ": <mimic> ignored");
    }
  }

  void addMassAndShapes(int g, const urdf::Link& link, const Transform& T) {
    const std::string ln = "link " + quoted(link.name);
    Group& grp = groups_[g];
    bool has_mesh = false;
    MassAccumulator from_volume;
    for (const auto& c : link.collision_array) {
      if (!c || !c->geometry) throw LoadError(ln + ": <collision> without <geometry>");
      ShapeDef s;
      s.local = T * toTransform(c->origin, ln + " <collision>");
      switch (c->geometry->type) {
        case urdf::Geometry::SPHERE:
          s.geometry = Geometry::sphere(static_cast<const urdf::Sphere&>(*c->geometry).radius);
          break;
        case urdf::Geometry::BOX:
          s.geometry = Geometry::box(0.5 * toVec(static_cast<const urdf::Box&>(*c->geometry).dim));
          break;
        case urdf::Geometry::CYLINDER: {
          const auto& cyl = static_cast<const urdf::Cylinder&>(*c->geometry);
          s.geometry = Geometry::cylinder(cyl.radius, 0.5 * cyl.length);
          break;
        }
        default:  // mesh: replaced below by a box fitted to the link inertia
          has_mesh = true;
          continue;
      }
      const double v = s.geometry.volume();
      if (!(v > 0) || !std::isfinite(v))
        throw LoadError(ln + ": <collision> geometry has a non-positive or non-finite size");
      from_volume.add(kDensity * v, s.local.p, kDensity * rotated(s.geometry.unitInertia(), s.local.q));
      grp.shapes.push_back(s);
    }

    if (link.inertial) {
      const urdf::Inertial& in = *link.inertial;
      const double m = in.mass;
      if (!std::isfinite(m) || m < 0) throw LoadError(ln + ": mass must be finite and >= 0");
      const Transform F = T * toTransform(in.origin, ln + " <inertial>");
      Mat3 I;
      I << in.ixx, in.ixy, in.ixz, in.ixy, in.iyy, in.iyz, in.ixz, in.iyz, in.izz;
      if (m > 0) {
        if (!positiveDefinite(I)) throw LoadError(ln + ": inertia is not positive definite");
        grp.mass.add(m, F.p, rotated(I, F.q));
      }
      if (has_mesh) grp.shapes.push_back(fittedBox(link.name, m, F.p, rotated(I, F.q)));
    } else if (has_mesh) {
      throw LoadError(ln + ": mesh <collision> without <inertial>, cannot size an approximation");
    } else if (from_volume.mass > 0) {
      grp.mass.add(from_volume.mass, from_volume.com(), from_volume.inertia());
      std::ostringstream os;
      os << ln << ": no <inertial>, mass " << from_volume.mass
         << " kg from the collision volume at 1000 kg/m^3";
      def_.notes.push_back(os.str());
    }
  }

  // Solid box with the same mass and principal moments, placed on the principal axes at the COM:
  // I1 = m/3 (b^2 + c^2) etc. for half extents (a, b, c)  =>  a^2 = 3/(2m) (I2 + I3 - I1).
  ShapeDef fittedBox(const std::string& link, double m, const Vec3& com, const Mat3& I) {
    if (!(m > 0)) throw LoadError("link " + quoted(link) + ": mesh <collision> with zero mass");
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
    std::ostringstream os;
    os << "link " << quoted(link) << ": mesh collision approximated by a " << 2 * h.x() << " x "
       << 2 * h.y() << " x " << 2 * h.z() << " m box fitted to its inertia";
    def_.notes.push_back(os.str());
    return s;
  }

  // ---- joints ---------------------------------------------------------------------------
  // Joint origin in the frame of the group holding its parent link.
  Transform origin(const urdf::Joint& j) const {
    return placement_.at(j.parent_link_name).second *
           toTransform(j.parent_to_joint_origin_transform, "joint " + quoted(j.name));
  }
  int groupOf(const std::string& link) const { return placement_.at(link).first; }

  static Vec3 unitAxis(const urdf::Joint& j) {
    const Vec3 a = toVec(j.axis);
    if (!a.allFinite() || a.norm() < 1e-9) throw LoadError("joint " + quoted(j.name) + ": zero <axis>");
    return a.normalized();
  }

  // Limits of one revolute / continuous joint (continuous: +-pi, not limited).
  static bool limits(const urdf::Joint& j, double& lo, double& hi) {
    if (j.type == urdf::Joint::CONTINUOUS || !j.limits) {
      lo = -M_PI;
      hi = M_PI;
      return false;
    }
    lo = j.limits->lower;
    hi = j.limits->upper;
    if (!std::isfinite(lo) || !std::isfinite(hi) || lo > hi)
      throw LoadError("joint " + quoted(j.name) + ": invalid <limit> (need lower <= upper)");
    return true;
  }

  // <dynamics damping friction> of one joint (0 without the element).
  static void dynamics(const urdf::Joint& j, double& damping, double& friction) {
    damping = j.dynamics ? j.dynamics->damping : 0.0;
    friction = j.dynamics ? j.dynamics->friction : 0.0;
    if (!std::isfinite(damping) || damping < 0 || !std::isfinite(friction) || friction < 0)
      throw LoadError("joint " + quoted(j.name) +
                      ": <dynamics> damping and friction must be finite and >= 0");
  }

  bool isChainLink(const Group& g, double parent_mass) const {
    return g.shapes.empty() && g.child_joints.size() == 1 &&
           g.mass.mass < kDummyFraction * parent_mass;
  }

  // Creates the LinkDef of group g at rest pose `rest`, then its joints and child bodies.
  void emitBody(int g, const Transform& rest) {
    Group& grp = groups_[g];
    const std::string ln = "link " + quoted(grp.top->name);
    LinkDef link;
    link.name = grp.top->name;
    link.mass = grp.mass.mass;
    link.com = grp.mass.com();
    link.inertia = grp.mass.inertia();
    link.shapes = grp.shapes;
    link.rest_pose = rest;
    if (!(link.mass > 0)) throw LoadError(ln + ": no mass (no <inertial> mass and no <collision>)");
    if (!positiveDefinite(link.inertia)) throw LoadError(ln + ": inertia is not positive definite");
    grp.def_index = int(def_.links.size());
    def_.links.push_back(std::move(link));
    for (const auto& j : grp.child_joints) emitJoint(g, j, rest);
  }

  void emitJoint(int parent, const urdf::JointConstSharedPtr& first, const Transform& parent_rest) {
    // Follow the chain through massless geometry-less links with a single moving child.
    std::vector<urdf::JointConstSharedPtr> chain{first};
    std::vector<std::string> dummies;
    const double parent_mass = groups_[parent].mass.mass;
    int child = groupOf(first->child_link_name);
    while (isChainLink(groups_[child], parent_mass)) {
      dummies.push_back(groups_[child].top->name);
      chain.push_back(groups_[child].child_joints[0]);
      child = groupOf(chain.back()->child_link_name);
    }
    std::string names;
    for (const auto& j : chain) names += (names.empty() ? "" : "+") + j->name;
    const std::string where = "joint chain " + quoted(names);
    if (chain.size() > 3) throw LoadError(where + ": more than 3 joints through massless links");
    for (const auto& d : dummies)
      if (!(groups_[groupOf(d)].mass.mass < kDummyFraction * groups_[child].mass.mass))
        throw LoadError(where + ": link " + quoted(d) + " is not negligible next to " +
                        quoted(groups_[child].top->name));

    RagdollJointDef jd;
    jd.name = names;
    jd.parent = groups_[parent].def_index;
    jd.frame_parent = origin(*first);
    jd.chain_links = dummies;
    Quat Q = Quat::Identity();  // Q2 Q3 ... accumulated (see the derivation at the top)
    for (size_t k = 0; k < chain.size(); ++k) {
      const urdf::Joint& j = *chain[k];
      if (k > 0) {
        const Transform O = origin(j);
        if (O.p.norm() > kCoincident)
          throw LoadError(where + ": joint " + quoted(j.name) +
                          " has a translated origin, cannot form a ball joint");
        Q = Q * O.q;
      }
      double lo, hi;
      jd.limited |= limits(j, lo, hi);
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
    if (chain.size() == 1) {
      jd.kind = RagdollJointKind::Hinge;
    } else {
      jd.kind = RagdollJointKind::Ball;
      for (size_t a = 0; a < jd.axes.size(); ++a)
        for (size_t b = a + 1; b < jd.axes.size(); ++b)
          if (std::abs(jd.axes[a].dot(jd.axes[b])) > kOrthogonal)
            throw LoadError(where + ": axes are not orthogonal, cannot form a ball joint");
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
    jd.child = int(def_.links.size());  // emitBody appends the child next
    const Transform rest = parent_rest * jd.frame_parent * jd.frame_child.inverse();
    def_.no_collide.emplace_back(jd.parent, jd.child);
    def_.joints.push_back(std::move(jd));
    folded_links_ += dummies.size();
    for (const auto& d : dummies) folded_mass_ += groups_[groupOf(d)].mass.mass;
    emitBody(child, rest);
  }

  const urdf::ModelInterface& model_;
  RagdollDef def_;
  std::vector<Group> groups_;
  std::map<std::string, std::pair<int, Transform>> placement_;  // link -> (group, frame in group)
  size_t folded_links_ = 0;
  double folded_mass_ = 0;
};

// urdfdom rejects a joint's <dynamics/> that has neither damping nor friction (the whole
// model then fails to parse); URDF gives both a default of 0. This pass over the XML gives such
// an element damping="0" so that it means "no damping, no friction", and notes the attributes
// of a joint's <dynamics> that the simulator ignores (only damping and friction are used, e.g.
// Gazebo's spring_stiffness). Returns true and sets *out when it changed the text.
// A small scanner, enough for URDF: comments, CDATA, <? ?> and <! > are skipped; quoted
// attribute values may hold '>'. Only <dynamics> of a <robot>'s <joint> is touched.
bool normalizeDynamics(const std::string& xml, std::string* out, std::vector<std::string>* notes) {
  auto isNameChar = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == ':' || c == '.';
  };
  std::vector<std::string> stack;  // open elements
  std::vector<size_t> inserts;     // positions after "<dynamics"
  std::string joint;               // name of the innermost open <joint>
  size_t i = 0;
  while ((i = xml.find('<', i)) != std::string::npos) {
    auto skipTo = [&](const char* end) {
      const size_t e = xml.find(end, i);
      i = e == std::string::npos ? xml.size() : e + std::strlen(end);
    };
    if (xml.compare(i, 4, "<!--") == 0) { skipTo("-->"); continue; }
    if (xml.compare(i, 9, "<![CDATA[") == 0) { skipTo("]]>"); continue; }
    if (xml.compare(i, 2, "<?") == 0) { skipTo("?>"); continue; }
    if (xml.compare(i, 2, "<!") == 0) { skipTo(">"); continue; }
    const bool closing = xml.compare(i, 2, "</") == 0;
    size_t p = i + (closing ? 2 : 1);
    const size_t name_start = p;
    while (p < xml.size() && isNameChar(xml[p])) ++p;
    const std::string name = xml.substr(name_start, p - name_start);
    const size_t name_end = p;
    // Attributes up to '>' (quotes respected).
    std::vector<std::pair<std::string, std::string>> attrs;
    bool self_closing = false;
    while (p < xml.size() && xml[p] != '>') {
      const char c = xml[p];
      if (c == '/') { self_closing = true; ++p; continue; }
      if (std::isspace(static_cast<unsigned char>(c))) { ++p; continue; }
      self_closing = false;
      const size_t a = p;
      while (p < xml.size() && isNameChar(xml[p])) ++p;
      std::string attr = xml.substr(a, p - a), value;
      while (p < xml.size() && std::isspace(static_cast<unsigned char>(xml[p]))) ++p;
      if (p < xml.size() && xml[p] == '=') {
        ++p;
        while (p < xml.size() && std::isspace(static_cast<unsigned char>(xml[p]))) ++p;
        if (p < xml.size() && (xml[p] == '"' || xml[p] == '\'')) {
          const char q = xml[p];
          const size_t e = xml.find(q, p + 1);
          const size_t end = e == std::string::npos ? xml.size() : e;
          value = xml.substr(p + 1, end - p - 1);
          p = std::min(xml.size(), end + 1);
        }
      }
      if (attr.empty()) ++p;  // stray character: step over it
      else attrs.emplace_back(attr, value);
    }
    i = std::min(xml.size(), p + 1);
    if (closing) {
      while (!stack.empty()) {  // tolerate unbalanced input; urdfdom reports it
        const std::string top = stack.back();
        stack.pop_back();
        if (top == name) break;
      }
      if (name == "joint") joint.clear();
      continue;
    }
    if (name == "joint") {
      joint.clear();
      for (const auto& [k, v] : attrs)
        if (k == "name") joint = v;
    }
    if (name == "dynamics" && stack.size() >= 2 && stack.back() == "joint" &&
        stack[stack.size() - 2] == "robot") {
      bool has = false;
      for (const auto& [k, v] : attrs) {
        if (k == "damping" || k == "friction") has = true;
        else notes->push_back("joint " + quoted(joint) + ": <dynamics> attribute " + quoted(k) +
                              " ignored (only damping and friction are used)");
      }
      if (!has) {
        inserts.push_back(name_end);
        notes->push_back("joint " + quoted(joint) +
                         ": <dynamics> without damping or friction, both taken as 0");
      }
    }
    if (!self_closing) stack.push_back(name);
  }
  if (inserts.empty()) return false;
  out->clear();
  out->reserve(xml.size() + 12 * inserts.size());
  size_t from = 0;
  for (size_t at : inserts) {
    out->append(xml, from, at - from);
    out->append(" damping=\"0\"");
    from = at;
  }
  out->append(xml, from, std::string::npos);
  return true;
}

}  // namespace

UrdfLoadResult loadUrdfString(const std::string& xml) {
  UrdfLoadResult result;
  urdf::ModelInterfaceSharedPtr model;
  std::vector<std::string> notes;  // from normalizeDynamics
  {
    static std::mutex mutex;  // the console_bridge output handler is global
    std::lock_guard<std::mutex> lock(mutex);
    LogCapture capture;
    std::string normalized;
    model = urdf::parseURDF(normalizeDynamics(xml, &normalized, &notes) ? normalized : xml);
    if (!model || !model->getRoot()) {
      result.error = "URDF <robot> could not be parsed: " +
                     (capture.errors().empty() ? std::string("unknown error") : capture.errors());
      return result;
    }
  }
  try {
    result.def = Loader(*model).run();
    result.def.notes.insert(result.def.notes.begin(), notes.begin(), notes.end());
    result.ok = true;
  } catch (const LoadError& e) {
    result.error = e.what();
  }
  return result;
}

UrdfLoadResult loadUrdfFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) {
    UrdfLoadResult result;
    result.error = "cannot open URDF file " + quoted(path);
    return result;
  }
  std::stringstream ss;
  ss << in.rdbuf();
  UrdfLoadResult result = loadUrdfString(ss.str());
  if (!result.ok) result.error = path + ": " + result.error;
  return result;
}

}  // namespace ragdoll_sim
