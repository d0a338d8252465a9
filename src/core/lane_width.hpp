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

// Items [0, n) of the double-lane kernels in runs by lane width: four at a time in AVX lanes
// where the CPU has AVX2, then two in SSE2 lanes, the last one alone; run(width, first, count)
// for each run.
template <class Run>
void byLaneWidth(int n, Run&& run) {
  const int n4 = cpuHasAvx2() ? n / 4 * 4 : 0;
  const int n2 = n4 + (n - n4) / 2 * 2;
  run(4, 0, n4);
  run(2, n4, n2 - n4);
  run(1, n2, n - n2);
}

}  // namespace ragdoll_sim
