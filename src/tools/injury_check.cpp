// See injury_check.hpp.
#include "injury_check.hpp"

#include <cstdio>

namespace ragdoll_sim {

namespace {

void printOne(const InjuryReport& f, const char* status) {
  std::printf("injury: ragdoll '%s', head '%s', neck '%s': %.3f-%.3f s of sim time (%s)\n",
              f.ragdoll.c_str(), f.head_link.c_str(),
              f.neck_joint.empty() ? "(none)" : f.neck_joint.c_str(), f.start_time, f.end_time,
              status);
  std::printf("  peak acceleration %.1f g at %.4f s\n", f.peak_g, f.peak_time);
  std::printf("  HIC15 %.1f over %.4f-%.4f s, HIC36 %.1f over %.4f-%.4f s\n", f.hic15,
              f.hic15_t1, f.hic15_t2, f.hic36, f.hic36_t1, f.hic36_t2);
  std::printf("  peak angular acceleration %.0f rad/s^2\n", f.peak_angular_acceleration);
  std::printf("  peak neck force %.1f N, torque %.2f N m\n", f.peak_neck_force,
              f.peak_neck_torque);
  std::printf("injury: status=%s start_s=%.4f end_s=%.4f peak_g=%.2f peak_s=%.4f hic15=%.2f "
              "hic15_t1=%.4f hic15_t2=%.4f hic36=%.2f hic36_t1=%.4f hic36_t2=%.4f "
              "peak_angular_acceleration=%.1f neck_force_n=%.2f neck_torque_nm=%.3f\n",
              status, f.start_time, f.end_time, f.peak_g, f.peak_time, f.hic15, f.hic15_t1,
              f.hic15_t2, f.hic36, f.hic36_t1, f.hic36_t2, f.peak_angular_acceleration,
              f.peak_neck_force, f.peak_neck_torque);
}

}  // namespace

void printInjury(const std::vector<InjuryReport>& falls, const InjuryReport& running) {
  for (const InjuryReport& f : falls) printOne(f, f.reason.c_str());
  if (falls.empty()) printOne(running, "running");
}

}  // namespace ragdoll_sim
