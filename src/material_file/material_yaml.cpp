// See material_yaml.hpp. Every check names the entry as the file spells it (surfaces/NAME,
// pairs[i]) and, for text read from a file, its line.
#include "material_yaml.hpp"

#include <algorithm>
#include <map>
#include <set>

namespace ragdoll_sim {
namespace material_yaml {
namespace {

std::string quote(const std::string& s) { return "'" + s + "'"; }

// " (line N)" for a node read from text; nodes built in memory (the node's parameters) have none.
std::string lineOf(const YAML::Node& n) {
  const YAML::Mark m = n.Mark();
  return m.is_null() || m.line < 0 ? "" : " (line " + std::to_string(m.line + 1) + ")";
}

// A key left out, or written with no value.
bool absent(const YAML::Node& n) { return !n.IsDefined() || n.IsNull(); }

bool text(const YAML::Node& n, std::string* out) {
  if (!n.IsScalar()) return false;
  *out = n.Scalar();
  return !out->empty();
}

bool number(const YAML::Node& n, double* out) {
  if (!n.IsScalar()) return false;
  try {
    *out = n.as<double>();
    return true;
  } catch (const YAML::Exception&) {
    return false;
  }
}

// The coefficients of an entry, in the order they are listed.
constexpr const char* kFields =
    "static_friction, kinetic_friction, restitution(, rolling_resistance(, contact_hertz(, "
    "contact_damping_ratio)))";
constexpr const char* kRanges = "numbers >= 0, restitution <= 1";

// Coefficients list[first ...] (at least `least`, at most kAllCoefficients of them) into *m;
// *given: how many.
bool coefficients(const YAML::Node& list, size_t first, int least, Material* m, int* given) {
  constexpr int kMost = MaterialTable::kAllCoefficients;
  if (!list.IsSequence() || list.size() < first + least || list.size() > first + kMost)
    return false;
  double* fields[kMost] = {&m->static_friction,    &m->kinetic_friction,
                           &m->restitution,        &m->rolling_resistance,
                           &m->contact_hertz,      &m->contact_damping_ratio};
  *given = int(list.size() - first);
  for (int k = 0; k < *given; ++k)
    if (!number(list[first + k], fields[k])) return false;
  return materialError(*m).empty();
}

// ": <the coefficient out of range>" when the numbers read break materialError's ranges.
std::string whichRange(const Material& m) {
  const std::string e = materialError(m);
  return e.empty() ? "" : ": " + e;
}

// A pair's side: one surface name or a non-empty list of them.
bool sideNames(const YAML::Node& n, std::vector<std::string>* out) {
  std::string name;
  if (text(n, &name)) {
    out->push_back(name);
    return true;
  }
  if (!n.IsSequence() || n.size() == 0) return false;
  for (const YAML::Node& item : n) {
    if (!text(item, &name)) return false;
    out->push_back(name);
  }
  return true;
}

bool readCombine(const YAML::Node& c, const std::string& where, MaterialTable* t, std::string* error) {
  if (absent(c)) return true;
  if (!c.IsMap()) {
    *error = where + lineOf(c) + " must be a dictionary {friction, restitution}";
    return false;
  }
  for (const auto& kv : c) {
    const std::string key = kv.first.Scalar();
    CombineRule* rule = key == "friction" ? &t->friction_rule
                        : key == "restitution" ? &t->restitution_rule : nullptr;
    if (!rule) {
      *error = where + lineOf(kv.first) + " has an unknown key " + quote(key) +
               " (known: friction, restitution)";
      return false;
    }
    std::string value;
    if (!text(kv.second, &value) || !parseCombineRule(value, rule)) {
      *error = where + "/" + key + lineOf(kv.second) + " must be geometric_mean, average, min or max";
      return false;
    }
  }
  return true;
}

bool readSurfaces(const YAML::Node& s, const std::string& where, MaterialTable* t, std::string* error) {
  if (absent(s)) return true;
  if (!s.IsMap()) {
    *error = where + lineOf(s) + " must be a dictionary: name -> [" + kFields + "]";
    return false;
  }
  std::set<std::string> seen;
  for (const auto& kv : s) {
    std::string name;
    if (!text(kv.first, &name)) {
      *error = where + lineOf(kv.first) + ": a surface name must be a non-empty string";
      return false;
    }
    if (!seen.insert(name).second) {
      *error = where + "/" + name + lineOf(kv.first) + " is listed twice";
      return false;
    }
    Material m;
    int given = 0;
    if (!coefficients(kv.second, 0, 3, &m, &given)) {
      *error = where + "/" + name + lineOf(kv.second) + " must be [" + kFields + "] (" +
               kRanges + ")" + whichRange(m);
      return false;
    }
    t->add(name, m);
  }
  return true;
}

bool readPairs(const YAML::Node& p, const std::string& where, const std::string& surfaces,
               MaterialTable* t, std::string* error) {
  if (absent(p)) return true;
  if (!p.IsSequence()) {
    *error = where + lineOf(p) + " must be a list of [a, b, " + kFields + "]";
    return false;
  }
  std::map<std::pair<int, int>, std::string> listed;  // pair -> the entry that listed it
  for (size_t i = 0; i < p.size(); ++i) {
    const YAML::Node& e = p[i];
    const std::string item = where + "[" + std::to_string(i) + "]" + lineOf(e);
    std::vector<std::string> a, b;
    Material m;
    int given = 0;
    if (!e.IsSequence() || e.size() < 2 || !sideNames(e[0], &a) || !sideNames(e[1], &b) ||
        !coefficients(e, 2, 2, &m, &given)) {
      *error = item + " must be [a, b, " + kFields +
               "]: a and b surface names (or lists of them), " + kRanges + whichRange(m);
      return false;
    }
    for (const std::string& na : a)
      for (const std::string& nb : b) {
        const int ia = t->find(na), ib = t->find(nb);
        if (ia < 0 || ib < 0) {
          *error = item + " names " + quote(ia < 0 ? na : nb) + ", not in " + surfaces;
          return false;
        }
        const auto key = std::make_pair(std::min(ia, ib), std::max(ia, ib));
        const auto [it, fresh] = listed.emplace(key, item);
        if (!fresh) {
          *error = item + " lists the pair " + quote(na) + "/" + quote(nb) + " again (first in " +
                   it->second + ")";
          return false;
        }
        t->setPair(ia, ib, m, given);
      }
  }
  return true;
}

}  // namespace

bool readTable(const YAML::Node& materials, const std::string& where, MaterialTable* table,
               std::string* error) {
  if (absent(materials)) return true;
  if (!materials.IsMap()) {
    *error = where + lineOf(materials) + " must be a dictionary {combine, surfaces, pairs}";
    return false;
  }
  for (const auto& kv : materials) {
    const std::string key = kv.first.Scalar();
    if (key != "combine" && key != "surfaces" && key != "pairs") {
      *error = where + lineOf(kv.first) + " has an unknown key " + quote(key) +
               " (known: combine, surfaces, pairs)";
      return false;
    }
  }
  // Surfaces first: the pairs name them, in whatever order the keys come.
  return readCombine(materials["combine"], where + "/combine", table, error) &&
         readSurfaces(materials["surfaces"], where + "/surfaces", table, error) &&
         readPairs(materials["pairs"], where + "/pairs", where + "/surfaces", table, error);
}

bool readLinkMaterials(const YAML::Node& map, const std::string& where, const MaterialTable& table,
                       std::vector<std::pair<std::string, std::string>>* out, std::string* error) {
  if (absent(map)) return true;
  if (!map.IsMap()) {
    *error = where + lineOf(map) + " must be a dictionary: link name (or \"*\") -> surface name";
    return false;
  }
  std::vector<std::pair<std::string, std::string>> entries;
  for (const auto& kv : map) {
    std::string link, surface;
    if (!text(kv.first, &link)) {
      *error = where + lineOf(kv.first) + ": a link name must be a non-empty string";
      return false;
    }
    const std::string item = where + "/" + link + lineOf(kv.second);
    if (!text(kv.second, &surface)) {
      *error = item + " must be a surface name";
      return false;
    }
    if (table.find(surface) < 0) {
      *error = item + " names " + quote(surface) + ", not in the materials' surfaces";
      return false;
    }
    for (const auto& [l, s] : entries)
      if (l == link) {
        *error = item + " is listed twice";
        return false;
      }
    entries.emplace_back(link, surface);
  }
  // One order whatever the source's (a file keeps its own, the parameter server sorts).
  std::sort(entries.begin(), entries.end(), [](const auto& x, const auto& y) {
    return (x.first == "*") != (y.first == "*") ? y.first == "*" : x.first < y.first;
  });
  *out = std::move(entries);
  return true;
}

}  // namespace material_yaml
}  // namespace ragdoll_sim
