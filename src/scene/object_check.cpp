// Checks of objects before they are added (object_check.hpp).
#include "object_check.hpp"

#include <Eigen/Cholesky>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "names.hpp"
#include "ragdoll_sim/material.hpp"

namespace ragdoll_sim {
namespace scene {

namespace {

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

bool finitePose(const Transform& t) {
  return withinWorldRange(t.p) && t.q.coeffs().allFinite() && t.q.norm() > 1e-9;
}

}  // namespace

std::string objectModelError(const RagdollDef& def, bool is_static) {
  if (def.links.empty()) return "the model has no links";
  if (def.root < 0 || def.root >= static_cast<int>(def.links.size()))
    return "the root link index " + std::to_string(def.root) + " names no link";
  for (const LinkDef& l : def.links) {
    const std::string where = "link '" + l.name + "'";
    if (!finitePose(l.rest_pose)) return where + ": its pose is not finite";
    if (!is_static) {
      if (!std::isfinite(l.mass) || l.mass <= 0.0)
        return where + ": mass must be a finite number > 0 (kg), got " + number(l.mass);
      if (!l.com.allFinite()) return where + ": centre of mass is not finite";
      const Mat3 sym = 0.5 * (l.inertia + l.inertia.transpose());
      if (!l.inertia.allFinite() || sym.llt().info() != Eigen::Success)
        return where + ": inertia must be finite and positive definite (kg m^2)";
    }
    for (size_t k = 0; k < l.shapes.size(); ++k) {
      const ShapeDef& s = l.shapes[k];
      const std::string shape = where + " shape " + std::to_string(k) + " (" +
                                shapeTypeName(s.geometry.type) + ")";
      const std::string g = geometryError(s.geometry);
      if (!g.empty()) return shape + ": " + g;
      if (!finitePose(s.local)) return shape + ": its pose in the link is not finite";
      if (!is_static && s.geometry.type == ShapeType::Plane)
        return shape + ": a plane is unbounded and can only belong to a static object";
      const std::string m = materialError(s.material);
      if (!m.empty()) return shape + ": " + m;
    }
  }
  return "";
}

std::string objectPoseError(const Transform& pose) {
  if (!withinWorldRange(pose.p))
    return "pose position must be finite and within " + number(kWorldRange) +
           " m of the origin, got (" + number(pose.p.x()) + ", " + number(pose.p.y()) + ", " +
           number(pose.p.z()) + ")";
  if (!pose.q.coeffs().allFinite() || pose.q.norm() < 1e-9)
    return "pose orientation must be a finite non-zero quaternion";
  return "";
}

std::string sanitizedName(const std::string& name) {
  std::string out;
  for (char c : name)
    out += std::isalnum(static_cast<unsigned char>(c)) || c == '_' ? c : '_';
  if (out.empty() || !std::isalpha(static_cast<unsigned char>(out[0]))) out = "m_" + out;
  if (out.size() > kMaxNameLength) out.resize(kMaxNameLength);
  return out;
}

}  // namespace scene
}  // namespace ragdoll_sim
