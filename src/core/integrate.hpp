// The body arrays as integrate_kernel.hpp reads them (integrate.cpp).
#pragma once

#include <vector>

#include "body.hpp"
#include "integrate_kernel.hpp"

namespace ragdoll_sim {

// Bases, strides and offsets of the fields the position step reads; the arrays are not empty.
integrate_kernel::BodyFields bodyFields(std::vector<SolverBody>& solver,
                                        const std::vector<BodyMotion>& motions,
                                        std::vector<Mat3>& rotations);
// Those finishPoses reads and writes; the arrays are not empty.
integrate_kernel::PoseFields poseFields(std::vector<BodyMotion>& motions,
                                        const std::vector<SolverBody>& solver);

}  // namespace ragdoll_sim
