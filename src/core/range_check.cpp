#include "ragdoll_sim/range_check.hpp"

#include <cmath>
#include <sstream>

namespace ragdoll_sim {

namespace {
std::string must(const std::string& name, const std::string& what, double v) {
  std::ostringstream s;
  s << name << " must be " << what << ", got " << v;
  return s.str();
}
}  // namespace

std::string positiveError(const std::string& name, double v) {
  return std::isfinite(v) && v > 0.0 ? "" : must(name, "a finite number > 0", v);
}

std::string nonNegativeError(const std::string& name, double v) {
  return std::isfinite(v) && v >= 0.0 ? "" : must(name, "a finite number >= 0", v);
}

std::string rangeError(const std::string& name, double v, double lo, double hi) {
  if (std::isfinite(v) && v >= lo && v <= hi) return "";
  std::ostringstream what;
  what << "a finite number in [" << lo << ", " << hi << "]";
  return must(name, what.str(), v);
}

std::string intRangeError(const std::string& name, int v, int lo, int hi, const char* note) {
  if (v >= lo && v <= hi) return "";
  std::ostringstream s;
  s << name << " must be >= " << lo;
  if (hi != INT_MAX) s << " and <= " << hi;
  s << note << ", got " << v;
  return s.str();
}

std::string finiteError(const std::string& name, double v) {
  return std::isfinite(v) ? "" : must(name, "finite", v);
}

std::string positiveOrInfError(const std::string& name, double v) {
  return v > 0.0 ? "" : must(name, "> 0 (or inf)", v);
}

std::string nonNegativeOrInfError(const std::string& name, double v) {
  return v >= 0.0 ? "" : must(name, ">= 0 (or inf)", v);
}

std::string orderError(const std::string& lo_name, double lo, const std::string& hi_name,
                       double hi) {
  if (lo <= hi) return "";
  std::ostringstream s;
  s << lo_name << " must be <= " << hi_name << ", got " << lo << " > " << hi;
  return s.str();
}

std::string firstError(std::initializer_list<std::string> errors) {
  for (const std::string& e : errors)
    if (!e.empty()) return e;
  return "";
}

}  // namespace ragdoll_sim
