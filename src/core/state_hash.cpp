#include "ragdoll_sim/state_hash.hpp"

namespace ragdoll_sim {

uint64_t hashStates(const World& world, uint64_t h) {
  for (int i = 0; i < world.bodyCount(); ++i) {
    if (!world.isValid(BodyId{i})) continue;  // a removed body's slot
    const BodyState st = world.bodyState(BodyId{i});
    const double v[13] = {st.pose.p.x(), st.pose.p.y(), st.pose.p.z(), st.pose.q.w(),
                          st.pose.q.x(), st.pose.q.y(), st.pose.q.z(), st.linear_velocity.x(),
                          st.linear_velocity.y(), st.linear_velocity.z(),
                          st.angular_velocity.x(), st.angular_velocity.y(),
                          st.angular_velocity.z()};
    const auto* bytes = reinterpret_cast<const unsigned char*>(v);
    for (size_t k = 0; k < sizeof v; ++k) h = (h ^ bytes[k]) * 1099511628211ull;
  }
  return h;
}

}  // namespace ragdoll_sim
