#!/usr/bin/env bash
# Builds the ROS-free core and bench_ragdoll in Release and runs scenes a, b, c on the peers'
# ragdoll15.urdf (../shared/peers, or PEERS_DIR). Result lines go to stdout.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
PEERS_DIR="${PEERS_DIR:-$ROOT/../shared/peers}"
BUILD="$WS/bench"
cmake -S "$ROOT" -B "$BUILD" -DRAGDOLL_SIM_CORE_ONLY=ON -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$BUILD" -j2 --target bench_ragdoll >/dev/null
for s in a b c; do "$BUILD/bench_ragdoll" "$s" --urdf "$PEERS_DIR/ragdoll15.urdf"; done
