// The naming rule of everything a user names in the Scene: ragdolls now, objects later, and the
// TF prefixes of their frames. A name becomes a ROS topic namespace, a parameter namespace and a
// TF frame prefix, so it must be one ROS graph name token of bounded length. ROS-free: the Scene
// refuses a bad name when it is added, the node checks requests and parameters with the same
// functions before doing anything else.
#pragma once

#include <cstddef>
#include <string>

namespace ragdoll_sim {
namespace scene {

// Longest name, and longest TF prefix, in characters.
constexpr size_t kMaxNameLength = 128;
constexpr size_t kMaxTfPrefixLength = 128;

// The rules, as the refusal messages state them.
std::string nameRule();
std::string tfPrefixRule();

// A valid name: 1..kMaxNameLength characters, a letter first, then letters, digits and '_'.
// Returns "" or the problem followed by the rule; `what` names the thing ("ragdoll name",
// "object name").
std::string nameError(const std::string& name, const std::string& what);

// nameError for a ragdoll.
std::string ragdollNameError(const std::string& name);

// A valid TF prefix: names separated by single '/' (no leading or trailing '/'), at most
// kMaxTfPrefixLength characters in all. "" is not checked here: its meaning is the caller's.
std::string tfPrefixError(const std::string& prefix);

// A user's string for a message: quoted, and cut after `max_chars` characters with the full
// length stated, so a huge name never makes a huge message.
std::string quoted(const std::string& text, size_t max_chars = 48);

}  // namespace scene
}  // namespace ragdoll_sim
