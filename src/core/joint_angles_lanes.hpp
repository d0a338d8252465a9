// The exact angles and rate rows of hinges and Euler ball joints (joint_angles.hpp derives
// them), computed W joints at a time in double lanes: four in AVX registers
// (joint_angles_w4.cpp, only on a CPU with AVX2), else two in SSE2 ones (joint_angles_lanes.cpp;
// a last joint or a lone one fills the spare lanes, byLaneWidth). Every width (one alone too, in
// the tests) does the same IEEE operations in the same order, with atan2 and asin of their own
// (joint_angles_kernel.hpp) instead of libm's, so a joint's angles have the same bits whether
// it was computed alone (HingeJoint::updateAngle, the projection, the reports) or with others
// (PointLanes::exactAngles).
// Plain records and declarations only: the AVX2 kernel file includes this header too.
#pragma once

namespace ragdoll_sim {

// Quaternions are x, y, z, w. A joint's frames are fa = (dq_a q_a) frame_a and
// fb = (dq_b q_b) frame_b: the bodies' rotation deltas, step-start rotations and joint frames.
struct JointFrameInputs {
  const double *dq_a, *q_a, *frame_a, *dq_b, *q_b, *frame_b;
};

// Hinge: row = fa axis, angle = atan2(row . (fa perp x fb perp), fa perp . fb perp).
struct HingeAngleJob {
  JointFrameInputs in;
  const double *axis, *perp;  // joint frame
  double *row, *angle;        // 3, 1
};

// Euler (EulerBasis): the angles of qP^-1 fa^-1 fb qP and their world rows; ok 0 near gimbal
// lock (the rows then are not written).
struct EulerAngleJob {
  JointFrameInputs in;
  const double *basis, *sign;  // EulerBasis::qP, s
  double *angles, *rows, *ok;  // 3, 9 (row after row), 1
};

// jobs[0, count), with the widest lanes the CPU runs.
void hingeAngles(const HingeAngleJob* jobs, int count);
void eulerAngles(const EulerAngleJob* jobs, int count);

// atan2 and asin as the kernel computes them (within 2 ulp of libm's; finite arguments, |s| <=
// 1), for tests.
double laneAtan2(double y, double x);
double laneAsin(double s);

// The kernels behind them, on a count that is a multiple of four (byLaneWidth).
namespace joint_angles_w4 {
void hingeAngles(const HingeAngleJob* jobs, int count);
void eulerAngles(const EulerAngleJob* jobs, int count);
}  // namespace joint_angles_w4

}  // namespace ragdoll_sim
