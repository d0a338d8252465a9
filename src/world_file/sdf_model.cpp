// SDFormat's DOM of one model -> WorldModelDef: link poses through SDFormat's frame semantics
// (relative_to, nested models), <inertial> about the centre of mass in link axes, and joints
// through the URDF loader's mapping to RagdollJointDefs.
#include <sdf/sdf.hh>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "loader.hpp"  // urdf_load::repairInertia
#include "world_load.hpp"

namespace ragdoll_sim {
namespace world_load {
namespace {

Vec3 vec(const ignition::math::Vector3d& v) { return Vec3(v.X(), v.Y(), v.Z()); }

Transform transform(const ignition::math::Pose3d& p) {
  return Transform(vec(p.Pos()), Quat(p.Rot().W(), p.Rot().X(), p.Rot().Y(), p.Rot().Z()).normalized());
}

// SDF's default limits (+-1e16) mean none.
constexpr double kNoLimit = 1e15;

struct Walker {
  WalkContext& ctx;
  const std::map<std::string, LinkLook>& looks;
  WorldModelDef* def;
  std::map<std::string, int> link_index;  // scoped name -> def->links index

  void link(const sdf::Link& l, const Transform& model_pose, const std::string& scope,
            const std::string& where_model, bool is_static) {
    const bool dynamic = !is_static;
    WorldLinkDef L;
    L.is_static = is_static;
    L.name = scope + l.Name();
    const std::string where = where_model + " link " + quote(l.Name());
    ignition::math::Pose3d p;
    sdf::Errors errs = l.SemanticPose().Resolve(p, "__model__");
    if (!errs.empty()) throw LoadError(where + " <pose>: " + errs[0].Message());
    L.pose = model_pose * transform(p);
    L.has_inertial = l.Element() && l.Element()->HasElement("inertial");
    const ignition::math::Inertiald& in = l.Inertial();
    L.mass = in.MassMatrix().Mass();
    L.com = vec(in.Pose().Pos());
    const auto& moi = in.MassMatrix().Moi();
    Mat3 I;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) I(r, c) = moi(r, c);
    const Mat3 R = Quat(in.Pose().Rot().W(), in.Pose().Rot().X(), in.Pose().Rot().Y(), in.Pose().Rot().Z())
                       .normalized()
                       .toRotationMatrix();
    L.inertia = R * I * R.transpose();
    if (dynamic) {
      if (!(std::isfinite(L.mass) && L.mass > 0))
        throw LoadError(where + " <inertial><mass>: must be a finite number > 0, got " + num(L.mass));
      if (!L.com.allFinite() || !L.inertia.allFinite())
        throw LoadError(where + " <inertial>: non-finite pose or inertia");
      if (!urdf_load::repairInertia(L.inertia, L.mass).empty())
        ctx.warnings->push_back(where + " <inertial>: inertia repaired (not physical)");
    }
    std::string first_failure;
    for (uint64_t k = 0; k < l.CollisionCount(); ++k) {
      const sdf::Collision* c = l.CollisionByIndex(k);
      const std::string wc = where + " collision " + quote(c->Name());
      WorldCollisionDef cd;
      std::string failure;
      if (collisionShape(*c, wc, l.Name(), ctx, &cd, &failure)) {
        L.collisions.push_back(std::move(cd));
      } else if (!failure.empty()) {
        // As the URDF loader: one box fitted to a dynamic link's inertia stands in for its
        // unreadable meshes; a static link has no inertia to size it.
        if (first_failure.empty() && dynamic && L.has_inertial) {
          first_failure = failure;
          standIn(L, wc, failure);
        } else {
          ctx.warnings->push_back(wc + ": " + failure + "; skipped");
          ++*ctx.skipped;
        }
      }
    }
    const auto look = looks.find(L.name);
    if (look != looks.end()) {
      L.has_color = look->second.has_color;
      L.color = look->second.color;
      L.visual_material = look->second.material;
    }
    link_index[L.name] = int(def->links.size());
    def->links.push_back(std::move(L));
  }

