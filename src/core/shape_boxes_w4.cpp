// The shape boxes four at a time in AVX registers, compiled with -mavx2 -mno-fma (CMakeLists.txt)
// and called only on a CPU with AVX2; see shape_boxes_kernel.hpp. Without those flags (a compiler
// or target without AVX2) it runs two shapes at a time, with the same bits.
#include "shape_boxes_kernel.hpp"

namespace ragdoll_sim {
namespace shape_boxes_w4 {

void shapeBoxes(int kind, const shape_boxes::ShapeBoxJob* jobs, int count, double spec,
                double dt) {
  shape_boxes::shapeBoxesOf<double_lanes::WidestLanes>(kind, jobs, count, spec, dt);
}

}  // namespace shape_boxes_w4
}  // namespace ragdoll_sim
