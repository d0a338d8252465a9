#!/usr/bin/env bash
# make bench: our engine against the peers (MuJoCo, Bullet, ODE from ../shared/peers) in one sitting.
#
#  1. Builds the ROS-free core and bench/bench_ragdoll in Release with the package's own flags
#     (CMake's Release, -O3 -DNDEBUG: what catkin_make -DCMAKE_BUILD_TYPE=Release gives a user)
#     into .ws/bench. The peer bench drivers get the peers' README flags (-O2 -march=native);
#     their engines are Debian's prebuilt libraries.
#  2. Builds the peer benches from $PEERS_DIR (bench_<engine>, unmodified sources) and their
#     scaling drivers (bench/peers_scaling/scaling_<engine>.cpp: the same sources plus scene g)
#     into .ws/bench/peers. Nothing is written to $PEERS_DIR.
#  3. Runs ROUNDS rounds. In each round every scene is run by every engine back to back
#     (round-robin, the engine order rotating from round to round), so all engines see the same
#     machine load: scenes a, b, c (ours twice: sleeping off, the headline figure since the peers'
#     benches do not sleep, and sleeping on, engine ragdoll_sim_sleep, right after it); the scaling
#     scene g with N = $SCALING_NS ragdolls; then our own scenes p and s (no peer has them). Ours
#     with every row in double (--opt lanes=1, engine ragdoll_sim_lanes1, with its _sleep and
#     _1thread runs) runs all of these as an engine of its own beside the default float lanes
#     (lanes=0). Then the scale of worlds: scenes f, w, v back to back (the bundled ragdoll on the
#     plane, among 10 000 static boxes as bodies, as shapes of one body) and the load of generated
#     worlds of dynamic primitives (scene l, bench_world_load, LOAD_RUNS). Each round times fresh
#     copies of every engine's binaries (fresh_copies, env.sh).
#  4. Raw result lines (plus round=R) go to bench/results_raw.txt, and scripts/bench_report.py
#     turns them into bench/RESULTS.md and bench/scaling.png.
#
# Settings (environment):
#   ROUNDS=3                 rounds (the report gives the median and min-max over them)
#   PEERS_DIR=../shared/peers
#   SCENES="a b c"           scenes that every engine runs
#   OWN_SCENES="p s"         scenes that only bench_ragdoll has
#   SCALE_SCENES="f w v"     static-world scenes, with urdf/ragdoll.urdf ("" skips them)
#   LOAD_RUNS="3000:8 300:0" runs of scene l per round, OBJECTS:SIZES (sizes per kind of
#                            primitive; 0: every model its own, each parsed by SDFormat); "" skips
#   SCALING_NS="1 4 16 64 256"   ragdoll counts for scene g ("" skips scaling)
#   SCALING_STEPS=           steps for scene g (default: the scene's 3000)
#   ENGINES="ragdoll_sim ragdoll_sim_lanes1 mujoco bullet ode"
#                            ragdoll_sim_lanes1: ours with SolverSettings::lanes = 1 (double rows)
#   RUN_TIMEOUT=1800         seconds before one run is killed (and reported as failed)
#   OWN_THREADS=$(nproc)     threads our solver uses (WorldDef::threads: islands in parallel,
#                            same result for any count); the peers are single-threaded.
#   BENCH_THREADS=1          OMP_NUM_THREADS for every run (only matters for threads=0).
#   BENCH_OUT=bench          folder for results_raw.txt, RESULTS.md, scaling.png
#   SLEEP_ON=1               also run ours with sleeping on in scenes a, b, c (0 skips it);
#                            ours runs a, b, c, g and p with sleeping off (--opt sleep=0)
#   SCALING_1THREAD=1        also run our scene g on one thread (ragdoll_sim_1thread and
#                            ragdoll_sim_lanes1_1thread):
#                            the cost per body-step of the algorithm alone, the same thread
#                            count at every N (N = 1 is one island, which runs on one core)
#   FLOPS=1                  0 skips the flop count (scripts/flops.sh, valgrind, ~5 min)
#   FLOPS_OPTS=sleep=0,lanes=1   --opt of the flop count's runs (scripts/flops.sh: the double rows)
#   ENSEMBLE="b c"           chaotic scenes that our bench also runs as ENSEMBLE_COPIES (32)
#                            yaw-perturbed copies after the timed rounds (scripts/bench_ensemble.sh;
#                            once per engine of ours, lanes=1 with --opt lanes=1):
#                            at rest at 3 s and within each quality bar, counted over the copies
#                            ("" skips it; the peers have no yaw option)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
PEERS_DIR="$(cd "${PEERS_DIR:-$ROOT/../shared/peers}" && pwd)"
ROUNDS="${ROUNDS:-3}"
SCENES="${SCENES-a b c}"
OWN_SCENES="${OWN_SCENES-p s}"
SCALE_SCENES="${SCALE_SCENES-f w v}"
LOAD_RUNS="${LOAD_RUNS-3000:8 300:0}"
SCALING_NS="${SCALING_NS-1 4 16 64 256}"
SCALING_STEPS="${SCALING_STEPS:-}"
ENGINES="${ENGINES:-ragdoll_sim ragdoll_sim_lanes1 mujoco bullet ode}"
RUN_TIMEOUT="${RUN_TIMEOUT:-1800}"
BENCH_OUT="${BENCH_OUT:-$ROOT/bench}"
OWN_THREADS="${OWN_THREADS:-$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)}"
export OMP_NUM_THREADS="${BENCH_THREADS:-1}"
URDF="$PEERS_DIR/ragdoll15.urdf"
BUILD="$WS/bench"
PEER_BUILD="$BUILD/peers"
FLAGS="-O2 -march=native"   # the peer drivers (../shared/peers/README.md)
OWN_FLAGS="-O3 -DNDEBUG"    # CMake's Release default; the core adds -O3 itself (CMakeLists.txt)
mkdir -p "$PEER_BUILD" "$BENCH_OUT"
LOG="$BUILD/bench_stderr.log"
: >"$LOG"

