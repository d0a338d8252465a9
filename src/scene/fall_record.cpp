// FallRecorder (fall_record.hpp): per-step peaks from the Scene's reports, the rest test on the
// ragdoll's bodies, and the rest pose from the root and torso links at the end.
#include "ragdoll_sim/fall_record.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace ragdoll_sim {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string rangeError(const char* field, double value, const char* rule) {
  std::ostringstream s;
  s << field << " must be " << rule << ", got " << value;
  return s.str();
}

bool finiteState(const BodyState& s) {
  return s.pose.p.allFinite() && s.pose.q.coeffs().allFinite() && s.linear_velocity.allFinite() &&
         s.angular_velocity.allFinite();
}

}  // namespace

std::string fallRecordDefError(const FallRecordDef& d) {
  const double kHalfPi = 1.5707963267948966;
  if (!(std::isfinite(d.rest_speed) && d.rest_speed >= 0))
    return rangeError("rest_speed", d.rest_speed, "a finite number >= 0");
  if (!(std::isfinite(d.rest_angular_speed) && d.rest_angular_speed >= 0))
    return rangeError("rest_angular_speed", d.rest_angular_speed, "a finite number >= 0");
  if (!(std::isfinite(d.min_rest) && d.min_rest >= 0))
    return rangeError("min_rest", d.min_rest, "a finite number >= 0");
  if (!(d.up.allFinite() && d.up.norm() > 1e-9)) return "up must be a finite nonzero vector";
  if (!(d.forward.allFinite() && d.forward.norm() > 1e-9))
    return "forward must be a finite nonzero vector";
  if (!(std::isfinite(d.upright_angle) && d.upright_angle > 0 && d.upright_angle < kHalfPi))
    return rangeError("upright_angle", d.upright_angle, "in (0, pi/2) rad");
  if (!(std::isfinite(d.lying_angle) && d.lying_angle > 0 && d.lying_angle < kHalfPi))
    return rangeError("lying_angle", d.lying_angle, "in (0, pi/2) rad");
  return "";
}

const char* restClassName(RestClass c) {
  switch (c) {
    case RestClass::Upright: return "upright";
    case RestClass::Supine: return "supine";
    case RestClass::Prone: return "prone";
    case RestClass::Side: return "side";
    case RestClass::Other: break;
  }
  return "other";
}

Vec3 rpyFromQuat(const Quat& q) {
  const Mat3 R = q.normalized().toRotationMatrix();
  const double pitch = std::asin(std::clamp(-R(2, 0), -1.0, 1.0));
  // Near pitch +-pi/2 roll and yaw share one axis: all of it goes into yaw.
  if (std::abs(R(2, 0)) > 1.0 - 1e-12) return Vec3(0.0, pitch, std::atan2(-R(0, 1), R(1, 1)));
  return Vec3(std::atan2(R(2, 1), R(2, 2)), pitch, std::atan2(R(1, 0), R(0, 0)));
}

RestClass classifyRest(const Quat& q, const FallRecordDef& def) {
  const Quat n = q.normalized();
  const double up_z = (n * def.up.normalized()).z();
  const double forward_z = (n * def.forward.normalized()).z();
  if (up_z >= std::cos(def.upright_angle)) return RestClass::Upright;
  if (std::abs(up_z) > std::sin(def.lying_angle)) return RestClass::Other;
  if (forward_z >= std::cos(def.lying_angle)) return RestClass::Supine;
  if (forward_z <= -std::cos(def.lying_angle)) return RestClass::Prone;
  return RestClass::Side;
}

FallRecorder::FallRecorder(const Scene& scene, const std::string& ragdoll, FallRecordDef def)
    : def_(std::move(def)) {
  const std::string bad = fallRecordDefError(def_);
  if (!bad.empty()) throw std::invalid_argument("fall record: " + bad);
  const int k = scene.find(ragdoll);
  if (k < 0 || scene.isObject(k))
    throw std::invalid_argument("fall record: no ragdoll '" + ragdoll + "' in the scene");
  id_ = scene.id(k);
  name_ = scene.name(k);
  const RagdollDef& rd = scene.def(k);
  if (!def_.torso_link.empty()) {
    torso_ = rd.findLink(def_.torso_link);
    if (torso_ < 0)
      throw std::invalid_argument("fall record: ragdoll '" + name_ + "' has no link '" +
                                  def_.torso_link + "' (torso_link)");
  } else {
    torso_ = rd.findLink("torso");
    if (torso_ < 0) torso_ = rd.root;
  }
  start_time_ = scene.time();
  start_faults_ = static_cast<int64_t>(scene.counters().body_faults);
  head_on_ = !scene.headLink(k).empty();
  rec_.ragdoll = name_;
  rec_.head_link = scene.headLink(k);
  for (const LinkDef& l : rd.links) rec_.links.push_back(l.name);
  rec_.peak_contact_force.assign(rd.links.size(), 0.0);
}

