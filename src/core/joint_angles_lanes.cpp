// The baseline build of the joint angle kernel (two lanes in SSE2, one alone) and the run-time
// choice of width; see joint_angles_kernel.hpp.
#include "joint_angles_kernel.hpp"
#include "lane_width.hpp"

namespace ragdoll_sim {

namespace {
using joint_angles::eulerBlocks;
using joint_angles::hingeBlocks;
using double_lanes::Double2;
}  // namespace

void hingeAngles(const HingeAngleJob* jobs, int count) {
  int done = cpuHasAvx2() ? joint_angles_w4::hingeAngles(jobs, count) : 0;
  done += hingeBlocks<Double2>(jobs + done, count - done);
  hingeBlocks<double>(jobs + done, count - done);
}

void eulerAngles(const EulerAngleJob* jobs, int count) {
  int done = cpuHasAvx2() ? joint_angles_w4::eulerAngles(jobs, count) : 0;
  done += eulerBlocks<Double2>(jobs + done, count - done);
  eulerBlocks<double>(jobs + done, count - done);
}

double laneAtan2(double y, double x) { return joint_angles::atan2Lanes(y, x); }
double laneAsin(double s) { return joint_angles::asinLanes(s); }

}  // namespace ragdoll_sim
