#!/usr/bin/env bash
# Builds and runs all tests (gtests and rostests) of the workspace, the sanitizer build of the
# ROS-free gtests (sanitize.sh), a short fuzz run (fuzz.sh) and the journal check of the
# documents (check_journal.py), prints the results and a final
# line "tests: N passed, M failed, K skipped". Exits non-zero on any failure or error.
set -uo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
cd "$WS"
rm -rf "$WS/build/test_results"
if ! catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -j2 run_tests; then
  echo "test: catkin_make run_tests failed (build error?)"
  exit 1
fi
# The ROS-free gtests again under ASan + UBSan, and a short libFuzzer run of each fuzz target
# over its seed corpus; both leave JUnit reports next to catkin's, counted below.
scripts_rc=0
"$ROOT/scripts/sanitize.sh" "$WS/build/test_results/sanitize" || scripts_rc=1
"$ROOT/scripts/fuzz.sh" --runs "${FUZZ_TEST_RUNS:-2000}" --junit "$WS/build/test_results/fuzz" ||
  scripts_rc=1
# The user documents and the sources must not read like a lab journal (commit hashes, "session").
"$ROOT/scripts/check_journal.py" --junit "$WS/build/test_results/journal" || scripts_rc=1
results="$(catkin_test_results --all "$WS/build/test_results")"
rc=$?
[[ $scripts_rc -ne 0 ]] && rc=1
echo "$results"
# Count test cases from the JUnit reports (catkin_test_results counts gtest files twice).
# The failed cases are named last, next to the count, where the tail of a CI log shows them.
counts="$(/usr/bin/python3 - "$WS/build/test_results" <<'PY'
import glob, os, sys, xml.etree.ElementTree as ET
p = f = s = 0
failed = []
for path in sorted(glob.glob(sys.argv[1] + "/**/*.xml", recursive=True)):
    wrapper = "/rostest-" in path  # one case per launch; its test cases are in rosunit-*.xml
    for case in ET.parse(path).getroot().iter("testcase"):
        if case.find("failure") is not None or case.find("error") is not None:
            f += 1
            bad = case.find("failure") if case.find("failure") is not None else case.find("error")
            why = " ".join((bad.get("message") or bad.text or "").split())[:160]
            failed.append(f"{os.path.relpath(path, sys.argv[1])}: {case.get('classname', '')}."
                          f"{case.get('name', '')}: {why}")
        elif wrapper: continue
        elif case.find("skipped") is not None or case.get("status") == "notrun": s += 1
        else: p += 1
for name in failed[:10]:
    print("failed:", name)
print(p, f, s)
PY
)"
grep '^failed: ' <<<"$counts"
read -r passed failed skipped < <(tail -n 1 <<<"$counts")
if [[ "$((passed + failed))" -eq 0 ]]; then
  echo "test: no tests ran"
  rc=1
fi
echo "tests: $passed passed, $failed failed, $skipped skipped"
exit $rc
