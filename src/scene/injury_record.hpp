// One ragdoll's injury record (injury.hpp): its head and neck, the metrics of the fall so far,
// and whether a fall is under way. scene_injury.cpp keeps it; RagdollInstance holds it.
#pragma once

#include <string>

#include "ragdoll_sim/injury.hpp"

namespace ragdoll_sim {
namespace scene {

struct InjuryRecord {
  bool on = false;    // enabled and a head was found: the head is tracked
  InjuryDef def;      // as asked (SceneDef::injury or setInjury)
  int head = -1;      // RagdollDef::links index
  int neck = -1;      // RagdollDef::joints index; -1: none (a root head)
  std::string head_name, neck_name;
  InjuryReport report;  // peaks and times so far (names and reason filled when reported)
  HicMeter hic15{0.015}, hic36{0.036};
  // A link went faster than fall_speed: the record runs (between falls it stays empty).
  bool falling = false;
  double slow_for = 0.0;  // s every link has been below rest_speed while falling

  // An empty record from sim time t (peaks cleared, no fall under way).
  void restart(double t) {
    report = InjuryReport();
    report.start_time = report.end_time = t;
    hic15.reset();
    hic36.reset();
    falling = false;
    slow_for = 0.0;
  }
};

}  // namespace scene
}  // namespace ragdoll_sim