int FallRecorder::ragdollIndex(const Scene& scene) const { return scene.indexOf(id_); }

void FallRecorder::sample(const Scene& scene) {
  const int k = scene.indexOf(id_);
  if (k < 0) return;
  ++rec_.samples;
  const double now = scene.time();
  rec_.duration = now - start_time_;

  scene.linkLoads(k, link_scratch_);
  for (size_t l = 0; l < link_scratch_.size() && l < rec_.peak_contact_force.size(); ++l) {
    const double f = link_scratch_[l].contact_force.norm();
    // A non-finite force is the NaN flag's business, not a peak.
    if (std::isfinite(f)) rec_.peak_contact_force[l] = std::max(rec_.peak_contact_force[l], f);
    else rec_.nan = true;
  }

  for (const BrokenJointReport& b : scene.brokenJoints())
    if (b.ragdoll == name_) rec_.broken_joints.push_back(b.joint);

  if (head_on_)
    for (const InjuryReport& r : scene.injuryReports())
      if (r.ragdoll == name_) {
        rec_.head_peak_g = std::max(rec_.head_peak_g, r.peak_g);
        rec_.hic15 = std::max(rec_.hic15, r.hic15);
      }

  const World& world = scene.world();
  bool at_rest = true;
  for (const BodyId b : scene.bodies(k).bodies) {
    if (!world.isValid(b)) continue;
    const BodyState s = world.bodyState(b);
    if (!finiteState(s)) {
      rec_.nan = true;
      at_rest = false;
      continue;
    }
    if (at_rest && world.isAwake(b) &&
        !(s.linear_velocity.norm() < def_.rest_speed &&
          s.angular_velocity.norm() < def_.rest_angular_speed))
      at_rest = false;
  }
  if (static_cast<int64_t>(scene.counters().body_faults) > start_faults_) rec_.nan = true;
  if (!at_rest) rest_since_ = -1.0;
  else if (rest_since_ < 0.0) rest_since_ = now;
}

void FallRecorder::run(Scene& scene, int64_t steps) {
  for (int64_t i = 0; i < steps; ++i) {
    scene.step();
    sample(scene);
  }
}

FallRecord FallRecorder::record(const Scene& scene) const {
  FallRecord out = rec_;
  out.body_faults = static_cast<int64_t>(scene.counters().body_faults) - start_faults_;
  const double now = start_time_ + rec_.duration;
  out.time_to_rest = rest_since_ >= 0.0 && now - rest_since_ >= def_.min_rest - 1e-12
                         ? rest_since_ - start_time_
                         : kNaN;
  const int k = scene.indexOf(id_);
  if (k < 0) {
    out.root_position = Vec3::Constant(kNaN);
    out.roll = out.pitch = out.yaw = kNaN;
    out.rest = RestClass::Other;
    return out;
  }
  if (head_on_) {
    const InjuryReport now_rec = scene.injury(k);
    out.head_peak_g = std::max(out.head_peak_g, now_rec.peak_g);
    out.hic15 = std::max(out.hic15, now_rec.hic15);
  }
  const RagdollDef& rd = scene.def(k);
  const World& world = scene.world();
  const std::vector<BodyId>& bodies = scene.bodies(k).bodies;
  const Transform root = world.bodyPose(bodies[static_cast<size_t>(rd.root)]);
  out.root_position = root.p;
  const Vec3 rpy = rpyFromQuat(root.q);
  out.roll = rpy.x();
  out.pitch = rpy.y();
  out.yaw = rpy.z();
  out.rest = classifyRest(world.bodyPose(bodies[static_cast<size_t>(torso_)]).q, def_);
  return out;
}

}  // namespace ragdoll_sim