# ---- 1. our bench
echo "bench: building bench_ragdoll (Release, $OWN_FLAGS) in $BUILD"
build_bench_ragdoll "$BUILD" "-DCMAKE_CXX_FLAGS_RELEASE=$OWN_FLAGS"
if [[ -n "$LOAD_RUNS" ]]; then cmake --build "$BUILD" -j2 --target bench_world_load >/dev/null; fi

# ---- 2. peer benches (a failed build drops that engine and is reported)
RAW_TMP="$BENCH_OUT/results_raw.txt.partial"
: >"$RAW_TMP"
declare -A PEER_LIBS=(
  [mujoco]="-lmujoco -ltinyxml2 -lurdfdom_model"
  [bullet]="-I/usr/include/bullet -lBulletDynamics -lBulletCollision -lLinearMath -lurdfdom_model"
  [ode]="-lode -lurdfdom_model"
)
# engines of ours in ENGINES, and the --opt of each (bench_ragdoll prints engine=ragdoll_sim)
declare -A OURS_OPTS=([ragdoll_sim]="" [ragdoll_sim_lanes1]="lanes=1")
engines=()
for e in $ENGINES; do
  if [[ -n "${OURS_OPTS[$e]+x}" ]]; then engines+=("$e"); continue; fi
  if [[ -z "${PEER_LIBS[$e]+x}" ]]; then echo "bench: unknown engine $e" >&2; exit 2; fi
  echo "bench: building peer $e from $PEERS_DIR"
  # shellcheck disable=SC2086  # PEER_LIBS holds several words
  if g++ $FLAGS -std=c++17 -I"$PEERS_DIR" "$PEERS_DIR/bench_$e.cpp" -o "$PEER_BUILD/bench_$e" \
       ${PEER_LIBS[$e]} 2>>"$LOG" &&
     { [[ -z "$SCALING_NS" ]] ||
       g++ $FLAGS -std=c++17 -I"$PEERS_DIR" "$ROOT/bench/peers_scaling/scaling_$e.cpp" \
         -o "$PEER_BUILD/scaling_$e" ${PEER_LIBS[$e]} 2>>"$LOG"; }; then
    engines+=("$e")
  else
    echo "bench: building peer $e failed (see $LOG); it is left out" >&2
    echo "# FAILED engine=$e scenario=build ragdolls=0 round=0 rc=1 reason=build_failed" >>"$RAW_TMP"
  fi
done

