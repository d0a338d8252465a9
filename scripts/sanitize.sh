#!/usr/bin/env bash
# The ROS-free gtests (test_core, test_urdf, test_world_file, test_scene; ragdoll_check too, which
# test_urdf and test_world_file run)
# built with AddressSanitizer + UndefinedBehaviorSanitizer (gcc's runtimes, OpenMP on) in
# .ws/sanitize, and run. Usage: sanitize.sh RESULTS_DIR. Each binary writes its gtest JUnit
# report there; a run that a sanitizer ends (no report, or one without the failure) gets a
# failing case <binary>.sanitizer with the report's tail, so that scripts/test.sh counts it.
# Exits non-zero when a build fails or any run fails.
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
RESULTS="${1:?usage: sanitize.sh RESULTS_DIR}"
BUILD="$WS/sanitize"
SAN="-fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all"
mkdir -p "$RESULTS"

# -O2 -g: the solver (Eigen) at near-Release speed under ASan; -g for the reports.
if ! cmake -S "$ROOT" -B "$BUILD" -DRAGDOLL_SIM_CORE_ONLY=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -g" -DCMAKE_CXX_FLAGS="$SAN" \
      -DCMAKE_EXE_LINKER_FLAGS="$SAN" -DCMAKE_SHARED_LINKER_FLAGS="$SAN" >"$BUILD.cmake.log" 2>&1 ||
   ! cmake --build "$BUILD" -j2 --target test_core test_urdf test_world_file test_scene ragdoll_check \
      >"$BUILD.build.log" 2>&1; then
  echo "sanitize: build failed (see $BUILD.cmake.log, $BUILD.build.log):"
  tail -n 30 "$BUILD.build.log" 2>/dev/null
  exit 1
fi

# A distinct exit code (not ragdoll_check's 0..3) so that a report inside ragdoll_check, which
# test_urdf runs, fails the test that runs it; leaks are checked at exit.
export ASAN_OPTIONS="exitcode=66:detect_leaks=1:halt_on_error=1:print_summary=1"
export UBSAN_OPTIONS="exitcode=66:halt_on_error=1:print_stacktrace=1"
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

rc=0
for t in test_core test_urdf test_world_file test_scene; do
  xml="$RESULTS/sanitize-$t.xml"
  log="$BUILD/$t.log"
  rm -f "$xml"
  "$BUILD/$t" --gtest_output="xml:$xml" >"$log" 2>&1
  code=$?
  summary="$(grep -E '^\[  (PASSED|FAILED)  \]' "$log" | tr '\n' ' ')"
  if grep -qE '^(==[0-9]+==ERROR: |SUMMARY: (Address|Undefined|Leak)Sanitizer)|runtime error: ' "$log" ||
     [[ $code -ne 0 ]]; then
    rc=1
    echo "sanitize: $t FAILED (exit $code) $summary; log: $log"
    grep -E 'runtime error: |==ERROR: |SUMMARY: |^\[  FAILED  \]' "$log" | head -n 20
    if [[ ! -f "$xml" ]] || ! grep -q '<failure' "$xml"; then
      failure_xml "$t.sanitizer" "$log" "$RESULTS/sanitize-$t-sanitizer.xml"
    fi
  else
    echo "sanitize: $t clean (ASan + UBSan) $summary"
  fi
done
exit $rc
