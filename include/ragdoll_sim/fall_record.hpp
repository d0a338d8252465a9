// FallRecorder: what one fall of one ragdoll of a Scene did, sampled after every Scene::step:
// per-link peak contact force, the head's peak g and HIC15 (the Scene's injury record), the
// joints that broke, when the ragdoll came to rest, whether a body went non-finite, and the
// pose it rests in. The batch runner (ragdoll_batch, docs/batch.md) makes one row of it per run;
// run() steps and samples in C++ so that nothing per step crosses into Python.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ragdoll_sim/math.hpp"
#include "ragdoll_sim/scene.hpp"
#include "ragdoll_sim/scene_reports.hpp"

namespace ragdoll_sim {

// How a fall is judged.
struct FallRecordDef {
  // At rest: every body of the ragdoll asleep, or slower than both speeds (centre of mass,
  // and angular). The time to rest is the first sample from which it stays at rest to the end.
  double rest_speed = 0.05;          // m/s
  double rest_angular_speed = 0.5;   // rad/s
  // A rest shorter than this at the end is no rest yet (a body at the top of a bounce).
  double min_rest = 0.2;             // s
  // The link whose axes give the rest pose's class: "" = "torso" when the ragdoll has one,
  // else its root link. Its `up` axis points from the hips to the head, `forward` out of the
  // chest (link axes; the bundled ragdoll's +z and +x).
  std::string torso_link;
  Vec3 up = Vec3::UnitZ();
  Vec3 forward = Vec3::UnitX();
  // Upright: the up axis within this angle of world +z. Lying (supine, prone, side): the up
  // axis within this angle of the horizontal; then forward within `lying_angle` of world +z is
  // supine, of -z prone, else side.
  double upright_angle = 0.5235987755982988;  // rad, 30 deg
  double lying_angle = 0.7853981633974483;    // rad, 45 deg
};

// Empty when the def is usable, else the first field out of range, named ("rest_speed must be a
// finite number >= 0, got -1").
std::string fallRecordDefError(const FallRecordDef& def);

enum class RestClass { Upright, Supine, Prone, Side, Other };
const char* restClassName(RestClass c);  // "upright", "supine", "prone", "side", "other"

// One fall, from the recorder's start to its last sample.
struct FallRecord {
  std::string ragdoll;
  std::vector<std::string> links;         // RagdollDef::links names
  std::vector<double> peak_contact_force; // N per link: the largest |sum of its contact forces|
  double head_peak_g = 0.0;               // g, the largest of the injury records' peaks
  double hic15 = 0.0;                     // the largest of the injury records' HIC15
  std::string head_link;                  // "" when the ragdoll has no injury record
  std::vector<std::string> broken_joints; // RagdollDef joint names, in the order they broke
  // s from the start until the ragdoll is at rest for good; NaN when it is not at rest (for at
  // least min_rest) at the end.
  double time_to_rest = 0.0;
  // A body fault in the scene (the World reset a non-finite or out-of-range body) or a
  // non-finite state of one of the ragdoll's bodies at some sample.
  bool nan = false;
  int64_t body_faults = 0;                // the scene's body faults since the start
  // The root link at the last sample: position (m) and roll, pitch, yaw (rad; URDF's
  // R = Rz(yaw) Ry(pitch) Rx(roll)); the class from the torso link's axes.
  Vec3 root_position = Vec3::Zero();
  double roll = 0.0, pitch = 0.0, yaw = 0.0;
  RestClass rest = RestClass::Other;
  double duration = 0.0;                  // s sampled
  int64_t samples = 0;
};

// Roll, pitch, yaw of q as URDF writes them (quatFromRpy's inverse; pitch in [-pi/2, pi/2]).
Vec3 rpyFromQuat(const Quat& q);
// The class of a torso at orientation q (world from link) by def's axes and angles.
RestClass classifyRest(const Quat& q, const FallRecordDef& def);

class FallRecorder {
 public:
  // Bound to ragdoll `ragdoll` ("" = the first) of a started scene; starts at the scene's
  // current time. Throws std::invalid_argument naming an unknown ragdoll or torso link, or a
  // def field out of range.
  FallRecorder(const Scene& scene, const std::string& ragdoll, FallRecordDef def = {});

  // After each Scene::step.
  void sample(const Scene& scene);
  // `steps` Scene::step calls, each sampled.
  void run(Scene& scene, int64_t steps);
  // The fall so far (the head's metrics include the injury record still under way).
  FallRecord record(const Scene& scene) const;

  const FallRecordDef& def() const { return def_; }
  int ragdollIndex(const Scene& scene) const;  // -1 once the ragdoll is removed

 private:
  FallRecordDef def_;
  RagdollId id_;
  std::string name_;
  int torso_ = 0;
  double start_time_ = 0.0;
  int64_t start_faults_ = 0;
  FallRecord rec_;
  double rest_since_ = -1.0;  // sim time from which it has been at rest; < 0: moving
  bool head_on_ = false;
  std::vector<LinkLoad> link_scratch_;
};

}  // namespace ragdoll_sim