  // The box with the link's mass and principal moments on its centre of mass, or a cube of
  // water density where that box would be implausible (placeholder inertias: SDF's default
  // unit inertia on a light part gives a box metres wide).
  void standIn(WorldLinkDef& L, const std::string& where, const std::string& failure) {
    Eigen::SelfAdjointEigenSolver<Mat3> eig(L.inertia);
    const Vec3 I = eig.eigenvalues();
    const double s2 = 6.0 / L.mass;  // Ixx = m (b^2 + c^2) / 12 for full sizes a, b, c
    Vec3 sq(s2 * (I.y() + I.z() - I.x()), s2 * (I.x() + I.z() - I.y()), s2 * (I.x() + I.y() - I.z()));
    Mat3 R = eig.eigenvectors();
    if (R.determinant() < 0) R.col(2) = -R.col(2);
    WorldCollisionDef cd;
    cd.name = "stand-in";
    cd.shape.local = Transform(L.com, Quat(R).normalized());
    std::string how = "fitted to the link's inertia";
    const double density = sq.allFinite() && sq.minCoeff() > 0 ? L.mass / sq.cwiseSqrt().prod() : 0.0;
    if (!(density >= urdf_load::kMinDensity && density <= urdf_load::kMaxDensity)) {
      sq = Vec3::Constant(std::pow(L.mass / urdf_load::kDensity, 2.0 / 3.0));
      cd.shape.local.q = Quat::Identity();
      how = "of water density (the inertia gives an implausible box)";
    }
    const Vec3 size = sq.cwiseSqrt();
    cd.shape.geometry = Geometry::box(0.5 * size);
    cd.source = "box " + how + " (" + failure + ")";
    ctx.warnings->push_back(where + ": " + failure + "; replaced by a " + num(size.x()) + " x " +
                            num(size.y()) + " x " + num(size.z()) + " m box " + how);
    L.collisions.push_back(std::move(cd));
  }

  int indexOf(const std::string& scoped, const std::string& where) const {
    if (scoped == "world") return -1;
    const auto it = link_index.find(scoped);
    if (it == link_index.end()) throw LoadError(where + ": link " + quote(scoped) + " not found");
    return it->second;
  }

  void joint(const sdf::Joint& j, const Transform& model_pose, const std::string& scope,
             const std::string& where_model) {
    const std::string where = where_model + " joint " + quote(j.Name());
    RagdollJointDef jd;
    jd.name = scope + j.Name();
    jd.source_joints = {j.Name()};
    const std::string parent = j.ParentLinkName(), child = j.ChildLinkName();
    jd.parent = indexOf(parent == "world" ? parent : scope + parent, where + " <parent>");
    jd.child = indexOf(scope + child, where + " <child>");
    ignition::math::Pose3d p;
    sdf::Errors errs = j.SemanticPose().Resolve(p, parent == "world" ? "__model__" : parent);
    if (errs.empty()) jd.frame_parent = parent == "world" ? model_pose * transform(p) : transform(p);
    if (errs.empty()) errs = j.SemanticPose().Resolve(p, child);
    if (!errs.empty()) throw LoadError(where + " <pose>: " + errs[0].Message());
    jd.frame_child = transform(p);
    const int axes = j.Type() == sdf::JointType::FIXED ? 0 : j.Type() == sdf::JointType::BALL ? 3 : 1;
    switch (j.Type()) {
      case sdf::JointType::FIXED: jd.kind = RagdollJointKind::Fixed; break;
      case sdf::JointType::BALL: jd.kind = RagdollJointKind::Ball; break;
      case sdf::JointType::PRISMATIC: jd.kind = RagdollJointKind::Prismatic; break;
      case sdf::JointType::REVOLUTE:
      case sdf::JointType::CONTINUOUS: jd.kind = RagdollJointKind::Hinge; break;
      default:
        // revolute2, universal, screw, gearbox: two axes or coupled ones.
        ctx.warnings->push_back(where + ": joint type not simulated; the links move as a ball joint");
        jd.kind = RagdollJointKind::Ball;
        break;
    }
    if (jd.kind == RagdollJointKind::Ball) {
      jd.axes = {Vec3::UnitX(), Vec3::UnitY(), Vec3::UnitZ()};
      jd.lower.assign(3, -M_PI);
      jd.upper.assign(3, M_PI);
      jd.damping.assign(3, 0.0);
      jd.friction.assign(3, 0.0);
    }
    if (axes == 1) axis(j, where, &jd);
    def->joints.push_back(std::move(jd));
  }

