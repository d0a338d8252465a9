#!/usr/bin/env bash
# Scenes b and c are chaotic: a change that only moves round-off (a new code path, other
# flags) gives another trajectory, and one run's vmax_3s says little about the change. This
# runs COPIES copies of one scene whose ragdolls are all turned by a tiny yaw (--opt yaw=R,
# 0 to 3e-3 rad), prints each copy's metric line and sums them up: how many copies are at rest
# at 3 s (vmax_3s <= 0.01 m/s, the joints issue's bar), the range of every quality metric, how
# many copies pass each of the other bars (anchor <= 1 mm, penetration <= 5 mm, limit <= 0.05
# rad: a rare hard hit shows in these counts, not in one run), the median steps/s, and the
# awake body-steps (bodies awake after each step, summed: what sleeping left to solve; the
# median, range and how many copies are all asleep at the end). The last are deterministic:
# they tell a change that moves when the copies sleep (11 of 16 copies of b sleep after 3 s,
# the scene as defined before) from one that changes the cost of a step. Compare two builds
# with BIN=.
#
#   scripts/bench_ensemble.sh SCENE ["k=v,..." solver options, as bench_ragdoll --opt]
#
# Settings (environment):
#   COPIES=16       1..64 copies (the first one is the scene as the bench runs it, yaw 0; the
#                   first 16 yaws are listed below, copy k > 16 is turned by (k - 16) * 1.37e-5)
#   BIN=            a bench_ragdoll binary; default: build it as `make bench` does (.ws/bench)
#   OWN_THREADS=2   WorldDef::threads of every copy (the result does not depend on it)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
SCENE="${1:?usage: $0 a|b|c|g|p|s [\"k=v,...\"]}"
OPTS="${2:-}"
COPIES="${COPIES:-16}"
OWN_THREADS="${OWN_THREADS:-2}"
YAWS=(0 1e-7 1e-6 3e-6 1e-5 1e-4 1e-3 0.01 2e-7 5e-7 2e-6 5e-6 2e-5 5e-5 3e-4 3e-3)
if ! [[ "$COPIES" =~ ^[0-9]+$ ]] || ((COPIES < 1 || COPIES > 64)); then
  echo "bench_ensemble: COPIES must be 1..64" >&2
  exit 2
fi
for ((k = ${#YAWS[@]}; k < COPIES; ++k)); do
  YAWS+=("$(awk -v k="$k" 'BEGIN { printf "%.6g", (k - 15) * 1.37e-5 }')")
done
if [[ -z "${BIN:-}" ]]; then
  BIN="$WS/bench/bench_ragdoll"
  build_bench_ragdoll "$WS/bench" "-DCMAKE_CXX_FLAGS_RELEASE=-O3 -DNDEBUG"  # as bench.sh
fi
cd "$ROOT"  # bench_ragdoll finds ../shared/peers/ragdoll15.urdf from here

LINES=()
FAILED=0
ERR=$(mktemp)
trap 'rm -f "$ERR"' EXIT
for ((k = 0; k < COPIES; ++k)); do
  # A copy that fails is reported (status and the last lines of its stderr) and left out of
  # the summary; the script goes on with the other copies and exits 1 at the end.
  rc=0
  line=$("$BIN" "$SCENE" --opt "${OPTS:+$OPTS,}yaw=${YAWS[k]},threads=$OWN_THREADS" 2>"$ERR") || rc=$?
  if ((rc != 0)); then
    echo "yaw=${YAWS[k]} FAILED (exit $rc): $(tail -n 3 "$ERR" | tr '\n' ' ')" >&2
    FAILED=$((FAILED + 1))
    continue
  fi
  LINES+=("$line")
  echo "$line" | tr ' ' '\n' | awk -F= -v y="${YAWS[k]}" '
    { v[$1] = $2 }
    END { printf "yaw=%-6s steps_per_s=%s max_anchor_err_m=%s max_ground_pen_m=%s max_limit_viol_rad=%s vmax_3s=%s nan=%s awake_body_steps=%s\n",
          y, v["steps_per_s"], v["max_anchor_err_m"], v["max_ground_pen_m"], v["max_limit_viol_rad"], v["vmax_3s"], v["nan"], v["awake_body_steps"] }'
done
if ((${#LINES[@]} == 0)); then
  echo "bench_ensemble: every copy failed" >&2
  exit 1
fi
printf '%s\n' "${LINES[@]}" | awk -v scene="$SCENE" -v opts="$OPTS" -v failed="$FAILED" '
  # median of a[1..n], sorting a in place (insertion sort: n <= 64)
  function median(a, n,    i, j, x) {
    for (i = 2; i <= n; ++i) { x = a[i]; for (j = i - 1; j >= 1 && a[j] > x; --j) a[j + 1] = a[j]; a[j + 1] = x }
    return n % 2 ? a[(n + 1) / 2] : 0.5 * (a[n / 2] + a[n / 2 + 1])
  }
  {
    delete v
    for (i = 1; i <= NF; ++i) { split($i, kv, "="); v[kv[1]] = kv[2] }
    n++
    rest += (v["vmax_3s"] + 0 <= 0.01)
    nan += v["nan"]
    sps[n] = v["steps_per_s"] + 0
    if ("awake_body_steps" in v) abs_[++na] = v["awake_body_steps"] + 0  # not from older builds
    asleep += (v["awake_bodies_end"] + 0 == 0)
    if (n == 1 || v["vmax_3s"] + 0 < vlo) vlo = v["vmax_3s"] + 0
    if (n == 1 || v["vmax_3s"] + 0 > vhi) vhi = v["vmax_3s"] + 0
    if (v["max_anchor_err_m"] + 0 > anc) anc = v["max_anchor_err_m"] + 0
    if (v["max_ground_pen_m"] + 0 > pen) pen = v["max_ground_pen_m"] + 0
    if (v["max_limit_viol_rad"] + 0 > lim) lim = v["max_limit_viol_rad"] + 0
    anc_ok += (v["max_anchor_err_m"] + 0 <= 0.001)
    pen_ok += (v["max_ground_pen_m"] + 0 <= 0.005)
    lim_ok += (v["max_limit_viol_rad"] + 0 <= 0.05)
  }
  END {
    med = median(sps, n)
    awake = "awake_body_steps_median=- awake_body_steps=-"
    if (na == n) {  # median() leaves abs_ sorted: [1] and [n] are the range
      amed = median(abs_, n)
      awake = sprintf("awake_body_steps_median=%.0f awake_body_steps=%.0f..%.0f", amed, abs_[1], abs_[n])
    }
    printf "ensemble scene=%s opts=%s copies=%d at_rest_3s=%d (vmax_3s <= 0.01) vmax_3s=%g..%g max_anchor_err_m=%g max_ground_pen_m=%g max_limit_viol_rad=%g anchor_ok=%d pen_ok=%d limit_ok=%d nan_copies=%d failed_copies=%d steps_per_s_median=%.0f %s asleep_end=%d\n",
           scene, opts == "" ? "-" : opts, n, rest, vlo, vhi, anc, pen, lim, anc_ok, pen_ok, lim_ok, nan, failed, med, awake, asleep
  }'
((FAILED == 0))
