#include "ragdoll_sim/material.hpp"

#include <algorithm>
#include <cmath>

#include "ragdoll_sim/range_check.hpp"

namespace ragdoll_sim {

bool parseCombineRule(const std::string& text, CombineRule* rule) {
  if (text == "geometric_mean") *rule = CombineRule::GeometricMean;
  else if (text == "average") *rule = CombineRule::Average;
  else if (text == "min") *rule = CombineRule::Min;
  else if (text == "max") *rule = CombineRule::Max;
  else return false;
  return true;
}

double combine(CombineRule rule, double a, double b) {
  switch (rule) {
    case CombineRule::GeometricMean: return std::sqrt(a * b);
    case CombineRule::Average: return 0.5 * (a + b);
    case CombineRule::Min: return std::min(a, b);
    case CombineRule::Max: return std::max(a, b);
  }
  return a;
}

std::string materialError(const Material& m) {
  return firstError({nonNegativeError("static_friction", m.static_friction),
                     nonNegativeError("kinetic_friction", m.kinetic_friction),
                     rangeError("restitution", m.restitution, 0.0, 1.0),
                     nonNegativeError("rolling_resistance", m.rolling_resistance),
                     nonNegativeError("contact_hertz", m.contact_hertz),
                     nonNegativeError("contact_damping_ratio", m.contact_damping_ratio)});
}

std::string MaterialTable::error() const {
  for (int i = 0; i < n_; ++i) {
    std::string e = materialError(materials_[i]);
    if (!e.empty()) return "materials '" + names_[i] + "': " + e;
    for (int j = i; j < n_; ++j) {
      if (!given_[size_t(i) * n_ + j]) continue;
      e = materialError(pairs_[size_t(i) * n_ + j]);
      if (!e.empty()) return "materials pair '" + names_[i] + "'/'" + names_[j] + "': " + e;
    }
  }
  return "";
}

void MaterialTable::grow(int n) {
  if (n <= n_) return;
  std::vector<Material> pairs(size_t(n) * n);
  std::vector<char> has(size_t(n) * n, 0);
  for (int i = 0; i < n_; ++i)
    for (int j = 0; j < n_; ++j) {
      pairs[size_t(i) * n + j] = pairs_[size_t(i) * n_ + j];
      has[size_t(i) * n + j] = given_[size_t(i) * n_ + j];
    }
  pairs_.swap(pairs);
  given_.swap(has);
  n_ = n;
}

int MaterialTable::add(const std::string& name, const Material& material) {
  int id = find(name);
  if (id < 0) {
    id = int(materials_.size());
    names_.push_back(name);
    materials_.push_back(material);
    grow(id + 1);
  }
  materials_[id] = material;
  materials_[id].id = id;
  return id;
}

int MaterialTable::find(const std::string& name) const {
  for (size_t i = 1; i < names_.size(); ++i)
    if (names_[i] == name) return int(i);
  return -1;
}

void MaterialTable::setPair(int a, int b, const Material& pair, int given) {
  grow(std::max(a, b) + 1);
  for (const auto& [i, j] : {std::make_pair(a, b), std::make_pair(b, a)}) {
    pairs_[size_t(i) * n_ + j] = pair;
    given_[size_t(i) * n_ + j] = char(std::clamp(given, 2, kAllCoefficients));
  }
}

int MaterialTable::pairGiven(int a, int b) const {
  if (a <= 0 || b <= 0 || a >= n_ || b >= n_) return 0;
  return given_[size_t(a) * n_ + b];
}

namespace {
// The softer surface's compliance: the lower contact_hertz > 0 (equal ones: the higher damping
// ratio, so that the order of the two does not matter); none when both are rigid.
const Material* softerSurface(const Material& a, const Material& b) {
  if (!(a.contact_hertz > 0.0)) return b.contact_hertz > 0.0 ? &b : nullptr;
  if (!(b.contact_hertz > 0.0) || a.contact_hertz < b.contact_hertz) return &a;
  if (b.contact_hertz < a.contact_hertz) return &b;
  return a.contact_damping_ratio >= b.contact_damping_ratio ? &a : &b;
}
}  // namespace

Material MaterialTable::resolve(const Material& a, const Material& b) const {
  const int given = pairGiven(a.id, b.id);
  if (given == kAllCoefficients) return pairs_[size_t(a.id) * n_ + b.id];
  Material m;
  m.static_friction = combine(friction_rule, a.static_friction, b.static_friction);
  m.kinetic_friction = combine(friction_rule, a.kinetic_friction, b.kinetic_friction);
  m.restitution = combine(restitution_rule, a.restitution, b.restitution);
  m.rolling_resistance = std::max(a.rolling_resistance, b.rolling_resistance);
  if (const Material* soft = softerSurface(a, b)) {
    m.contact_hertz = soft->contact_hertz;
    m.contact_damping_ratio = soft->contact_damping_ratio;
  }
  if (given > 0) {
    const Material& p = pairs_[size_t(a.id) * n_ + b.id];
    m.static_friction = p.static_friction;
    m.kinetic_friction = p.kinetic_friction;
    if (given >= 3) m.restitution = p.restitution;
    if (given >= 4) m.rolling_resistance = p.rolling_resistance;
    if (given >= 5) {
      m.contact_hertz = p.contact_hertz;
      m.contact_damping_ratio = p.contact_damping_ratio;
    }
  }
  return m;
}

}  // namespace ragdoll_sim