  void axis(const sdf::Joint& j, const std::string& where, RagdollJointDef* jd) {
    const sdf::JointAxis* a = j.Axis(0);
    if (!a) throw LoadError(where + ": no <axis>");
    ignition::math::Vector3d xyz;
    const sdf::Errors errs = a->ResolveXyz(xyz);
    if (!errs.empty()) throw LoadError(where + " <axis><xyz>: " + errs[0].Message());
    const Vec3 v = vec(xyz);
    if (!(v.allFinite() && v.norm() > 1e-9)) throw LoadError(where + " <axis><xyz>: zero or non-finite");
    jd->axes = {v.normalized()};
    const double damping = a->Damping(), friction = a->Friction();
    if (!(std::isfinite(damping) && damping >= 0 && std::isfinite(friction) && friction >= 0))
      throw LoadError(where + " <axis><dynamics>: damping and friction must be finite and >= 0");
    jd->damping = {damping};
    jd->friction = {friction};
    double lo = a->Lower(), hi = a->Upper();
    const bool hinge = jd->kind == RagdollJointKind::Hinge;
    if (std::isnan(lo) || std::isnan(hi)) throw LoadError(where + " <axis><limit>: not a number");
    if (lo > hi) throw LoadError(where + " <axis><limit>: lower " + num(lo) + " > upper " + num(hi));
    jd->limited = j.Type() != sdf::JointType::CONTINUOUS && lo > -kNoLimit && hi < kNoLimit;
    if (hinge && jd->limited && hi - lo >= 2 * M_PI - 1e-9) jd->limited = false;
    if (!jd->limited) {
      lo = hinge ? -M_PI : -kNoLimit;
      hi = hinge ? M_PI : kNoLimit;
    } else if (hinge) {
      // As the URDF loader: angles wrap at +-pi, so a limit stays short of it.
      const double kWrap = M_PI - 0.05;
      if (lo < -kWrap || hi > kWrap) {
        ctx.warnings->push_back(where + ": <limit> " + num(lo) + ".." + num(hi) + " rad clipped to +-" +
                                num(kWrap) + " (angles wrap at +-pi)");
        lo = std::max(lo, -kWrap);
        hi = std::min(hi, kWrap);
        if (lo > hi) lo = hi = std::abs(lo) < std::abs(hi) ? lo : hi;
      }
    }
    jd->lower = {lo};
    jd->upper = {hi};
  }

  void model(const sdf::Model& m, const Transform& pose, const std::string& scope, const std::string& where,
             bool is_static) {
    is_static = is_static || m.Static();
    for (uint64_t k = 0; k < m.LinkCount(); ++k) link(*m.LinkByIndex(k), pose, scope, where, is_static);
    for (uint64_t k = 0; k < m.ModelCount(); ++k) {
      const sdf::Model* n = m.ModelByIndex(k);
      ignition::math::Pose3d p;
      const sdf::Errors errs = n->SemanticPose().Resolve(p, "__model__");
      const std::string wn = where + " model " + quote(n->Name());
      if (!errs.empty()) throw LoadError(wn + " <pose>: " + errs[0].Message());
      model(*n, pose * transform(p), scope + n->Name() + "::", wn, is_static);
    }
    for (uint64_t k = 0; k < m.JointCount(); ++k) joint(*m.JointByIndex(k), pose, scope, where);
  }
};

}  // namespace

void walkModel(const sdf::Model& model, const Transform& model_pose,
               const std::map<std::string, LinkLook>& looks, WalkContext& ctx, WorldModelDef* def) {
  def->is_static = model.Static();
  def->pose = model_pose;
  Walker w{ctx, looks, def, {}};
  w.model(model, model_pose, "", "model " + quote(def->name), false);
}

}  // namespace world_load
}  // namespace ragdoll_sim
