// The shape boxes four at a time in AVX registers, compiled with -mavx2 -mno-fma (CMakeLists.txt)
// and called only on a CPU with AVX2; see shape_boxes_kernel.hpp. Without those flags (a compiler
// or target without AVX2) it runs two shapes at a time, with the same bits.
#include "shape_boxes_kernel.hpp"

namespace ragdoll_sim {
namespace shape_boxes_w4 {

void shapeBoxes(int kind, const shape_boxes::ShapeBoxJob* jobs, int count, double spec,
                double dt) {
  using namespace shape_boxes;
  using Lanes = double_lanes::WidestLanes;
  switch (kind) {
    case kSphereBox: return shape_boxes::shapeBoxes<kSphereBox, Lanes>(jobs, count, spec, dt);
    case kCapsuleBox: return shape_boxes::shapeBoxes<kCapsuleBox, Lanes>(jobs, count, spec, dt);
    case kBoxBox: return shape_boxes::shapeBoxes<kBoxBox, Lanes>(jobs, count, spec, dt);
    default: return shape_boxes::shapeBoxes<kCylinderBox, Lanes>(jobs, count, spec, dt);
  }
}

}  // namespace shape_boxes_w4
}  // namespace ragdoll_sim
