#!/usr/bin/env bash
# Flop count of our solver per body-step, for bench/RESULTS.md (make bench calls it).
# There are no hardware counters in this VM (perf: "not supported"), so we count in software:
# bench_ragdoll is built with x87 arithmetic and Eigen's vectorisation off, so every double
# operation is one F64 ALU op in valgrind's IR, and lackey (--detailed-counts) counts them.
# Two runs of scene a (N0 and N1 steps) are subtracted, which leaves the steps N0+1..N1 (the
# ragdoll on the ground with its contacts) without the start-up. The count includes the few
# conversions and negations, so it is an upper bound on the flops.
# lackey counts by the IR's type: F64 (valgrind models the x87 registers as doubles, so float
# arithmetic in this build lands there too), F32 (results of type float: the conversions to
# float) and V128 / V256 (SSE / AVX lanes, which the x87 flags do not touch: the wide solver's
# float kernels, up to 4 / 8 flops each). flops_per_body_step = F64 + F32 + 4 V128 + 8 V256.
# Prints "# meta" lines for results_raw.txt: flops_per_body_step and each type's count, the
# window, the options, peak_gflops (cores x MHz x DP flops/cycle from the CPU flags: 32 with
# AVX-512, 16 with AVX2+FMA, 4 else) and peak_gflops_float (twice that: SSE and AVX do twice as
# many float as double operations per instruction).
#   FLOPS_OPTS=sleep=0,lanes=1   bench_ragdoll --opt. The double rows by default: they are the
#                        float lanes' rows one at a time, so their count is the solver's work; in
#                        the lanes lackey would also count the padding lanes, selects and
#                        conversions (lanes=0: an upper bound ~2.7 times as large)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
N0="${FLOPS_N0:-1000}"
N1="${FLOPS_N1:-1200}"
URDF="${URDF:-$ROOT/../shared/peers/ragdoll15.urdf}"
BUILD="$WS/flops"
build_bench_ragdoll "$BUILD" \
  "-DCMAKE_CXX_FLAGS=-O2 -mfpmath=387 -fno-tree-vectorize -fno-tree-slp-vectorize -DEIGEN_DONT_VECTORIZE"
OPTS="${FLOPS_OPTS-sleep=0,lanes=1}"
# counts STEPS: "F64 F32 V128 V256", lackey's arithmetic ops of each type over STEPS steps
counts() {
  valgrind --tool=lackey --detailed-counts=yes "$BUILD/bench_ragdoll" a --steps "$1" --no-metrics \
    --urdf "$URDF" ${OPTS:+--opt "$OPTS"} 2>&1 >/dev/null |
    awk '{gsub(",", "", $5)} $2 ~ /^(F64|F32|V128|V256)$/ {n[$2] = $5}
         END {printf "%d %d %d %d\n", n["F64"], n["F32"], n["V128"], n["V256"]}'
}
read -r f64_0 f32_0 v128_0 v256_0 < <(counts "$N0")
read -r f64_1 f32_1 v128_1 v256_1 < <(counts "$N1")
bodies=15
div=$(( (N1 - N0) * bodies ))
f64=$(( (f64_1 - f64_0) / div ))
f32=$(( (f32_1 - f32_0) / div ))
v128=$(( (v128_1 - v128_0) / div ))
v256=$(( (v256_1 - v256_0) / div ))
per=$(( f64 + f32 + 4 * v128 + 8 * v256 ))
cores="$(getconf _NPROCESSORS_ONLN)"  # not nproc: it honours OMP_NUM_THREADS (bench.sh sets 1)
mhz="$(awk -F: '/cpu MHz/ {print $2; exit}' /proc/cpuinfo | tr -d ' ')"
if grep -qw avx512f /proc/cpuinfo; then fpc=32; elif grep -qw fma /proc/cpuinfo; then fpc=16; else fpc=4; fi
peak="$(awk -v c="$cores" -v m="$mhz" -v f="$fpc" 'BEGIN {printf "%.1f", c * m * 1e6 * f / 1e9}')"
peak_float="$(awk -v c="$cores" -v m="$mhz" -v f="$fpc" 'BEGIN {printf "%.1f", 2 * c * m * 1e6 * f / 1e9}')"
echo "# meta flops_per_body_step=$per"
echo "# meta flops_f64_per_body_step=$f64"
echo "# meta flops_f32_per_body_step=$f32"
echo "# meta flops_v128_per_body_step=$v128"
echo "# meta flops_v256_per_body_step=$v256"
echo "# meta flops_opts=$OPTS"
echo "# meta flops_commit=$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)"
echo "# meta flops_window=a:$((N0 + 1))-$N1"
echo "# meta peak_gflops=$peak"
echo "# meta peak_gflops_float=$peak_float"
echo "# meta peak_basis=${cores}_cores_x_${mhz}_MHz_x_${fpc}_DP_flops/cycle"
