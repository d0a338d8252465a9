// The position step four bodies at a time in AVX registers, compiled with -mavx2 -mno-fma
// (CMakeLists.txt) and called only on a CPU with AVX2; see integrate_kernel.hpp. Without those
// flags (a compiler or target without AVX2) it runs two bodies at a time, with the same bits.
#include "integrate_kernel.hpp"

namespace ragdoll_sim {
namespace integrate_w4 {

using Lanes = double_lanes::WidestLanes;

void stepPositions(const integrate_kernel::BodyFields& f, const int* bodies, int count, double h,
                   double half_h) {
  integrate_kernel::stepPositions<Lanes>(f, bodies, count, h, half_h);
}

int advanceVelocities(const integrate_kernel::BodyFields& f, const int* bodies, int count, double h,
                      const double* gravity, double max_v2, double max_w2, int* clamp) {
  return integrate_kernel::advanceVelocities<Lanes>(f, bodies, count, h, gravity, max_v2, max_w2,
                                                    clamp);
}

void prepareRotations(const integrate_kernel::BodyFields& f, const int* bodies, int count) {
  integrate_kernel::prepareRotations<Lanes>(f, bodies, count);
}

void finishPoses(const integrate_kernel::BodyFields& f, const int* bodies, int count, double grid,
                 double range) {
  integrate_kernel::finishPoses<Lanes>(f, bodies, count, grid, range);
}

}  // namespace integrate_w4
}  // namespace ragdoll_sim
