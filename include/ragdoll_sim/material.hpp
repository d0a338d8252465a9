// Material pair table: coefficients measured for pairs of surfaces (a textbook friction table
// lists pairs, not single materials), with a combine rule for the pairs not listed.
#pragma once

#include <string>
#include <vector>

#include "ragdoll_sim/shape.hpp"

namespace ragdoll_sim {

enum class CombineRule { GeometricMean, Average, Min, Max };

// Parses "geometric_mean" | "average" | "min" | "max"; false if unknown.
bool parseCombineRule(const std::string& text, CombineRule* rule);
double combine(CombineRule rule, double a, double b);

// "" when every coefficient is finite and >= 0 and restitution <= 1, else the first that is not,
// named as in Material ("restitution must be a finite number in [0, 1], got 1.5"). A
// contact_hertz above a quarter of the substep rate is accepted and capped by the solver at
// each step, as SolverSettings::contact_hertz is.
std::string materialError(const Material& m);

class MaterialTable {
 public:
  CombineRule friction_rule = CombineRule::GeometricMean;
  CombineRule restitution_rule = CombineRule::Max;

  // Registers a named material and returns its id (>= 1); an existing name is updated.
  int add(const std::string& name, const Material& material);
  int find(const std::string& name) const;  // -1 if unknown
  const Material& material(int id) const { return materials_.at(id); }
  const std::string& name(int id) const { return names_.at(id); }
  int size() const { return int(materials_.size()); }

  // Coefficients for the pair (a, b), in either order. `given`: how many of the leading
  // coefficients the pair sets (2: the frictions, 3: and restitution, 4: and rolling
  // resistance, 5 or 6: and the compliance, contact_hertz with contact_damping_ratio); the rest
  // come from the two surfaces by the combine rules, as for a pair not listed (a friction
  // table measures friction, not restitution), and the compliance from the softer surface
  // (Material::contact_hertz).
  static constexpr int kAllCoefficients = 6;
  void setPair(int a, int b, const Material& pair, int given = kAllCoefficients);
  // How many coefficients the pair (a, b) sets (setPair's `given`); 0 when it is not listed.
  int pairGiven(int a, int b) const;
  // The pair's listed coefficients, else the combination of the two surfaces' own.
  Material resolve(const Material& a, const Material& b) const;
  // "" when every material and pair entry passes materialError, else which does not
  // ("materials 'ice': kinetic_friction must be ...", "materials pair 'ice'/'rubber': ...").
  std::string error() const;

 private:
  std::vector<std::string> names_{""};
  std::vector<Material> materials_{Material()};
  std::vector<Material> pairs_{Material()};  // n x n, valid where given_ > 0
  std::vector<char> given_{0};               // setPair's `given`; 0: not listed
  int n_ = 1;
  void grow(int n);
};

}  // namespace ragdoll_sim
