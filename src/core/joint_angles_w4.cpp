// The joint angles four lanes at a time in AVX registers, compiled with -mavx2 -mno-fma
// (CMakeLists.txt) and called only on a CPU with AVX2; see joint_angles_kernel.hpp. Without
// those flags it runs two lanes at a time, with the same bits.
#include "joint_angles_kernel.hpp"

namespace ragdoll_sim {
namespace joint_angles_w4 {

using Lanes = double_lanes::WidestLanes;

void hingeAngles(const HingeAngleJob* jobs, int count) {
  joint_angles::jobBlocks<Lanes>(jobs, count);
}
void eulerAngles(const EulerAngleJob* jobs, int count) {
  joint_angles::jobBlocks<Lanes>(jobs, count);
}

}  // namespace joint_angles_w4
}  // namespace ragdoll_sim
