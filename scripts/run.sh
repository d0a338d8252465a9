#!/usr/bin/env bash
# Starts roscore if no master is running, then the simulator (with rviz when $DISPLAY is set).
# WORLD=NAME (a shipped world: launch/NAME.launch when there is one, e.g. stairs, else sim.launch
# world:=NAME) or WORLD=PATH (an SDF world file, made absolute) loads a world.
set -eo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
source "$WS/devel/setup.bash"
set -u

master_online() {
  /usr/bin/python3 -c 'import rosgraph, sys; sys.exit(0 if rosgraph.is_master_online() else 1)' \
    2>/dev/null
}

ROSCORE_PID=""
cleanup() {
  if [[ -n "$ROSCORE_PID" ]]; then
    kill -INT "$ROSCORE_PID" 2>/dev/null || true
    wait "$ROSCORE_PID" 2>/dev/null || true
  fi
}
trap cleanup EXIT

if ! master_online; then
  # roscore ignores the port in ROS_MASTER_URI unless told (default http://localhost:11311)
  PORT="$(/usr/bin/python3 -c 'import rosgraph, urllib.parse as u; print(u.urlparse(rosgraph.get_master_uri()).port or 11311)')"
  echo "run: starting roscore on port $PORT (log: $WS/roscore.log)"
  roscore -p "$PORT" >"$WS/roscore.log" 2>&1 &
  ROSCORE_PID=$!
  for _ in $(seq 100); do
    master_online && break
    kill -0 "$ROSCORE_PID" 2>/dev/null || { echo "run: roscore died, see $WS/roscore.log"; exit 1; }
    sleep 0.2
  done
  master_online || { echo "run: roscore did not come up"; exit 1; }
fi

RVIZ=false
if [[ -n "${DISPLAY:-}" ]]; then RVIZ=true; fi
WORLD="${WORLD:-}"
if [[ -z "$WORLD" ]]; then
  roslaunch ragdoll_sim sim.launch rviz:=$RVIZ "$@"
elif [[ "$WORLD" != */* && -f "$ROOT/launch/$WORLD.launch" ]]; then
  roslaunch ragdoll_sim "$WORLD.launch" rviz:=$RVIZ "$@"
elif [[ "$WORLD" == */* ]]; then
  roslaunch ragdoll_sim sim.launch rviz:=$RVIZ world:="$(realpath -m "$WORLD")" "$@"
else
  roslaunch ragdoll_sim sim.launch rviz:=$RVIZ world:="$WORLD" "$@"
fi
