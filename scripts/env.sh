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
