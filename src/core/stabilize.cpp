// Mass and inertia conditioning (see stabilize.hpp).
#include "ragdoll_sim/stabilize.hpp"

#include <Eigen/Eigenvalues>
#include <cstdio>

namespace ragdoll_sim {

std::vector<std::string> stabilizeRagdoll(RagdollDef& def, const StabilizeSettings& s) {
  std::vector<std::string> report;
  const size_t n = def.links.size();
  std::vector<double> mass0(n);
  for (size_t i = 0; i < n; ++i) mass0[i] = def.links[i].mass;
  const double r = std::max(1.0, s.max_mass_ratio);
  for (int pass = 0; pass < s.max_passes; ++pass) {
    bool changed = false;
    for (const RagdollJointDef& j : def.joints) {
      double& mp = def.links[j.parent].mass;
      double& mc = def.links[j.child].mass;
      if (!(mp > 0.0 && mc > 0.0) || std::max(mp, mc) <= r * std::min(mp, mc) * (1.0 + 1e-12))
        continue;
      // Share the pair's mass m as m/(1+r) and r m/(1+r), the heavier side keeping the larger.
      const double total = mp + mc, light = total / (1.0 + r), heavy = total - light;
      if (mp > mc) mp = heavy, mc = light;
      else mc = heavy, mp = light;
      changed = true;
    }
    if (!changed) break;
  }
  char buf[256];
  for (size_t i = 0; i < n; ++i) {
    LinkDef& l = def.links[i];
    if (l.mass != mass0[i] && mass0[i] > 0.0) {
      l.inertia *= l.mass / mass0[i];
      std::snprintf(buf, sizeof buf, "link '%s': mass %.4g -> %.4g kg (parent/child ratio <= %g)",
                    l.name.c_str(), mass0[i], l.mass, r);
      report.push_back(buf);
    }
    const Eigen::SelfAdjointEigenSolver<Mat3> eig(0.5 * (l.inertia + l.inertia.transpose()));
    Vec3 d = eig.eigenvalues();
    const double floor = d.maxCoeff() / std::max(1.0, s.max_inertia_ratio);
    if (d.minCoeff() < floor && floor > 0.0) {
      const Vec3 before = d;
      d = d.cwiseMax(floor);
      l.inertia = eig.eigenvectors() * d.asDiagonal() * eig.eigenvectors().transpose();
      std::snprintf(buf, sizeof buf,
                    "link '%s': principal moments (%.3g %.3g %.3g) -> (%.3g %.3g %.3g) kg m^2",
                    l.name.c_str(), before[0], before[1], before[2], d[0], d[1], d[2]);
      report.push_back(buf);
    }
  }
  def.notes.insert(def.notes.end(), report.begin(), report.end());
  return report;
}

}  // namespace ragdoll_sim
