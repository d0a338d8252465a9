// See drop_check.hpp.
#include "ragdoll_sim/drop_check.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

namespace ragdoll_sim {

namespace {
// s of sim time a model dropped 5 cm takes to settle; shorter runs are not asked to be at rest.
constexpr double kSettleSeconds = 2.0;
}  // namespace

double lowestPoint(const ShapeDef& shape, const Transform& body_pose) {
  const Transform W = body_pose * shape.local;
  const Geometry& g = shape.geometry;
  const Mat3 R = W.q.toRotationMatrix();
  const Vec3 up = R.row(2).transpose();  // world z in shape axes
  switch (g.type) {
    case ShapeType::Sphere: return W.p.z() - g.radius;
    case ShapeType::Capsule: return W.p.z() - g.half_height * std::abs(up.z()) - g.radius;
    case ShapeType::Box: return W.p.z() - g.half_extents.dot(up.cwiseAbs());
    case ShapeType::Cylinder:
      return W.p.z() - g.half_height * std::abs(up.z()) - g.radius * up.head<2>().norm();
    case ShapeType::ConvexHull: {
      double z = std::numeric_limits<double>::infinity();
      if (g.hull)
        for (const Vec3& v : g.hull->vertices) z = std::min(z, W.apply(v).z());
      return z;
    }
    case ShapeType::Plane: break;
  }
  return std::numeric_limits<double>::infinity();
}

double highestPoint(const ShapeDef& shape, const Transform& body_pose) {
  const Geometry& g = shape.geometry;
  if (g.type == ShapeType::Plane) return -std::numeric_limits<double>::infinity();
  if (g.type == ShapeType::ConvexHull) {
    double z = -std::numeric_limits<double>::infinity();
    if (g.hull)
      for (const Vec3& v : g.hull->vertices) z = std::max(z, (body_pose * shape.local).apply(v).z());
    return z;
  }
  // The other primitives are symmetric about their origin.
  return 2 * (body_pose * shape.local).p.z() - lowestPoint(shape, body_pose);
}

namespace {
bool hasShapes(const RagdollDef& def) {
  for (const LinkDef& l : def.links)
    if (!l.shapes.empty()) return true;
  return false;
}

// Lowest shape point of `link` at `pose`; a link without shapes counts with its centre of mass,
// so that a body with nothing to hold it up shows when it falls through the ground.
double linkLowest(const LinkDef& link, const Transform& pose) {
  if (link.shapes.empty()) return pose.apply(link.com).z();
  double z = std::numeric_limits<double>::infinity();
  for (const ShapeDef& s : link.shapes) z = std::min(z, lowestPoint(s, pose));
  return z;
}
}  // namespace

double restLowestPoint(const RagdollDef& def) {
  const Transform root_inv = def.links.at(def.root).rest_pose.inverse();
  const bool shapes = hasShapes(def);
  double z0 = std::numeric_limits<double>::infinity();
  for (const LinkDef& l : def.links)
    if (!shapes || !l.shapes.empty()) z0 = std::min(z0, linkLowest(l, root_inv * l.rest_pose));
  return std::isfinite(z0) ? z0 : 0.0;
}

namespace {
double lowest(const World& world, const Ragdoll& r, const RagdollDef& def) {
  double z = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < r.bodies.size(); ++i)
    z = std::min(z, linkLowest(def.links[i], world.bodyPose(r.bodies[i])));
  return z;
}

// Kinetic plus gravitational energy of the ragdoll's bodies alone.
double mechanicalEnergy(const World& world, const Ragdoll& r) {
  double e = 0.0;
  const Vec3& g = world.def().gravity;
  for (BodyId b : r.bodies) {
    const BodyDef& d = world.bodyDef(b);
    if (d.type != BodyType::Dynamic) continue;
    const BodyState st = world.bodyState(b);
    const Vec3 w = st.pose.q.conjugate() * st.angular_velocity;  // link axes
    e += 0.5 * d.mass * st.linear_velocity.squaredNorm() + 0.5 * w.dot(d.inertia * w);
    e -= d.mass * g.dot(st.com_position);
  }
  return e;
}

bool isFinite(const BodyState& st) {
  return st.pose.p.allFinite() && st.pose.q.coeffs().allFinite() && st.linear_velocity.allFinite() &&
         st.angular_velocity.allFinite();
}
}  // namespace

namespace {
WorldDef dropWorldDef(const DropSettings& settings) {
  WorldDef wd;
  wd.solver.substeps = settings.substeps;
  return wd;
}
}  // namespace

DropWorld::DropWorld(const RagdollDef& def, const DropSettings& settings)
    : world(dropWorldDef(settings)) {
  BodyDef gd;
  gd.type = BodyType::Static;
  gd.name = "ground";
  ShapeDef ground;
  ground.geometry = Geometry::plane(Vec3::UnitZ(), 0.0);
  world.addShape(world.createBody(gd), ground);
  // Rest pose with the root at the origin: lift it so the lowest point is `clearance` up.
  spawn_z = settings.clearance - restLowestPoint(def);
  ragdoll = spawnRagdoll(world, def, Transform(Vec3(0, 0, spawn_z), Quat::Identity()));
}

