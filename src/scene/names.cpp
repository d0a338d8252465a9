#include "names.hpp"

#include <cctype>
#include <cstdio>

namespace ragdoll_sim {
namespace scene {

std::string nameRule() {
  return "a name is 1 to " + std::to_string(kMaxNameLength) +
         " characters: a letter first, then letters, digits or '_'";
}

std::string tfPrefixRule() {
  return "a tf_prefix is names (a letter first, then letters, digits or '_') joined by single "
         "'/', no leading or trailing '/', at most " + std::to_string(kMaxTfPrefixLength) +
         " characters";
}

namespace {

bool isLetter(char c) { return std::isalpha(static_cast<unsigned char>(c)) != 0; }
bool isNameChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_'; }

// The problem with one name token (no rule appended), or "".
std::string tokenProblem(const std::string& s, size_t begin, size_t end) {
  if (begin == end) return "is empty";
  if (std::isdigit(static_cast<unsigned char>(s[begin]))) return "starts with a digit";
  if (!isLetter(s[begin])) return "does not start with a letter";
  for (size_t i = begin; i < end; ++i) {
    if (isNameChar(s[i])) continue;
    const unsigned char c = static_cast<unsigned char>(s[i]);
    if (std::isprint(c)) return "holds the character " + quoted(std::string(1, s[i]));
    char hex[8];
    std::snprintf(hex, sizeof hex, "0x%02x", c);
    return std::string("holds the byte ") + hex;  // not printable, or part of a UTF-8 letter
  }
  return "";
}

}  // namespace

std::string quoted(const std::string& text, size_t max_chars) {
  if (text.size() <= max_chars) return "'" + text + "'";
  return "'" + text.substr(0, max_chars) + "...' (" + std::to_string(text.size()) +
         " characters)";
}

std::string nameError(const std::string& name, const std::string& what) {
  std::string problem;
  if (name.size() > kMaxNameLength)
    problem = "is too long";
  else
    problem = tokenProblem(name, 0, name.size());
  if (problem.empty()) return "";
  return what + " " + (name.empty() ? std::string() : quoted(name) + " ") + problem + " (" +
         nameRule() + ")";
}

std::string ragdollNameError(const std::string& name) { return nameError(name, "ragdoll name"); }

std::string tfPrefixError(const std::string& prefix) {
  if (prefix.empty()) return "";
  std::string problem;
  if (prefix.size() > kMaxTfPrefixLength) {
    problem = "is too long";
  } else {
    for (size_t begin = 0; problem.empty() && begin <= prefix.size();) {
      size_t end = prefix.find('/', begin);
      if (end == std::string::npos) end = prefix.size();
      const std::string p = tokenProblem(prefix, begin, end);
      if (!p.empty())
        problem = begin == end ? std::string("has an empty name (a leading, trailing or double '/')")
                               : "has a name that " + p;
      begin = end + 1;
    }
  }
  if (problem.empty()) return "";
  return "tf_prefix " + quoted(prefix) + " " + problem + " (" + tfPrefixRule() + ")";
}

}  // namespace scene
}  // namespace ragdoll_sim
