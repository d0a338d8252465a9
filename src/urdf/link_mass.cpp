// Mass properties of a link: <inertial> (repaired when not physical) or the collision volume at
// water density, and a box fitted to the inertia when a collision mesh does not resolve.
#include "loader.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace ragdoll_sim {
namespace urdf_load {

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

void Loader::addMassAndShapes(int g, const urdf::Link& link, const Transform& T) {
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
ShapeDef Loader::fittedBox(double m, const Vec3& com, const Mat3& I) {
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

}  // namespace urdf_load
}  // namespace ragdoll_sim
