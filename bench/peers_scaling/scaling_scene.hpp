// scaling_scene.hpp -- adds the scaling scene g to an unmodified peer bench (../shared/peers).
//
// The peers' CLI (ragdoll_common.hpp: rd::parse_args / rd::make_scene) only knows scenes a, b, c,
// so this header, included by scaling_<engine>.cpp right before the engine's own bench file,
// wraps those two functions:
//   scaling_<engine> g --ragdolls N [--steps S] [--urdf F] [--no-metrics] [--opt X]
// runs N standing ragdolls on the grid of ../scaling_grid.hpp (the same definition bench_ragdoll
// uses for its scene g); any other command line goes to the peer's own parse_args/make_scene
// unchanged. Everything else -- model, engine settings, timing, metrics, result line -- is the
// peer's own code: ragdoll_common.hpp is #pragma once, so the engine file's own include of it is
// skipped, and the two macros below only rename the two calls in the engine's main().
#pragma once

#include <string>
#include <vector>

#include "ragdoll_common.hpp"  // from the peers' folder (-I$PEERS_DIR)
#include "../scaling_grid.hpp"

namespace rd {
namespace scaling_driver {

inline int& ragdolls() {
  static int n = -1;  // -1: not scene g
  return n;
}

inline Args parse_args(int argc, char** argv) {
  std::vector<char*> rest{argv[0]};
  bool g = false;
  int n = -1;
  for (int i = 1; i < argc; ++i) {
    const std::string s = argv[i];
    if (s == "g") g = true;
    else if (s == "--ragdolls" && i + 1 < argc) n = std::atoi(argv[++i]);
    else rest.push_back(argv[i]);
  }
  if (n >= 0 && !g) {
    std::fprintf(stderr, "%s: --ragdolls is only for scene g\n", argv[0]);
    std::exit(2);
  }
  if (g) {
    if (n < 0) n = 1;
    if (n < 1) {
      std::fprintf(stderr, "%s: --ragdolls must be >= 1\n", argv[0]);
      std::exit(2);
    }
    ragdolls() = n;
  }
  rest.push_back(nullptr);
  return rd::parse_args(int(rest.size()) - 1, rest.data());
}

inline Scene make_scene(char id) {
  if (ragdolls() < 0) return rd::make_scene(id);
  Scene s;
  s.id = 'g';
  s.n = ragdolls();
  s.steps = scaling::kDefaultSteps;
  s.desc = "scaling: N ragdolls standing on a grid, 1.5 m pitch, pelvis at 1.5 m";
  for (const auto& p : scaling::gridRoots(s.n)) {
    s.xyz.push_back({p[0], p[1], p[2]});
    s.rpy.push_back({0, 0, 0});
  }
  for (int k = 0; k < s.n; ++k) s.root.push_back({s.xyz[k], rpy(s.rpy[k].x, s.rpy[k].y, s.rpy[k].z)});
  return s;
}

}  // namespace scaling_driver
}  // namespace rd

// The engine files call both unqualified, under `using namespace rd;`.
#define parse_args scaling_driver::parse_args
#define make_scene scaling_driver::make_scene
