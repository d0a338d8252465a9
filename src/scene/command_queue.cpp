#include "command_queue.hpp"

#include <algorithm>

namespace ragdoll_sim {
namespace scene {

bool CommandQueue::push(QueuedCommand c) {
  if (items_.size() >= capacity_) {
    ++dropped_;
    return false;
  }
  c.seq = next_seq_++;
  // After every item due at the same time or earlier: ties keep their arrival order (a
  // command due now lands at the end unless future ones wait, in O(1)).
  auto it = std::upper_bound(items_.begin(), items_.end(), c.due_ns,
                             [](int64_t due, const QueuedCommand& q) { return due < q.due_ns; });
  items_.insert(it, std::move(c));
  max_size_ = std::max(max_size_, items_.size());
  return true;
}

std::vector<QueuedCommand> CommandQueue::takeDue(int64_t now_ns) {
  auto end = std::upper_bound(items_.begin(), items_.end(), now_ns,
                              [](int64_t now, const QueuedCommand& q) { return now < q.due_ns; });
  std::vector<QueuedCommand> out(std::make_move_iterator(items_.begin()),
                                 std::make_move_iterator(end));
  items_.erase(items_.begin(), end);
  return out;
}

int64_t commandDueNs(int64_t stamp_ns, int64_t origin_ns, int64_t now_ns) {
  if (stamp_ns == 0) return now_ns;
  return std::max(now_ns, stamp_ns - origin_ns);
}

}  // namespace scene
}  // namespace ragdoll_sim
