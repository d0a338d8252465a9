#!/usr/bin/python3
"""Record every link's height over a fall from ~link_states and plot it to a PNG.

Notebook-style: the `# %%` cells run one by one in Jupyter, VS Code or Spyder (set ARGS in
the first cell there), or all at once from the command line. With a node up:
    roslaunch ragdoll_sim sim.launch rviz:=false paused:=true
    rosrun ragdoll_sim plot_link_heights.py heights.png             # 1.5 s of sim time
    examples/plot_link_heights.py heights.png                       # the same, from the source tree
    rosrun ragdoll_sim plot_link_heights.py heights.png --duration 3 --node /sim_a/ragdoll_sim

The node is paused, its ragdolls put back at their spawn poses (~reset) and stepped (~step)
while the link heights (z of each link origin, m) are recorded against sim time; a node that
was running is unpaused at the end.
"""
# %% Settings
import argparse
import sys
import threading
import time

import matplotlib

matplotlib.use("Agg")  # files only: no display needed
import matplotlib.pyplot as plt  # noqa: E402
import rospy  # noqa: E402
from ragdoll_sim.msg import LinkStates  # noqa: E402
from ragdoll_sim.srv import Step  # noqa: E402
from std_srvs.srv import Empty  # noqa: E402

parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
parser.add_argument("png", help="the PNG file to write")
parser.add_argument("--node", default="/ragdoll_sim", help="the node's private namespace")
parser.add_argument("--duration", type=float, default=1.5, help="s of sim time to record")
parser.add_argument("--sample", type=float, default=0.02, help="s of sim time per ~step call")
parser.add_argument("--timeout", type=float, default=10.0, help="s to wait for the node")
ARGS = parser.parse_args(rospy.myargv(sys.argv)[1:])
NODE = ARGS.node.rstrip("/")

# %% Connect to the node and start recording ~link_states
rospy.init_node("plot_link_heights", anonymous=True)
rospy.wait_for_service(NODE + "/step", timeout=ARGS.timeout)
step = rospy.ServiceProxy(NODE + "/step", Step, persistent=True)  # one connection for many calls
pause, unpause, reset = (rospy.ServiceProxy(NODE + "/" + n, Empty)
                         for n in ("pause", "unpause", "reset"))
was_paused = step(steps=0).success  # refused while the simulation runs
pause()

lock = threading.Lock()
samples = []  # (stamp in s, {"ragdoll/link": z})


def on_link_states(msg):
    """Keeps each message's link heights with its stamp."""
    heights = {"%s/%s" % (r, l): p.position.z for r, l, p in zip(msg.ragdoll, msg.link, msg.pose)}
    with lock:
        samples.append((msg.header.stamp.to_sec(), heights))


sub = rospy.Subscriber(NODE + "/link_states", LinkStates, on_link_states, queue_size=100)
deadline = time.monotonic() + ARGS.timeout
while sub.get_num_connections() == 0 and time.monotonic() < deadline:
    time.sleep(0.01)

# %% Run the fall: back to the spawn pose, then step while the node publishes
reset()
rate = float(rospy.get_param(NODE + "/physics_rate", 1000.0))
chunk = max(1, int(round(ARGS.sample * rate)))
left = int(round(ARGS.duration * rate))
while left > 0:
    res = step(steps=min(chunk, left))
    if not res.success:
        sys.exit("plot_link_heights: ~step refused: " + res.message)
    left -= res.steps_done
    with lock:
        seen = len(samples)
    wait_until = time.monotonic() + 0.2  # the node publishes at ~publish_rate (wall)
    while time.monotonic() < wait_until:
        with lock:
            if len(samples) > seen:
                break
        time.sleep(0.002)
time.sleep(0.1)
sub.unregister()
if not was_paused:
    unpause()
with lock:
    data = sorted(samples, key=lambda s: s[0])
if len(data) < 2:
    sys.exit("plot_link_heights: only %d ~link_states message(s) in %.2f s of sim time"
             % (len(data), ARGS.duration))

# %% Plot the heights against sim time
t0 = data[0][0]
links = sorted(data[0][1])
fig, ax = plt.subplots(figsize=(8, 5))
for link in links:
    ax.plot([t - t0 for t, _ in data], [h.get(link, float("nan")) for _, h in data],
            label=link, linewidth=1)
ax.set_xlabel("sim time since the first sample (s)")
ax.set_ylabel("link origin height z (m)")
ax.set_title("link heights over %.2f s of a fall (%s)" % (data[-1][0] - t0, NODE))
ax.grid(True, alpha=0.3)
ax.legend(fontsize=6, ncol=2, loc="upper right")
fig.tight_layout()
fig.savefig(ARGS.png, dpi=100)
print("wrote %s: %d links, %d samples over %.3f s of sim time"
      % (ARGS.png, len(links), len(data), data[-1][0] - t0))
top = max(links, key=lambda l: data[0][1][l])
print("highest link at the start: %s, %.3f m; at the end %.3f m"
      % (top, data[0][1][top], data[-1][1].get(top, float("nan"))))