# ---- metadata for the report
{
  echo "# meta date=$(date -u +%Y-%m-%dT%H:%M:%SZ)"
  echo "# meta commit=$(git -C "$ROOT" rev-parse --short HEAD 2>/dev/null || echo unknown)"
  if [[ -n "$(git -C "$ROOT" status --porcelain 2>/dev/null)" ]]; then
    echo "# meta worktree=with_uncommitted_changes"
  else
    echo "# meta worktree=clean"
  fi
  # nproc honours OMP_NUM_THREADS, which is set above: ask it without
  echo "# meta nproc=$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)"
  echo "# meta cpu=$(grep -m1 '^model name' /proc/cpuinfo | sed 's/^[^:]*: *//')"
  echo "# meta compiler=$(g++ -dumpfullversion 2>/dev/null || g++ -dumpversion)"
  echo "# meta flags_ours=$OWN_FLAGS"
  echo "# meta flags_peers=$FLAGS (bench drivers; engines: Debian's libraries)"
  echo "# meta rounds=$ROUNDS"
  echo "# meta omp_num_threads=$OMP_NUM_THREADS"
  echo "# meta own_threads=$OWN_THREADS"
  echo "# meta loadavg_start=$(cut -d' ' -f1-3 /proc/loadavg)"
  echo "# meta engines=${engines[*]}"
  echo "# meta peers_dir=$PEERS_DIR"
} >>"$RAW_TMP"

