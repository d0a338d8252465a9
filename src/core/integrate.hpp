// The body arrays as integrate_kernel.hpp reads them (integrate.cpp).
#pragma once

#include <vector>

#include "body.hpp"
#include "integrate_kernel.hpp"

namespace ragdoll_sim {

// Bases, strides and offsets of the fields the position step reads; the arrays are not empty.
integrate_kernel::BodyFields bodyFields(std::vector<SolverBody>& solver,
                                        std::vector<BodyMotion>& motions,
                                        std::vector<Mat3>& rotations);

}  // namespace ragdoll_sim
