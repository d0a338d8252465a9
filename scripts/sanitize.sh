#!/usr/bin/env bash
# The ROS-free gtests (test_core, test_urdf, test_world_file, test_scene; ragdoll_check too, which
# test_urdf and test_world_file run) built with AddressSanitizer + UndefinedBehaviorSanitizer
# (clang, OpenMP on) in .ws/asan (build_asan in env.sh), and run: each binary in gtest shards
# (2 per core), SANITIZE_JOBS (default: the cores) shards at a time. Usage: sanitize.sh
# RESULTS_DIR. Each shard writes its gtest JUnit report there; a run that a sanitizer ends (no
# report, or one without the failure) gets a failing case <binary>.sanitizer with the report's
# tail, so that scripts/test.sh counts it. Exits non-zero when a build fails or any run fails.
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
RESULTS="${1:?usage: sanitize.sh RESULTS_DIR}"
BUILD="$ASAN_BUILD"
JOBS="${SANITIZE_JOBS:-$(nproc)}"
mkdir -p "$RESULTS"
build_asan test_core test_urdf test_world_file test_scene ragdoll_check || exit 1

# A distinct exit code (not ragdoll_check's 0..3) so that a report inside ragdoll_check, which
# test_urdf runs, fails the test that runs it; leaks are checked at exit.
export ASAN_OPTIONS="exitcode=66:detect_leaks=1:halt_on_error=1:print_summary=1"
export UBSAN_OPTIONS="exitcode=66:halt_on_error=1:print_stacktrace=1"
export LSAN_OPTIONS="suppressions=$ROOT/scripts/lsan.supp"
# The longest simulations (test/test_scale.hpp) at a tenth of their steps: ASan + UBSan run the
# solver about ten times slower.
export RAGDOLL_SIM_TEST_SCALE="${RAGDOLL_SIM_TEST_SCALE:-0.1}"

# One failing JUnit case (for scripts/test.sh's count) carrying the tail of a log.
failure_xml() {  # name log out.xml
  /usr/bin/python3 - "$1" "$2" "$3" <<'PY'
import sys, xml.etree.ElementTree as ET
name, log, out = sys.argv[1:]
text = open(log, errors="replace").read()[-6000:]
suite = ET.Element("testsuite", name="sanitize", tests="1", failures="1", errors="0", skipped="0")
case = ET.SubElement(suite, "testcase", classname="sanitize", name=name)
ET.SubElement(case, "failure", message="sanitizer report or abnormal exit").text = text
ET.ElementTree(suite).write(out, encoding="utf-8", xml_declaration=True)
PY
}

# run_shard BINARY INDEX COUNT: one gtest shard, its output in BUILD/BINARY-INDEX.log; its
# verdict ("ok" or "failed") goes to BUILD/BINARY-INDEX.status and the lines that say why to
# BUILD/BINARY-INDEX.report, printed once every shard has run.
run_shard() {
  local t="$1" i="$2" n="$3"
  local xml="$RESULTS/sanitize-$t-$i.xml" log="$BUILD/$t-$i.log" code summary verdict=ok
  rm -f "$xml" "$RESULTS/sanitize-$t-$i-sanitizer.xml"
  GTEST_TOTAL_SHARDS="$n" GTEST_SHARD_INDEX="$i" "$BUILD/$t" --gtest_output="xml:$xml" >"$log" 2>&1
  code=$?
  summary="$(grep -E '^\[  (PASSED|FAILED)  \]' "$log" | tr '\n' ' ')"
  if grep -qE '^(==[0-9]+==ERROR: |SUMMARY: (Address|Undefined|Leak)Sanitizer)|runtime error: ' "$log" ||
     [[ $code -ne 0 ]]; then
    verdict=failed
    {
      echo "sanitize: $t shard $i/$n FAILED (exit $code) $summary; log: $log"
      grep -E 'runtime error: |==ERROR: |SUMMARY: |^\[  FAILED  \]' "$log" | head -n 20
    } >"$BUILD/$t-$i.report"
    if [[ ! -f "$xml" ]] || ! grep -q '<failure' "$xml"; then
      failure_xml "$t.sanitizer" "$log" "$RESULTS/sanitize-$t-$i-sanitizer.xml"
    fi
  fi
  echo "$verdict" >"$BUILD/$t-$i.status"
}

# The longest binary first, so that the last shards to start are short ones.
TESTS=(test_urdf test_world_file test_core test_scene)
SHARDS=$((2 * JOBS))
rm -f "$RESULTS"/sanitize-*.xml "$BUILD"/*.status "$BUILD"/*.report
running=0
for t in "${TESTS[@]}"; do
  for ((i = 0; i < SHARDS; i++)); do
    if ((running >= JOBS)); then wait -n; running=$((running - 1)); fi
    run_shard "$t" "$i" "$SHARDS" &
    running=$((running + 1))
  done
done
wait

rc=0
for t in test_core test_urdf test_world_file test_scene; do
  passed=0 ok=1
  for ((i = 0; i < SHARDS; i++)); do
    [[ "$(cat "$BUILD/$t-$i.status" 2>/dev/null)" == ok ]] || ok=0
    [[ -f "$BUILD/$t-$i.report" ]] && cat "$BUILD/$t-$i.report"
    n="$(grep -oE '^\[  PASSED  \] [0-9]+' "$BUILD/$t-$i.log" 2>/dev/null | grep -oE '[0-9]+$')"
    passed=$((passed + ${n:-0}))
  done
  if ((ok)); then
    echo "sanitize: $t clean (ASan + UBSan) [  PASSED  ] $passed tests in $SHARDS shards"
  else
    rc=1
    echo "sanitize: $t FAILED ($passed tests passed in $SHARDS shards)"
  fi
done
exit $rc
