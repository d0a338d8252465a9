// The baseline build of the joint angle kernel (two lanes in SSE2, one alone) and the run-time
// choice of width; see joint_angles_kernel.hpp.
#include "joint_angles_kernel.hpp"
#include "lane_width.hpp"

namespace ragdoll_sim {

namespace {
// Four at a time where the CPU has AVX2, then two, then one.
template <class Job>
void allJobs(const Job* jobs, int count, int (*four)(const Job*, int)) {
  using joint_angles::jobBlocks;
  int done = cpuHasAvx2() ? four(jobs, count) : 0;
  done += jobBlocks<double_lanes::Double2>(jobs + done, count - done);
  jobBlocks<double>(jobs + done, count - done);
}
}  // namespace

void hingeAngles(const HingeAngleJob* jobs, int count) {
  allJobs(jobs, count, joint_angles_w4::hingeAngles);
}

void eulerAngles(const EulerAngleJob* jobs, int count) {
  allJobs(jobs, count, joint_angles_w4::eulerAngles);
}

double laneAtan2(double y, double x) { return joint_angles::atan2Lanes(y, x); }
double laneAsin(double s) { return joint_angles::asinLanes(s); }

}  // namespace ragdoll_sim
