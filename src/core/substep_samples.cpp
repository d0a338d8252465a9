// Velocities of tracked bodies at the end of every substep (SubstepVelocities; the data and
// who writes it: substep_samples.hpp).
#include <algorithm>

#include "ragdoll_sim/world.hpp"

#include "world_impl.hpp"

namespace ragdoll_sim {

void World::trackBody(BodyId body, bool on) {
  Impl& w = *impl_;
  w.checkBody(body);
  auto& t = w.tracks;
  const auto it = std::find_if(t.begin(), t.end(), [&](const BodyTrack& b) {
    return b.body == body.index;
  });
  if (!on) {
    if (it != t.end()) t.erase(it);
  } else if (it == t.end()) {
    BodyTrack b;
    b.body = body.index;
    t.push_back(std::move(b));
  }
}

bool World::substepVelocities(BodyId body, SubstepVelocities* out) const {
  const Impl& w = *impl_;
  if (!w.validBody(body)) return false;
  for (const BodyTrack& b : w.tracks)
    if (b.body == body.index) {
      if (!b.valid) return false;
      *out = b.samples;
      return true;
    }
  return false;
}

// Before the solve, once the islands are known: each track's place in them, its substep
// length and count, and its velocity at the start; a body no island solves (asleep, static)
// gets equal samples of that velocity now.
void World::Impl::beginSamples(const StepContexts& ctx, bool solved) {
  for (BodyTrack& t : tracks) {
    const BodyMotion& m = motions[t.body];
    const int island = solved ? island_of_body[t.body] : -1;
    const StepContext& c = ctx.of(island >= 0 && island_ranges[island].resting);
    SubstepVelocities& s = t.samples;
    s.h = c.h;
    s.start_linear = m.v;
    s.start_angular = m.w;
    s.linear.assign(size_t(c.substeps), m.v);
    s.angular.assign(size_t(c.substeps), m.w);
    t.valid = true;
    t.pos = -1;
    if (island < 0) continue;
    const IslandRange& r = island_ranges[island];
    const auto first = island_bodies.begin() + r.body_begin;
    t.pos = int(std::find(first, island_bodies.begin() + r.body_end, t.body) -
                island_bodies.begin());
  }
}

// Substep `sub` of part p (an island, or a half of a split one on this thread) just ended.
void World::Impl::sampleSubstep(const IslandRange& p, int sub,
                                const std::vector<SolverBody>& solver) {
  for (BodyTrack& t : tracks)
    if (t.pos >= p.body_begin && t.pos < p.body_end) {
      t.samples.linear[size_t(sub)] = solver[t.body].v;
      t.samples.angular[size_t(sub)] = solver[t.body].w;
    }
}

// Part p's bodies took the step: the last sample is what they end it with (restitution and
// the speed caps included).
void World::Impl::sampleFinish(const IslandRange& p) {
  for (BodyTrack& t : tracks)
    if (t.pos >= p.body_begin && t.pos < p.body_end) {
      t.samples.linear.back() = motions[t.body].v;
      t.samples.angular.back() = motions[t.body].w;
    }
}

void World::Impl::untrack(int body) {
  tracks.erase(std::remove_if(tracks.begin(), tracks.end(),
                              [&](const BodyTrack& t) { return t.body == body; }),
               tracks.end());
}

}  // namespace ragdoll_sim
