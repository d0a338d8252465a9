// The baseline build of the joint angle kernel (two lanes in SSE2; one alone for the tests'
// atan2 and asin) and the run-time choice of width (byLaneWidth); see joint_angles_kernel.hpp.
#include "joint_angles_kernel.hpp"
#include "lane_width.hpp"

namespace ragdoll_sim {

namespace {
// Four at a time where the CPU has AVX2, else two (byLaneWidth).
template <class Job>
void allJobs(const Job* jobs, int count, void (*four)(const Job*, int)) {
  byLaneWidth(jobs, count, [&](int width, const Job* j, int n) {
    if (width == 4) four(j, n);
    else joint_angles::jobBlocks<double_lanes::Double2>(j, n);
  });
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