DropReport dropTest(const RagdollDef& def, const DropSettings& settings) {
  DropWorld d(def, settings);
  DropReport measured =
      measureDrop(d.world, d.ragdoll, def, [&] { d.world.step(settings.dt); }, settings);
  measured.spawn_z = d.spawn_z;
  return measured;
}

DropReport measureDrop(const World& world, const Ragdoll& r, const RagdollDef& def,
                       const std::function<void()>& step, const DropSettings& settings) {
  DropReport rep;
  std::vector<char> mine(world.bodyCount(), 0);
  for (BodyId b : r.bodies) mine.at(b.index) = 1;
  const auto ours = [&](const ContactInfo& c) {
    return (size_t(c.body_a.index) < mine.size() && mine[c.body_a.index]) ||
           (size_t(c.body_b.index) < mine.size() && mine[c.body_b.index]);
  };
  const double t0 = world.time();
  rep.spawn_top_z = -std::numeric_limits<double>::infinity();
  for (BodyId b : r.bodies) rep.spawn_top_z = std::max(rep.spawn_top_z, world.bodyState(b).com_position.z());
  rep.min_lowest_point = std::numeric_limits<double>::infinity();
  const int steps = int(std::lround(settings.seconds / settings.dt));
  const int late = steps - std::min(steps / 2, int(std::lround(2.0 / settings.dt)));  // >= steps / 2
  double late_energy = mechanicalEnergy(world, r);
  for (int s = 0; s < steps; ++s) {
    if (s == late) late_energy = mechanicalEnergy(world, r);
    step();
    for (BodyId b : r.bodies) rep.finite = rep.finite && isFinite(world.bodyState(b));
    if (!rep.finite) break;
    rep.seconds = world.time() - t0;
    for (const ContactInfo& c : world.contacts())
      if (ours(c)) rep.max_penetration = std::max(rep.max_penetration, -c.separation);
    for (JointId j : r.joints)
      rep.max_anchor_error = std::max(rep.max_anchor_error, world.jointAnchorError(j).norm());
    for (BodyId b : r.bodies)
      rep.max_speed = std::max(rep.max_speed, world.bodyState(b).linear_velocity.norm());
    rep.min_lowest_point = std::min(rep.min_lowest_point, lowest(world, r, def));
  }
  rep.rest_height = world.bodyPose(r.bodies.at(def.root)).p.z();
  for (JointId j : r.joints)
    rep.final_anchor_error = std::max(rep.final_anchor_error, world.jointAnchorError(j).norm());
  rep.lowest_point = lowest(world, r, def);
  std::vector<char> touching(world.bodyCount(), 0);
  for (const ContactInfo& c : world.contacts())
    if (c.separation < 1e-3) touching[c.body_a.index] = touching[c.body_b.index] = 1;
  for (BodyId b : r.bodies) {
    const BodyState st = world.bodyState(b);
    const double speed = st.linear_velocity.norm() + 0.1 * st.angular_velocity.norm();
    rep.final_speed = std::max(rep.final_speed, speed);
    if (touching[b.index]) rep.final_contact_speed = std::max(rep.final_contact_speed, speed);
  }
  if (rep.finite) rep.late_energy_change = mechanicalEnergy(world, r) - late_energy;
  return rep;
}

namespace {
template <typename... Args>
std::string format(const char* fmt, Args... args) {
  char buf[160];
  std::snprintf(buf, sizeof buf, fmt, args...);
  return buf;
}
}  // namespace

DropVerdict judgeDrop(const DropReport& d, const VerdictRules& rules) {
  DropVerdict v;
  const auto fail = [&](std::string reason) {
    v.pass = false;
    v.reasons.push_back(std::move(reason));
  };
  if (!d.finite) fail(format("NaN: a body state went non-finite after %.3f s", d.seconds));
  const double floor = rules.ground_z - rules.max_sink;
  // Written as !(x <= limit) so that a NaN measurement breaks the rule instead of passing it.
  if (!(d.min_lowest_point >= floor))
    fail(format("fell through the ground: lowest point %.1f mm < %.1f mm",
                1e3 * (d.min_lowest_point - rules.ground_z), -1e3 * rules.max_sink));
  if (!(d.max_anchor_error <= rules.max_anchor_error))
    fail(format("joints stretched: anchor error %.1f mm > %.1f mm", 1e3 * d.max_anchor_error,
                1e3 * rules.max_anchor_error));
  const double g = 9.81;
  const double height = std::max(d.spawn_z, d.spawn_top_z) - rules.ground_z;
  const double limit = std::sqrt(2 * g * std::max(0.0, height)) + rules.speed_margin;
  if (!(d.max_speed <= limit))
    fail(format("exploded: body speed %.2f m/s > %.2f m/s (free fall from %.2f m + %.1f m/s)",
                d.max_speed, limit, height, rules.speed_margin));
  if (rules.expect_rest && d.finite && !(d.final_contact_speed <= rules.rest_speed))
    fail(format("not at rest: touching bodies at %.3f m/s at the end > %.3f m/s", d.final_contact_speed,
                rules.rest_speed));
  return v;
}

VerdictRules dropRules(const DropSettings& settings, double ground_z) {
  VerdictRules rules;
  rules.expect_rest = settings.seconds >= kSettleSeconds;
  rules.ground_z = ground_z;
  return rules;
}

}  // namespace ragdoll_sim
