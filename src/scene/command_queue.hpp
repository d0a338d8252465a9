// Commands held until the sim time at which they take effect (ROS-free, unit-tested). Every
// command of the topics passes through it: a zero stamp is due at once and is applied at the
// next loop iteration, so the subscriber callbacks stay short under load. It is bounded:
// beyond `capacity` waiting commands a push is refused and counted (dropped()).
//
// A command whose header stamp lies in the future is applied at the start of the first physics
// step that begins at or after that sim time, so that a recorded run replays step for step
// whatever the wall-clock timing (docs/interface.md, "Deterministic replay").
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <variant>
#include <vector>

#include "commands.hpp"
#include "joint_control.hpp"

namespace ragdoll_sim {
namespace scene {

struct QueuedCommand {
  int64_t due_ns = 0;   // sim time (ns since the start) at which it takes effect
  uint64_t seq = 0;     // arrival order (set by push), breaks ties between equal due times
  std::string ragdoll;  // "" = the first ragdoll
  RagdollId ragdoll_id; // resolved when it was submitted
  CommandCheck link;    // an impulse's or force's link and frame, resolved then too
  SceneCommandVariant command;
};

class CommandQueue {
 public:
  explicit CommandQueue(size_t capacity = 4096) : capacity_(capacity) {}
  // False (and nothing queued, dropped() counts it) when `capacity` commands are already waiting.
  bool push(QueuedCommand c);
  // Removes and returns the commands with due_ns <= now_ns, by due time, then arrival.
  std::vector<QueuedCommand> takeDue(int64_t now_ns);
  size_t size() const { return items_.size(); }
  size_t capacity() const { return capacity_; }
  size_t maxSize() const { return max_size_; }    // most commands ever waiting at once
  uint64_t dropped() const { return dropped_; }   // pushes refused because it was full
  void clear() { items_.clear(); }

 private:
  size_t capacity_;
  uint64_t next_seq_ = 0;
  size_t max_size_ = 0;
  uint64_t dropped_ = 0;
  std::vector<QueuedCommand> items_;  // sorted by (due_ns, seq)
};

// When a command stamped `stamp_ns` (absolute stamp, ns) takes effect, in sim ns since the
// start: stamps count from `origin_ns` (the stamp of sim time 0). A zero stamp means "now"
// (returns now_ns), and so does a stamp at or before now_ns.
int64_t commandDueNs(int64_t stamp_ns, int64_t origin_ns, int64_t now_ns);

}  // namespace scene
}  // namespace ragdoll_sim
