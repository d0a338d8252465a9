// The lane width of the wide solver, chosen at run time: 8 (AVX2) where the CPU has it, else 4
// (SSE2, the x86-64 baseline); the package itself is built for the baseline.
#pragma once

namespace ragdoll_sim {

// True when the 8-lane kernels were built (an x86-64 compiler that takes -mavx2) and this CPU
// runs AVX2.
bool cpuHasAvx2();
// True when the paired 8-lane kernels were built (a compiler that takes -mavx512f) and this CPU
// runs AVX-512F: the 8-lane width then solves two blocks of a colour at once, with the same bits.
bool cpuHasAvx512();

// The width to use: `requested` (4 or 8, a WorldDef-style switch) when not 0, else the
// environment variable RAGDOLL_SIM_LANES (4 or 8) when set and not empty, else the widest the
// CPU runs. 8 falls back to 4 where AVX2 is missing, so a forced width is always safe to run.
// Throws std::invalid_argument naming the value for anything but 0, 4, 8 (or 4, 8 in the
// variable).
int chooseLaneWidth(int requested);
// The same with the variable's value (nullptr: unset) and the CPU's answer given, for tests.
int chooseLaneWidth(int requested, const char* env, bool has_avx2);
// Whether nothing forces a width: `requested` 0 and the variable unset or empty. Only then does
// a world too small to fill the lanes solve its rows in double (World::kLanesMinBodies).
bool laneWidthAutomatic(int requested);
bool laneWidthAutomatic(int requested, const char* env);

// Items [0, n) of the double-lane kernels, in runs of the widest lanes the CPU runs: four at a
// time in AVX lanes where it has AVX2, else two in SSE2 lanes; run(width, items, count) with
// count a multiple of width. The last few go as one more run whose spare lanes repeat the last
// item: each lane of those kernels gathers its inputs before any lane writes and does the
// operations of its item alone, so a repeated item's results are written twice, the same bits.
template <class T, class Run>
void byLaneWidth(const T* items, int n, Run&& run) {
  const int width = cpuHasAvx2() ? 4 : 2;
  const int full = n / width * width;
  if (full > 0) run(width, items, full);
  if (full == n) return;
  T tail[4];
  for (int l = 0; l < width; ++l) tail[l] = items[full + l < n ? full + l : n - 1];
  run(width, static_cast<const T*>(tail), width);
}

}  // namespace ragdoll_sim
