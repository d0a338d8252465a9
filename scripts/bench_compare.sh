#!/usr/bin/env bash
# Old against new: two bench_ragdoll binaries run interleaved on the same machine at the same
# time, so that both see the same load (timings on a shared machine drift by tens of percent
# between minutes, far more than a change is worth).
#
#   scripts/bench_compare.sh OLD_BIN NEW_BIN [ROUNDS]       (or: make bench_compare OLD=.. NEW=..)
#
# Every round runs each scene at each thread count with both binaries back to back, the one that
# goes first swapping from round to round. Sleeping is off in every run (--opt sleep=0: the
# solver's cost, not how soon a scene falls asleep); before each round the new binary times the
# two threads' handoffs (`bench_ragdoll sync`). scripts/bench_compare_report.py prints them and
# the Markdown table: steps/s median (min-max) of each binary, new / old (ratio of the medians and
# min-max of the per-round ratios) and each binary's quality line.
#
# Settings (environment):
#   ROUNDS=5             rounds (also the third argument)
#   SCENES="b c p g1"    bench_ragdoll scenes; gN is scene g with N ragdolls (g1: one awake ragdoll)
#   THREADS="1 2"        --opt threads=T; scene g with fewer than 4 ragdolls runs at the first
#                        count only (under 48 bodies: islands that small never run in parallel)
#   STEPS=               --steps for every run (default: each scene's own)
#   OPTS=                --opt for both binaries, k=v,... (hash=1: the table says whether both
#                        binaries end every run on the same state hash)
#   OLD_OPTS=, NEW_OPTS= --opt for one binary only (NEW_OPTS=lanes=1: the double rows against a
#                        binary from before the wide solver, which does not know lanes=)
#   URDF=../shared/peers/ragdoll15.urdf
#   OUT_MD=              also write the table to this file
#   OUT_RAW=.ws/compare/raw.txt   the raw result lines
#   RUN_TIMEOUT=1800     seconds before one run is killed (and reported as failed)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
if (($# < 2 || $# > 3)); then
  echo "usage: $0 OLD_BIN NEW_BIN [ROUNDS]" >&2
  exit 2
fi
OLD_BIN="$(realpath "$1")"
NEW_BIN="$(realpath "$2")"
ROUNDS="${3:-${ROUNDS:-5}}"
SCENES="${SCENES:-b c p g1}"
THREADS="${THREADS:-1 2}"
STEPS="${STEPS:-}"
OPTS="${OPTS:-}" OLD_OPTS="${OLD_OPTS:-}" NEW_OPTS="${NEW_OPTS:-}"
URDF="${URDF:-$ROOT/../shared/peers/ragdoll15.urdf}"
OUT_RAW="${OUT_RAW:-$WS/compare/raw.txt}"
RUN_TIMEOUT="${RUN_TIMEOUT:-1800}"
for b in "$OLD_BIN" "$NEW_BIN"; do
  [[ -x "$b" ]] || { echo "bench_compare: $b is not an executable" >&2; exit 2; }
done
[[ "$ROUNDS" =~ ^[1-9][0-9]*$ ]] || { echo "bench_compare: ROUNDS must be >= 1" >&2; exit 2; }
export OMP_NUM_THREADS=1
mkdir -p "$(dirname "$OUT_RAW")"
: >"$OUT_RAW"
{
  echo "# meta date=$(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "# meta old_bin=$OLD_BIN"
  echo "# meta new_bin=$NEW_BIN"
  echo "# meta old_opts=$OPTS${OPTS:+${OLD_OPTS:+,}}$OLD_OPTS"
  echo "# meta new_opts=$OPTS${OPTS:+${NEW_OPTS:+,}}$NEW_OPTS"
  echo "# meta rounds=$ROUNDS"
  echo "# meta steps=${STEPS:-scene}"
  echo "# meta nproc=$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)"
  echo "# meta loadavg_start=$(cut -d' ' -f1-3 /proc/loadavg)"
} >>"$OUT_RAW"

# Each round runs fresh copies of the two binaries (fresh_copies, env.sh).
COPIES="$(dirname "$OUT_RAW")/binaries"

# run_one ROUND SIDE SCENE THREADS: one run; its line (with side, round, label) or "# FAILED".
run_one() {
  local r="$1" side="$2" label="$3" t="$4" bin opts args out rc line errf
  if [[ "$side" == old ]]; then bin="$OLD_BIN" opts="$OLD_OPTS"; else bin="$NEW_BIN" opts="$NEW_OPTS"; fi
  bin="$COPIES/$side/$(basename "$bin")"  # this round's copy
  args=("${label:0:1}" --urdf "$URDF" --opt "sleep=0,threads=$t")
  if [[ "$label" == g* ]]; then args+=(--ragdolls "${label:1}"); fi
  if [[ -n "$STEPS" ]]; then args+=(--steps "$STEPS"); fi
  if [[ -n "$OPTS" ]]; then args+=(--opt "$OPTS"); fi
  if [[ -n "$opts" ]]; then args+=(--opt "$opts"); fi
  errf="$(dirname "$OUT_RAW")/last_stderr.txt"
  rc=0
  out="$(timeout "$RUN_TIMEOUT" "$bin" "${args[@]}" 2>"$errf")" || rc=$?
  line="$(grep -m1 '^engine=' <<<"$out" || true)"
  if [[ "$rc" -eq 0 && -n "$line" ]]; then
    echo "$line side=$side round=$r label=$label run_threads=$t" >>"$OUT_RAW"
    echo "bench_compare: round $r $side $label threads=$t $(grep -o ' steps_per_s=[^ ]*' <<<"$line")" >&2
  else
    echo "# FAILED side=$side label=$label run_threads=$t round=$r rc=$rc reason=$(tail -n1 "$errf" | tr -s ' \t' '_' | cut -c1-160)" |
      tee -a "$OUT_RAW" >&2
  fi
}

for r in $(seq "$ROUNDS"); do
  # The two threads' handoffs and the cores' ceiling before the round (`bench_ragdoll sync`; an
  # older binary has none, or no ceiling).
  if probe="$("$NEW_BIN" sync --urdf "$URDF" 2>/dev/null || "$NEW_BIN" sync 2>/dev/null)" &&
     [[ "$probe" == region_us=* ]]; then
    echo "# meta sync_round_$r=$probe" >>"$OUT_RAW"
  fi
  fresh_copies "$COPIES/old" "$OLD_BIN"
  fresh_copies "$COPIES/new" "$NEW_BIN"
  if ((r % 2)); then pair=(old new); else pair=(new old); fi
  read -r -a counts <<<"$THREADS"
  for label in $SCENES; do
    if ! [[ "$label" =~ ^([abcpfsvw]|g[1-9][0-9]*)$ ]]; then
      echo "bench_compare: unknown scene $label" >&2
      exit 2
    fi
    for t in $THREADS; do
      if [[ "$label" == g* ]] && ((${label:1} < 4)) && [[ "$t" != "${counts[0]}" ]]; then continue; fi
      for side in "${pair[@]}"; do run_one "$r" "$side" "$label" "$t"; done
    done
  done
done
rm -rf "$COPIES"
echo "# meta loadavg_end=$(cut -d' ' -f1-3 /proc/loadavg)" >>"$OUT_RAW"
/usr/bin/python3 "$ROOT/scripts/bench_compare_report.py" "$OUT_RAW" ${OUT_MD:+--md "$OUT_MD"}
