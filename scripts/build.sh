#!/usr/bin/env bash
# Creates the catkin workspace .ws/ (src/ragdoll_sim -> repository root) and builds it.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
mkdir -p "$WS/src"
if [[ "$(readlink "$WS/src/ragdoll_sim" 2>/dev/null)" != "$ROOT" ]]; then
  rm -rf "$WS/src/ragdoll_sim"
  ln -s "$ROOT" "$WS/src/ragdoll_sim"
fi
cd "$WS"
catkin_make -DPYTHON_EXECUTABLE=/usr/bin/python3 -j2 "$@"
