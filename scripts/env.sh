# Sourced by the other scripts: repository root, workspace, and a PATH with the system python
# (Debian's ROS python modules live there; a pyenv python first on PATH lacks them).
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
WS="$ROOT/.ws"
export PATH="/usr/bin:$PATH"

# build_bench_ragdoll DIR "-DCMAKE_CXX_FLAGS...=...": the ROS-free core and bench/bench_ragdoll,
# CMake Release, into DIR (bench.sh, flops.sh, bench_ensemble.sh).
build_bench_ragdoll() {
  cmake -S "$ROOT" -B "$1" -DRAGDOLL_SIM_CORE_ONLY=ON -DCMAKE_BUILD_TYPE=Release "$2" >/dev/null
  cmake --build "$1" -j2 --target bench_ragdoll >/dev/null
}

# fresh_copies DIR FILE...: DIR emptied, then a fresh copy of each FILE in it (basenames kept).
# Where a binary's pages land in memory moves its speed by up to 5 % (the same bytes in two
# files): the timed runs of each round take copies made for it, which spreads that over the
# rounds instead of giving each binary one placement for the whole sitting (bench.sh,
# bench_compare.sh).
fresh_copies() {
  local dir="$1"
  shift
  rm -rf "$dir"
  mkdir -p "$dir"
  cp "$@" "$dir/"
}

# build_asan TARGET...: the ROS-free libraries, gtests and libFuzzer targets built with clang
# (much quicker to compile here than gcc), ASan and UBSan in $ASAN_BUILD, one build for
# sanitize.sh and fuzz.sh. Every file carries libFuzzer's edge counters, which the gtests link
# without the fuzzer driver, but not its comparison hooks (trace-cmp), which slow the solver's
# gtests far more. Logs: $ASAN_BUILD.cmake.log, $ASAN_BUILD.build.log.
ASAN_BUILD="$WS/asan"
build_asan() {
  local cxx san="-fsanitize=address,undefined -fsanitize-coverage=inline-8bit-counters,pc-table"
  cxx="$(command -v clang++-14 || command -v clang++)" || { echo "asan build: no clang++"; return 1; }
  # -O2: the solver near Release speed under ASan; -gline-tables-only: all a report's backtrace
  # needs (files and lines), at less compile time.
  if ! cmake -S "$ROOT" -B "$ASAN_BUILD" -DCMAKE_CXX_COMPILER="$cxx" -DRAGDOLL_SIM_CORE_ONLY=ON \
        -DRAGDOLL_SIM_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
        -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O2 -gline-tables-only" \
        -DCMAKE_CXX_FLAGS="$san -fno-omit-frame-pointer -fno-sanitize-recover=all" \
        -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
        -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" >"$ASAN_BUILD.cmake.log" 2>&1 ||
     ! cmake --build "$ASAN_BUILD" -j2 --target "$@" >"$ASAN_BUILD.build.log" 2>&1; then
    echo "asan build failed (see $ASAN_BUILD.cmake.log, $ASAN_BUILD.build.log):"
    tail -n 30 "$ASAN_BUILD.build.log" 2>/dev/null
    return 1
  fi
}
