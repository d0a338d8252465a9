// scaling_grid.hpp -- the one definition of the scaling scene g, shared by bench_ragdoll and the
// peer scaling drivers (bench/peers_scaling), so that every engine gets the same layout.
//   g: N ragdolls standing (same pose as scene b: identity orientation, pelvis at 1.5 m) on a
//      square-ish grid with 1.5 m pitch: ceil(sqrt(N)) columns, filled row by row, centred on
//      the origin. 3 000 steps by default. N = 1, 4, 16, 64, 256 are full squares.
#pragma once

#include <array>
#include <cmath>
#include <vector>

namespace scaling {

constexpr int kDefaultSteps = 3000;
constexpr double kPitch = 1.5;
constexpr double kPelvisZ = 1.5;

// Pelvis (root) positions of the n ragdolls; the orientation is the identity for all of them.
inline std::vector<std::array<double, 3>> gridRoots(int n) {
  std::vector<std::array<double, 3>> xyz;
  if (n <= 0) return xyz;
  const int cols = int(std::ceil(std::sqrt(double(n)) - 1e-9));
  const int rows = (n + cols - 1) / cols;
  for (int k = 0; k < n; ++k) {
    const int i = k % cols, j = k / cols;
    xyz.push_back({(i - 0.5 * (cols - 1)) * kPitch, (j - 0.5 * (rows - 1)) * kPitch, kPelvisZ});
  }
  return xyz;
}

}  // namespace scaling
