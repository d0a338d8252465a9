#!/usr/bin/env bash
# Regenerates docs/images/rviz.png, the README's screenshot: the active ragdoll and rviz on a
# private Xvfb display and ROS port (so that it never meets a running rostest), one shot just
# after a push on the torso. Needs `make build`; usage: scripts/screenshot.sh [OUT.png]
set -eo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/env.sh"
source "$WS/devel/setup.bash"
set -u
OUT="${1:-$ROOT/docs/images/rviz.png}"
export ROS_MASTER_URI="http://localhost:${SCREENSHOT_PORT:-11471}" LIBGL_ALWAYS_SOFTWARE=1
TMP="$(mktemp -d)"
trap 'kill $(jobs -p) 2>/dev/null; wait 2>/dev/null; rm -rf "$TMP"' EXIT
# -displayfd: Xvfb picks a free display and writes its number to the file.
Xvfb -displayfd 3 -screen 0 1400x1000x24 3>"$TMP/display" >"$TMP/xvfb.log" 2>&1 &
for _ in $(seq 50); do [[ -s "$TMP/display" ]] && break; sleep 0.2; done
export DISPLAY=":$(cat "$TMP/display")"
roslaunch -p "${ROS_MASTER_URI##*:}" ragdoll_sim active_ragdoll.launch rviz:=true \
  >"$TMP/launch.log" 2>&1 &
sleep "${SCREENSHOT_WAIT:-20}"   # master, node, rviz's software GL and the first frames
rostopic pub -1 /ragdoll_sim/apply_impulse ragdoll_sim/ApplyImpulse \
  '{link: torso, frame: link, point: {x: 0.1, z: 0.22}, impulse: {x: -15.0}}' >/dev/null &
sleep "${SCREENSHOT_AFTER:-1.3}"   # rostopic's start-up, then the push's arrow (it fades in 1 s)
mkdir -p "$(dirname "$OUT")"
import -window root "$TMP/root.png"
convert "$TMP/root.png" -trim +repage "$OUT"   # the rviz window without the empty screen
echo "screenshot: $OUT"
