#!/usr/bin/env bash
# Flop count of our solver per body-step, for bench/RESULTS.md (make bench calls it).
# There are no hardware counters in this VM (perf: "not supported"), so we count in software:
# bench_ragdoll is built with x87 arithmetic and Eigen's vectorisation off, so every double
# operation is one F64 ALU op in valgrind's IR, and lackey (--detailed-counts) counts them.
# Two runs of scene a (N0 and N1 steps) are subtracted, which leaves the steps N0+1..N1 (the
# ragdoll on the ground with its contacts) without the start-up. The count includes the few
# conversions and negations, so it is an upper bound on the flops.
# Prints "# meta" lines for results_raw.txt: flops_per_body_step, the window, peak_gflops
# (cores x MHz x DP flops/cycle from the CPU flags: 32 with AVX-512, 16 with AVX2+FMA, 4 else).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
N0="${FLOPS_N0:-1000}"
N1="${FLOPS_N1:-1200}"
URDF="${URDF:-$ROOT/../shared/peers/ragdoll15.urdf}"
BUILD="$WS/flops"
build_bench_ragdoll "$BUILD" \
  "-DCMAKE_CXX_FLAGS=-O2 -mfpmath=387 -fno-tree-vectorize -fno-tree-slp-vectorize -DEIGEN_DONT_VECTORIZE"
f64() {
  valgrind --tool=lackey --detailed-counts=yes "$BUILD/bench_ragdoll" a --steps "$1" --no-metrics \
    --urdf "$URDF" 2>&1 >/dev/null | awk '$2 == "F64" {gsub(",", "", $5); print $5}'
}
a0="$(f64 "$N0")"
a1="$(f64 "$N1")"
bodies=15
per=$(( (a1 - a0) / ((N1 - N0) * bodies) ))
cores="$(getconf _NPROCESSORS_ONLN)"  # not nproc: it honours OMP_NUM_THREADS (bench.sh sets 1)
mhz="$(awk -F: '/cpu MHz/ {print $2; exit}' /proc/cpuinfo | tr -d ' ')"
if grep -qw avx512f /proc/cpuinfo; then fpc=32; elif grep -qw fma /proc/cpuinfo; then fpc=16; else fpc=4; fi
peak="$(awk -v c="$cores" -v m="$mhz" -v f="$fpc" 'BEGIN {printf "%.1f", c * m * 1e6 * f / 1e9}')"
echo "# meta flops_per_body_step=$per"
echo "# meta flops_commit=$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)"
echo "# meta flops_window=a:$((N0 + 1))-$N1"
echo "# meta peak_gflops=$peak"
echo "# meta peak_basis=${cores}_cores_x_${mhz}_MHz_x_${fpc}_DP_flops/cycle"
