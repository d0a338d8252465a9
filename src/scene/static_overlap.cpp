// Ragdolls placed into static geometry: the check and the lift (static_overlap.hpp).
#include "static_overlap.hpp"

namespace ragdoll_sim {
namespace scene {

namespace {
// One pass clears a plane exactly; more are for a ragdoll between several static shapes, and
// a ragdoll still inside one after them is wedged where no lift frees it.
constexpr int kMaxLiftPasses = 8;
}  // namespace

bool overlapsStatics(const World& world, const std::vector<BodyId>& bodies,
                     StaticOverlap* overlap) {
  *overlap = world.staticOverlap(bodies);
  return overlap->depth > kStaticOverlapSlop;
}

StaticLift liftOutOfStatics(World& world, const std::vector<BodyId>& bodies) {
  StaticLift out;
  StaticOverlap o;
  if (!overlapsStatics(world, bodies, &o)) return out;
  out.first = o;
  for (int pass = 0; pass < kMaxLiftPasses; ++pass) {
    const Vec3 move = o.depth * o.direction;
    for (BodyId b : bodies) {
      const BodyState s = world.bodyState(b);
      world.setBodyState(b, Transform(s.pose.p + move, s.pose.q), s.linear_velocity,
                         s.angular_velocity);
    }
    out.lift += move;
    if (!overlapsStatics(world, bodies, &o)) return out;
  }
  out.clear = false;
  return out;
}

}  // namespace scene
}  // namespace ragdoll_sim
