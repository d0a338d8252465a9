// sizeof and alignof of the public structs that hold Eigen types, for test_layout.cpp: one list,
// expanded in two translation units built with different Eigen settings.
#pragma once

#include <cstddef>
#include <vector>

#include "ragdoll_sim/body.hpp"
#include "ragdoll_sim/joint.hpp"
#include "ragdoll_sim/math.hpp"
#include "ragdoll_sim/ragdoll.hpp"
#include "ragdoll_sim/shape.hpp"
#include "ragdoll_sim/world.hpp"

namespace ragdoll_sim::test {
struct LayoutEntry {
  const char* name;
  std::size_t size, align;
};
#define RAGDOLL_SIM_LAYOUT_ENTRY(T) LayoutEntry{#T, sizeof(T), alignof(T)}
#define RAGDOLL_SIM_LAYOUT_ENTRIES                                                            \
  {                                                                                           \
    RAGDOLL_SIM_LAYOUT_ENTRY(Quat), RAGDOLL_SIM_LAYOUT_ENTRY(Transform),                      \
        RAGDOLL_SIM_LAYOUT_ENTRY(BodyDef), RAGDOLL_SIM_LAYOUT_ENTRY(BodyState),               \
        RAGDOLL_SIM_LAYOUT_ENTRY(ShapeDef), RAGDOLL_SIM_LAYOUT_ENTRY(BallJointDef),           \
        RAGDOLL_SIM_LAYOUT_ENTRY(HingeJointDef), RAGDOLL_SIM_LAYOUT_ENTRY(FixedJointDef),     \
        RAGDOLL_SIM_LAYOUT_ENTRY(PrismaticJointDef), RAGDOLL_SIM_LAYOUT_ENTRY(LinkDef),       \
        RAGDOLL_SIM_LAYOUT_ENTRY(RagdollJointDef), RAGDOLL_SIM_LAYOUT_ENTRY(RagdollDef),      \
        RAGDOLL_SIM_LAYOUT_ENTRY(WorldDef), RAGDOLL_SIM_LAYOUT_ENTRY(ContactInfo),            \
  }
std::vector<LayoutEntry> layoutWithDefaultEigen();
}  // namespace ragdoll_sim::test
