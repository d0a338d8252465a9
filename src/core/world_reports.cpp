// World reports of the last step: the contact forces of each touching shape pair
// (world_reports.hpp), derived on request from what the solver keeps for its warm start (the
// last substep's accumulated impulses) and, with impulse tracking on, from what the step
// filed of each contact (ContactTrack, contact.hpp).
#include "ragdoll_sim/world.hpp"

#include "world_impl.hpp"

namespace ragdoll_sim {

void World::setContactImpulseTracking(bool on) {
  Impl& w = *impl_;
  w.track_contacts = on;
  if (!on) w.contact_tracks.clear();  // the capacity stays for the next time it is on
}

bool World::contactImpulseTracking() const { return impl_->track_contacts; }

namespace {
// A point touches when it overlapped at the step's collide or carried a normal impulse in the
// step; a speculative point that stayed apart does not.
bool touching(const Contact& c, const ContactTrack* t, int i) {
  return c.manifold.points[i].separation <= 0.0 || c.normal_impulse[i] > 0.0 ||
         (t && t->step_impulse[i] > 0.0);
}
// Velocity of body m's material point at offset r from its centre of mass.
Vec3 materialVelocity(const BodyMotion& m, const Vec3& r) { return m.v + m.w.cross(r); }
}  // namespace

void World::contactReports(std::vector<ContactReport>& out) const {
  out.clear();
  const Impl& w = *impl_;
  const bool tracked = w.track_contacts && w.contact_tracks.size() == w.contacts.size();
  if (w.solver.size() < w.motions.size()) return;  // no step yet since the bodies were made
  for (size_t ci = 0; ci < w.contacts.size(); ++ci) {
    const Contact& c = w.contacts[ci];
    const ContactTrack* t =
        tracked && w.contact_tracks[ci].key == c.key ? &w.contact_tracks[ci] : nullptr;
    bool any = false;
    for (int i = 0; i < c.manifold.count && !any; ++i) any = touching(c, t, i);
    if (!any) continue;

    const BodyMotion &A = w.motions[c.body_a], &B = w.motions[c.body_b];
    const SolverBody &sA = w.solver[c.body_a], &sB = w.solver[c.body_b];
    // The lever arms the solver used: from each centre at the step's start (the end less the
    // step's displacement dp; a body the step did not move has dp 0) to the points.
    const Vec3 oA = c.origin - (A.x - sA.dp), oB = c.origin - (B.x - sB.dp);
    const double inv_h = c.impulse_h > 0.0 ? 1.0 / c.impulse_h : 0.0;
    const Vec3& n = c.manifold.normal;
    ContactReport& r = out.emplace_back();
    r.body_a = BodyId{c.body_a};
    r.body_b = BodyId{c.body_b};
    r.shape_a = w.shapes[c.shape_a].index;
    r.shape_b = w.shapes[c.shape_b].index;
    r.normal = n;
    for (int i = 0; i < c.manifold.count; ++i) {
      if (!touching(c, t, i)) continue;
      const ManifoldPoint& mp = c.manifold.points[i];
      ContactPointReport& p = r.points[r.count++];
      const Vec3 rA = mp.point + oA, rB = mp.point + oB;
      p.point = c.origin + mp.point;
      p.depth = -mp.separation;
      p.normal_force = c.normal_impulse[i] * inv_h;
      p.friction_force = c.friction_impulse[i] * inv_h;
      if (t) {
        p.step_impulse = t->step_impulse[i];
        p.peak_force = t->peak_force[i];
        p.closing_speed = t->closing_speed[i];
      }
      // at the point as the bodies carried it through the step (turned by dq)
      p.separating_speed =
          (materialVelocity(B, sB.dq * rB) - materialVelocity(A, sA.dq * rA)).dot(n);
      const Vec3 f = p.normal_force * n + p.friction_force;  // on B
      r.force_b += f;
      r.torque_b += rB.cross(f);
      r.torque_a -= rA.cross(f);
    }
    const Vec3 rolling = c.rolling_impulse * inv_h;  // angular, on B
    r.torque_b += rolling;
    r.torque_a -= rolling;
    r.force_a = -r.force_b;
  }
}

}  // namespace ragdoll_sim
