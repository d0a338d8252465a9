#include "ragdoll_sim/range_check.hpp"

#include <cmath>
#include <sstream>

namespace ragdoll_sim {

namespace {
std::string must(std::string_view name, std::string_view what, double v) {
  std::ostringstream s;
  s.precision(10);  // 1048576.5 must not read as 1.04858e+06
  s << name << " must be " << what << ", got " << v;
  return s.str();
}
}  // namespace

std::string positiveError(std::string_view name, double v) {
  return std::isfinite(v) && v > 0.0 ? "" : must(name, "a finite number > 0", v);
}

std::string nonNegativeError(std::string_view name, double v) {
  return std::isfinite(v) && v >= 0.0 ? "" : must(name, "a finite number >= 0", v);
}

std::string rangeError(std::string_view name, double v, double lo, double hi) {
  if (std::isfinite(v) && v >= lo && v <= hi) return "";
  std::ostringstream what;
  what.precision(10);
  what << "a finite number in [" << lo << ", " << hi << "]";
  return must(name, what.str(), v);
}

std::string intRangeError(std::string_view name, int v, int lo, int hi, const char* note) {
  if (v >= lo && v <= hi) return "";
  std::ostringstream s;
  s << name << " must be >= " << lo;
  if (hi != INT_MAX) s << " and <= " << hi;
  s << note << ", got " << v;
  return s.str();
}

std::string finiteError(std::string_view name, double v) {
  return std::isfinite(v) ? "" : must(name, "finite", v);
}

std::string positiveOrInfError(std::string_view name, double v) {
  return v > 0.0 ? "" : must(name, "> 0 (or inf)", v);
}

std::string nonNegativeOrInfError(std::string_view name, double v) {
  return v >= 0.0 ? "" : must(name, ">= 0 (or inf)", v);
}

std::string orderError(std::string_view lo_name, double lo, std::string_view hi_name,
                       double hi) {
  if (lo <= hi) return "";
  std::ostringstream s;
  s << lo_name << " must be <= " << hi_name << ", got " << lo << " > " << hi;
  return s.str();
}

namespace {
// kWorldRange as the messages print it ("1048576")
const std::string& worldRangeText() {
  static const std::string text = [] {
    std::ostringstream s;
    s.precision(10);
    s << kWorldRange;
    return s.str();
  }();
  return text;
}
}  // namespace

std::string lengthError(std::string_view name, double v, bool zero_allowed) {
  if (std::isfinite(v) && (v > 0.0 || (zero_allowed && v == 0.0)) && v <= kWorldRange) return "";
  return must(name,
              std::string("a finite number ") + (zero_allowed ? ">= 0" : "> 0") + " and <= " +
                  worldRangeText() + " (m, kWorldRange)",
              v);
}

std::string worldPointError(std::string_view name, const Vec3& p) {
  if (withinWorldRange(p)) return "";
  std::ostringstream s;  // the coordinates at 6 digits, as the URDF loader prints numbers
  s << name << " must be finite and within " << worldRangeText() << " m (kWorldRange), got "
    << p.x() << " " << p.y() << " " << p.z();
  return s.str();
}

std::string poseError(std::string_view name, const Transform& t) {
  if (withinWorldRange(t.p) && t.q.coeffs().allFinite() && t.q.norm() > 0.0) return "";
  return std::string(name) + " must be a finite pose within " + worldRangeText() +
         " m (kWorldRange)";
}

std::string firstError(std::initializer_list<std::string> errors) {
  for (const std::string& e : errors)
    if (!e.empty()) return e;
  return "";
}

}  // namespace ragdoll_sim
