// Scene: one injury record per ragdoll (injury.hpp, injury_record.hpp; docs/injury.md). The
// head's centre of mass is tracked (World::trackBody). The links' speeds tell when a fall
// starts and ends; during a fall, every step's substep velocities of the head give the proper
// acceleration into the HIC meters and the peaks, and the neck's wrench its peaks. A rebuilt
// World (reset) starts every record afresh; removal reports a fall under way.
#include <algorithm>
#include <cctype>

#include "scene_impl.hpp"

namespace ragdoll_sim {

using scene::InjuryRecord;
using scene::RagdollInstance;

namespace {

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// The first link named like a head, or -1.
int guessHead(const RagdollDef& def) {
  for (const char* word : {"head", "skull"})
    for (size_t l = 0; l < def.links.size(); ++l)
      if (lower(def.links[l].name).find(word) != std::string::npos) return static_cast<int>(l);
  return -1;
}

int findJoint(const RagdollDef& def, const std::string& name) {
  for (size_t j = 0; j < def.joints.size(); ++j) {
    const RagdollJointDef& d = def.joints[j];
    if (d.name == name ||
        std::find(d.source_joints.begin(), d.source_joints.end(), name) != d.source_joints.end())
      return static_cast<int>(j);
  }
  return -1;
}

int parentJoint(const RagdollDef& def, int link) {
  for (size_t j = 0; j < def.joints.size(); ++j)
    if (def.joints[j].child == link) return static_cast<int>(j);
  return -1;
}

}  // namespace

bool Scene::Impl::resolveInjury(RagdollInstance& r, const InjuryDef& d, bool say,
                                std::string* error) {
  InjuryRecord rec;
  rec.def = d;
  const RagdollDef& def = r.def;
  if (d.enabled) {
    if (!d.head_link.empty()) {
      rec.head = def.findLink(d.head_link);
      if (rec.head < 0) {
        *error = "ragdoll '" + r.name + "' has no link '" + d.head_link +
                 "' for the injury record's head (head_link)";
        return false;
      }
    } else {
      rec.head = def.findLink("head");
      if (rec.head < 0) rec.head = guessHead(def);
    }
    if (!d.neck_joint.empty()) {
      rec.neck = findJoint(def, d.neck_joint);
      if (rec.neck < 0) {
        *error = "ragdoll '" + r.name + "' has no joint '" + d.neck_joint +
                 "' for the injury record's neck (neck_joint: a joint or URDF joint name)";
        return false;
      }
    } else if (rec.head >= 0) {
      rec.neck = parentJoint(def, rec.head);
    }
  }
  rec.on = rec.head >= 0;
  if (rec.on) rec.head_name = def.links[static_cast<size_t>(rec.head)].name;
  if (rec.on && rec.neck >= 0) rec.neck_name = def.joints[static_cast<size_t>(rec.neck)].name;
  if (say && d.enabled && d.head_link.empty() && rec.head_name != "head")
    info(rec.on ? "ragdoll '" + r.name + "': injury record's head guessed by name: link '" +
                      rec.head_name + "', neck '" +
                      (rec.neck_name.empty() ? "(none)" : rec.neck_name) +
                      "' (set the injury head_link and neck_joint to choose others)"
                : "ragdoll '" + r.name + "': no link named like a head ('head', 'skull'): no "
                  "injury record (set the injury head_link to name one)");
  r.injury = std::move(rec);
  return true;
}

void Scene::Impl::startInjury(RagdollInstance& r) {
  InjuryRecord& rec = r.injury;
  if (!rec.on || !world) return;
  world->trackBody(r.ragdoll.bodies[static_cast<size_t>(rec.head)], true);
  rec.restart(simTime());
}

InjuryReport Scene::Impl::endInjury(const RagdollInstance& r, const char* reason) const {
  InjuryReport out = r.injury.report;
  out.ragdoll = r.name;
  out.head_link = r.injury.head_name;
  out.neck_joint = r.injury.neck_name;
  out.reason = reason;
  out.end_time = simTime();
  const double t0 = out.start_time;
  out.hic15 = r.injury.hic15.hic();
  out.hic15_t1 = t0 + r.injury.hic15.t1();
  out.hic15_t2 = t0 + r.injury.hic15.t2();
  out.hic36 = r.injury.hic36.hic();
  out.hic36_t1 = t0 + r.injury.hic36.t1();
  out.hic36_t2 = t0 + r.injury.hic36.t2();
  return out;
}

void Scene::Impl::injuryRemoved(RagdollInstance& r) {
  if (r.injury.on && r.injury.falling) injury_reports.push_back(endInjury(r, "removed"));
}

// ------------------------------------------------------------------------------------------
// The step

namespace {

// The head's proper acceleration per substep into the record (t0: sim time at the step start).
void addSamples(InjuryRecord& rec, const SubstepVelocities& s, const Vec3& gravity, double t0) {
  InjuryReport& out = rec.report;
  Vec3 v = s.start_linear, w = s.start_angular;
  for (size_t k = 0; k < s.linear.size(); ++k) {
    const double g = ((s.linear[k] - v) / s.h - gravity).norm() / kStandardGravity;
    const double alpha = (s.angular[k] - w).norm() / s.h;
    v = s.linear[k];
    w = s.angular[k];
    rec.hic15.add(g, s.h);
    rec.hic36.add(g, s.h);
    if (g > out.peak_g) {
      out.peak_g = g;
      out.peak_time = t0 + static_cast<double>(k + 1) * s.h;
    }
    out.peak_angular_acceleration = std::max(out.peak_angular_acceleration, alpha);
  }
}

}  // namespace

void Scene::Impl::updateInjury() {
  // Reports of the step before go; those of removals since then stay for this step.
  injury_reports.erase(injury_reports.begin(),
                       injury_reports.begin() + static_cast<std::ptrdiff_t>(injury_reports_old));
  const double now = simTime(), t0 = now - dt;
  const Vec3 gravity = world->def().gravity;
  for (RagdollInstance& r : ragdolls) {
    InjuryRecord& rec = r.injury;
    if (!rec.on) continue;
    double fastest = 0.0;
    bool asleep = true;
    for (const BodyId b : r.ragdoll.bodies) {
      fastest = std::max(fastest, world->bodyState(b).linear_velocity.norm());
      asleep = asleep && !world->isAwake(b);
    }
    if (!rec.falling) {  // between falls nothing is measured: the step that starts one is
      if (!(fastest > rec.def.fall_speed)) continue;
      rec.restart(t0);
      rec.falling = true;
    }
    SubstepVelocities& s = samples_scratch;
    if (world->substepVelocities(r.ragdoll.bodies[static_cast<size_t>(rec.head)], &s))
      addSamples(rec, s, gravity, t0);
    if (rec.neck >= 0) {
      const JointId neck = r.ragdoll.joints[static_cast<size_t>(rec.neck)];
      if (world->isValid(neck)) {
        const JointWrench wrench = world->jointWrench(neck);
        rec.report.peak_neck_force = std::max(rec.report.peak_neck_force, wrench.force.norm());
        rec.report.peak_neck_torque = std::max(rec.report.peak_neck_torque, wrench.torque.norm());
      }
    }
    rec.report.end_time = now;
    rec.slow_for = fastest < rec.def.rest_speed ? rec.slow_for + dt : 0.0;
    if (asleep || rec.slow_for >= rec.def.rest_time) {
      injury_reports.push_back(endInjury(r, "rest"));
      rec.restart(now);
    }
  }
  injury_reports_old = injury_reports.size();
}

// ------------------------------------------------------------------------------------------
// The API

bool Scene::setInjury(int k, const InjuryDef& def, std::string* error) {
  Impl& s = *impl_;
  if (k < 0 || k >= static_cast<int>(s.ragdolls.size())) {
    *error = "no ragdoll with index " + std::to_string(k);
    return false;
  }
  RagdollInstance& r = s.ragdolls[static_cast<size_t>(k)];
  if (r.object) {
    *error = "'" + r.name + "' is an object: injury records are kept for ragdolls only";
    return false;
  }
  const InjuryRecord old = r.injury;
  if (!s.resolveInjury(r, def, /*say=*/true, error)) return false;
  if (s.world && old.on) {
    const BodyId head = r.ragdoll.bodies[static_cast<size_t>(old.head)];
    if (s.world->isValid(head)) s.world->trackBody(head, false);
  }
  s.startInjury(r);
  return true;
}

const std::string& Scene::headLink(int k) const {
  return impl_->ragdolls.at(static_cast<size_t>(k)).injury.head_name;
}
const std::string& Scene::neckJoint(int k) const {
  return impl_->ragdolls.at(static_cast<size_t>(k)).injury.neck_name;
}

InjuryReport Scene::injury(int k) const {
  return impl_->endInjury(impl_->ragdolls.at(static_cast<size_t>(k)), "");
}

InjuryReport Scene::resetInjury(int k) {
  RagdollInstance& r = impl_->ragdolls.at(static_cast<size_t>(k));
  InjuryReport out = impl_->endInjury(r, "reset");
  r.injury.restart(impl_->simTime());
  return out;
}

const std::vector<InjuryReport>& Scene::injuryReports() const { return impl_->injury_reports; }

}  // namespace ragdoll_sim
