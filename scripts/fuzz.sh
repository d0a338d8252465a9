#!/usr/bin/env bash
# Builds the libFuzzer targets (test/fuzz: fuzz_urdf, fuzz_commands, fuzz_world; clang, ASan +
# UBSan) in .ws/asan (build_asan in env.sh, shared with sanitize.sh) and runs each in turn.
# Prints each target's executions and any crash; exits non-zero on a crash (the input is saved
# as .ws/fuzz/artifacts/<target>-crash-*).
#   fuzz.sh                      FUZZ_SECONDS (60) per target, random seed; what it finds new is
#                                kept in .ws/fuzz/corpus/<target> for the next run (make fuzz)
#   fuzz.sh --runs N --junit DIR every seed input, then up to N executions in all from seed 1
#                                into a fresh corpus; one JUnit case per target in DIR (make test)
# Seeds: test/fuzz/corpus/<target>; fuzz_urdf also reads urdf/ and test/urdf/fixtures/ in place
# (the real ragdoll, the mesh fixture, the malformed fixtures) rather than copies of them;
# fuzz_world reads test/world_file/fixtures in place.
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
SECONDS_EACH="${FUZZ_SECONDS:-60}"
RUNS=""
JUNIT=""
while [[ $# -gt 0 ]]; do
  case "$1" in
    --runs) RUNS="$2"; shift 2 ;;
    --junit) JUNIT="$2"; shift 2 ;;
    *) echo "usage: fuzz.sh [--runs N] [--junit DIR]"; exit 2 ;;
  esac
done
BUILD="$ASAN_BUILD"
mkdir -p "$WS/fuzz/artifacts"
[[ -n "$JUNIT" ]] && mkdir -p "$JUNIT"
build_asan fuzz_urdf fuzz_commands fuzz_world || exit 1

seeds() {  # target -> SEEDS (array of corpus folders, read only)
  SEEDS=("$ROOT/test/fuzz/corpus/$1")
  if [[ "$1" == fuzz_urdf ]]; then SEEDS+=("$ROOT/urdf" "$ROOT/test/urdf/fixtures"); fi
  if [[ "$1" == fuzz_world ]]; then SEEDS+=("$ROOT/test/world_file/fixtures"); fi
}

junit() {  # target ok(0/1) log
  /usr/bin/python3 - "$@" "$JUNIT/fuzz-$1.xml" "$RUNS" <<'PY'
import sys, xml.etree.ElementTree as ET
target, failed, log, out, runs = sys.argv[1:]
suite = ET.Element("testsuite", name="fuzz", tests="1", failures=failed, errors="0", skipped="0")
case = ET.SubElement(suite, "testcase", classname="fuzz", name=f"{target}.corpus_plus_{runs}_runs")
if failed == "1":
    text = open(log, errors="replace").read()[-6000:]
    ET.SubElement(case, "failure", message="libFuzzer found a crash").text = text
ET.ElementTree(suite).write(out, encoding="utf-8", xml_declaration=True)
PY
}

rc=0
for t in fuzz_urdf fuzz_commands fuzz_world; do
  log="$WS/fuzz/$t.log"
  if [[ -n "$RUNS" ]]; then
    corpus="$(mktemp -d)"
    args=(-runs="$RUNS" -seed=1)
  else
    corpus="$WS/fuzz/corpus/$t"
    mkdir -p "$corpus"
    args=(-max_total_time="$SECONDS_EACH")
  fi
  seeds "$t"
  # -timeout: an input that runs 20 s is a hang; -rss_limit_mb: a runaway allocation is a crash.
  # New inputs go to the first folder ($corpus) only.
  "$BUILD/$t" "${args[@]}" -timeout=20 -rss_limit_mb=2048 -print_final_stats=1 \
    -dict="$ROOT/test/fuzz/$t.dict" -artifact_prefix="$WS/fuzz/artifacts/$t-" \
    "$corpus" "${SEEDS[@]}" >"$log" 2>&1
  code=$?
  [[ -n "$RUNS" ]] && rm -rf "$corpus"
  execs="$(awk '/stat::number_of_executed_units:/ {print $2}' "$log" | tail -n 1)"
  cov="$(grep -oE 'cov: [0-9]+ ft: [0-9]+ corp: [0-9]+/[0-9a-zA-Z]+' "$log" | tail -n 1)"
  secs="$(awk '/^Done [0-9]+ runs in/ {print $5}' "$log" | tail -n 1)"
  if [[ $code -ne 0 ]]; then
    rc=1
    echo "fuzz: $t CRASH (exit $code) after ${execs:-?} executions; log: $log"
    grep -E 'check failed|==ERROR|runtime error|SUMMARY|Test unit written|ALARM|out-of-memory' "$log" | head -n 10
    [[ -n "$JUNIT" ]] && junit "$t" 1 "$log"
  else
    echo "fuzz: $t ${execs:-?} executions in ${secs:-?} s, no crash (${cov:-})"
    [[ -n "$JUNIT" ]] && junit "$t" 0 "$log"
  fi
done
exit $rc