# ---- 3. runs
# engines of ours in ENGINES (OURS_OPTS above)
ours=()
for e in "${engines[@]}"; do if [[ -n "${OURS_OPTS[$e]+x}" ]]; then ours+=("$e"); fi; done
# Every round times fresh copies of every engine's binaries (fresh_copies, env.sh).
ROUND_BINS="$BUILD/round_binaries"
copy_round_binaries() {
  local own=("$BUILD/bench_ragdoll") peers=() e
  if [[ -n "$LOAD_RUNS" ]]; then own+=("$BUILD/bench_world_load"); fi
  fresh_copies "$ROUND_BINS" "${own[@]}"
  for e in "${engines[@]}"; do
    if [[ -n "${OURS_OPTS[$e]+x}" ]]; then continue; fi
    peers+=("$PEER_BUILD/bench_$e")
    if [[ -n "$SCALING_NS" ]]; then peers+=("$PEER_BUILD/scaling_$e"); fi
  done
  if ((${#peers[@]})); then fresh_copies "$ROUND_BINS/peers" "${peers[@]}"; fi
}
# run_one ROUND ENGINE SCENE [N]: one run; its line (with round=ROUND) or a "# FAILED" line.
# An engine of ours is OURS[_sleep|_1thread]: sleeping on, or one thread.
run_one() {
  local r="$1" e="$2" s="$3" n="${4:-}" bin args=() out rc err base="" variant=""
  if [[ "$e" == ragdoll_sim* ]]; then
    bin="$ROUND_BINS/bench_ragdoll"
    variant="${e##*_}"; [[ "$variant" == sleep || "$variant" == 1thread ]] || variant=""
    base="${e%_"$variant"}"
  elif [[ "$s" == g ]]; then bin="$ROUND_BINS/peers/scaling_$e"
  else bin="$ROUND_BINS/peers/bench_$e"; fi
  args=("$s" --urdf "$URDF")
  if [[ "$s" == [fwv] ]]; then args=("$s" --urdf "$ROOT/urdf/ragdoll.urdf"); fi
  if [[ -n "$base" ]]; then
    if [[ -n "${OURS_OPTS[$base]}" ]]; then args+=(--opt "${OURS_OPTS[$base]}"); fi
    if [[ "$variant" == 1thread ]]; then args+=(--opt threads=1); else args+=(--opt "threads=$OWN_THREADS"); fi
    # sleeping off where the peers run (they do not sleep) and in p; s is the sleep check
    if [[ "$variant" == sleep ]]; then args+=(--opt sleep=1)
    elif [[ "$s" == [abcgp] ]]; then args+=(--opt sleep=0); fi
  fi
  # scene l: the load of a generated world (bench_world_load), N primitives, LOAD_SIZE sizes
  if [[ "$s" == l ]]; then bin="$ROUND_BINS/bench_world_load"; args=(l --objects "$n" --sizes "$LOAD_SIZE"); n=""; fi
  if [[ "$s" == g ]]; then
    args+=(--ragdolls "$n")
    if [[ -n "$SCALING_STEPS" ]]; then args+=(--steps "$SCALING_STEPS"); fi
  fi
  local errf="$BUILD/last_stderr.txt"
  rc=0
  out="$(cd "$BUILD" && timeout "$RUN_TIMEOUT" "$bin" "${args[@]}" 2>"$errf")" || rc=$?
  { echo "### round=$r engine=$e scene=$s ${n:+ragdolls=$n }rc=$rc"; cat "$errf"; } >>"$LOG"
  local line
  line="$(grep -m1 '^engine=' <<<"$out" || true)"
  if [[ "$e" == ragdoll_sim_* ]]; then line="${line/#engine=ragdoll_sim /engine=$e }"; fi
  if [[ "$rc" -eq 0 && -n "$line" ]]; then
    echo "$line round=$r" | tee -a "$RAW_TMP"
  else
    err="$(grep -v '^$' "$errf" | tail -n1 | tr -s ' \t' '_' | cut -c1-160)"
    [[ "$rc" -eq 124 ]] && err="timeout_after_${RUN_TIMEOUT}s"
    echo "# FAILED engine=$e scenario=$s ragdolls=${n:-0} round=$r rc=$rc reason=${err:-no_result_line}" |
      tee -a "$RAW_TMP"
  fi
}

# engines of round R, rotated by R so that no engine always runs first
rotated() {
  local r="$1" k="${#engines[@]}" i
  for ((i = 0; i < k; ++i)); do echo "${engines[$(((i + r - 1) % k))]}"; done
}

t0=$SECONDS
for r in $(seq "$ROUNDS"); do
  echo "bench: round $r of $ROUNDS ($((SECONDS - t0)) s so far)"
  copy_round_binaries
  # what two threads' handoffs cost in this round and how fast the two cores run at once
  # (bench_ragdoll sync, bench/sync_probe.hpp)
  echo "# meta sync_round_$r=$(cd "$BUILD" && "$ROUND_BINS/bench_ragdoll" sync --urdf "$URDF")" \
    >>"$RAW_TMP"
  mapfile -t order < <(rotated "$r")
  for s in $SCENES; do
    for e in "${order[@]}"; do
      run_one "$r" "$e" "$s"
      if [[ -n "${OURS_OPTS[$e]+x}" && "${SLEEP_ON:-1}" != 0 ]]; then run_one "$r" "${e}_sleep" "$s"; fi
    done
  done
  for n in $SCALING_NS; do
    for e in "${order[@]}"; do run_one "$r" "$e" g "$n"; done
    if [[ "${SCALING_1THREAD:-1}" != 0 ]]; then
      for e in "${order[@]}"; do
        if [[ -n "${OURS_OPTS[$e]+x}" ]]; then run_one "$r" "${e}_1thread" g "$n"; fi
      done
    fi
  done
  for s in $OWN_SCENES; do
    for e in "${order[@]}"; do if [[ -n "${OURS_OPTS[$e]+x}" ]]; then run_one "$r" "$e" "$s"; fi; done
  done
  if [[ " ${engines[*]} " == *" ragdoll_sim "* ]]; then
    for s in $SCALE_SCENES; do run_one "$r" ragdoll_sim "$s"; done
    for lr in $LOAD_RUNS; do LOAD_SIZE="${lr#*:}" run_one "$r" ragdoll_sim l "${lr%%:*}"; done
  fi
done
rm -rf "$ROUND_BINS"
echo "# meta loadavg_end=$(cut -d' ' -f1-3 /proc/loadavg)" >>"$RAW_TMP"
# ---- chaotic scenes as perturbed copies (after the timed rounds; ours only)
for e in "${ours[@]}"; do
  for s in ${ENSEMBLE-b c}; do
    echo "bench: scene $s as ${ENSEMBLE_COPIES:-32} yaw-perturbed copies ($e)"
    if line="$(COPIES="${ENSEMBLE_COPIES:-32}" BIN="$BUILD/bench_ragdoll" OWN_THREADS="$OWN_THREADS" \
                 "$ROOT/scripts/bench_ensemble.sh" "$s" "${OURS_OPTS[$e]}" 2>>"$LOG" | grep '^ensemble ')"; then
      echo "# $line" >>"$RAW_TMP"
    else
      echo "bench: ensemble of scene $s ($e) failed (see $LOG)" >&2
    fi
  done
done
# ---- flop count (after the timed runs, so that it disturbs none of them)
if [[ " ${engines[*]} " == *" ragdoll_sim "* && "${FLOPS:-1}" != 0 ]] && command -v valgrind >/dev/null; then
  echo "bench: counting flops per body-step (valgrind lackey, a few minutes)"
  "$ROOT/scripts/flops.sh" >>"$RAW_TMP" || echo "bench: flop count failed" >&2
fi
echo "# meta total_s=$((SECONDS - t0))" >>"$RAW_TMP"
mv "$RAW_TMP" "$BENCH_OUT/results_raw.txt"
echo "bench: $((SECONDS - t0)) s; raw lines in $BENCH_OUT/results_raw.txt (engine stderr: $LOG)"

# ---- 4. report
/usr/bin/python3 "$ROOT/scripts/bench_report.py" "$BENCH_OUT/results_raw.txt" \
  --md "$BENCH_OUT/RESULTS.md" --png "$BENCH_OUT/scaling.png"
