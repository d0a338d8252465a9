#!/usr/bin/python3
"""Drive one fall down the shipped stairs through the node's services; print the head's HIC15.

With the node running worlds/stairs.world, paused or not:
    roslaunch ragdoll_sim stairs.launch rviz:=false paused:=true
    rosrun ragdoll_sim stairs_fall_hic.py                  # 3 s of sim time
    examples/stairs_fall_hic.py                            # the same, from the source tree
    rosrun ragdoll_sim stairs_fall_hic.py --push 2.0 --tip 1.0 --duration 5

It pauses the node, puts the ragdoll back at its spawn pose on the top landing (~reset), gives
it a push towards the stairs (~set_ragdoll_state: a rigid twist), starts a new injury record
(~injury/reset), runs the fall with ~step, and ends the record (~injury/reset) unless the fall
ended at rest on its own (~injury, reason "rest"). It prints the head's HIC15, HIC36 and peak
g from that record, and the head's hardest impact (~impacts): what it hit and where. A node that
was running is unpaused at the end.
"""
import argparse
import math
import sys
import threading
import time

import rospy
from geometry_msgs.msg import Pose, Twist
from ragdoll_sim.msg import Impact, Injury
from ragdoll_sim.srv import ResetInjury, SetRagdollState, Step
from std_srvs.srv import Empty


def quaternion(roll, pitch, yaw):
    """(x, y, z, w) of the rotation R = Rz(yaw) Ry(pitch) Rx(roll), as URDF's rpy."""
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy)


def spawn_pose(node):
    """The launch-time ragdoll's spawn pose from the node's ~spawn/* parameters."""
    p = {k: float(rospy.get_param("%s/spawn/%s" % (node, k), d))
         for k, d in (("x", 0.0), ("y", 0.0), ("z", 1.1), ("roll", 0.0), ("pitch", 0.0),
                      ("yaw", 0.0))}
    pose = Pose()
    pose.position.x, pose.position.y, pose.position.z = p["x"], p["y"], p["z"]
    q = pose.orientation
    q.x, q.y, q.z, q.w = quaternion(p["roll"], p["pitch"], p["yaw"])
    return pose


class Recorder:
    """Collects the node's ~injury records and ~impacts while the fall runs."""

    def __init__(self, node):
        self.lock = threading.Lock()
        self.injuries = []
        self.impacts = []
        self.subs = [rospy.Subscriber(node + "/injury", Injury, self._on, (self.injuries,)),
                     rospy.Subscriber(node + "/impacts", Impact, self._on, (self.impacts,))]

    def _on(self, msg, args):
        with self.lock:
            args[0].append(msg)

    def wait_connected(self, timeout):
        """Impacts are detected only while subscribed: wait until the node has our subscriptions."""
        deadline = time.monotonic() + timeout
        while any(s.get_num_connections() == 0 for s in self.subs):
            if time.monotonic() > deadline:
                raise RuntimeError("the node does not publish ~injury and ~impacts")
            time.sleep(0.01)

    def rest_record(self, ragdoll):
        """The record of `ragdoll` that ended at rest, or None."""
        with self.lock:
            return next((m for m in self.injuries if m.ragdoll == ragdoll and m.reason == "rest"),
                        None)

    def hardest_head_impact(self, ragdoll, head):
        """The impact on the head with the largest peak force, or None."""
        with self.lock:
            hits = [m for m in self.impacts if m.ragdoll == ragdoll and m.link == head]
        return max(hits, key=lambda m: m.peak_force) if hits else None


def call(proxy, what, **kw):
    """Calls a service whose answer has `success`; raises naming it when it refused."""
    res = proxy(**kw)
    if hasattr(res, "success") and not res.success:
        raise RuntimeError("%s refused: %s" % (what, res.message))
    return res


def main(argv=None):
    """Runs the fall and prints the head's injury numbers; returns the exit code."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--node", default="/ragdoll_sim", help="the node's private namespace")
    parser.add_argument("--ragdoll", default="", help='ragdoll name ("" = the launch-time one)')
    parser.add_argument("--push", type=float, default=1.5, help="velocity along +x (m/s)")
    parser.add_argument("--tip", type=float, default=1.5, help="pitch rate (rad/s)")
    parser.add_argument("--duration", type=float, default=3.0, help="s of sim time at most")
    parser.add_argument("--timeout", type=float, default=10.0, help="s to wait for the node")
    args = parser.parse_args(rospy.myargv(argv)[1:] if argv is None else argv)
    rospy.init_node("stairs_fall_hic", anonymous=True)
    node = args.node.rstrip("/")

    rospy.wait_for_service(node + "/injury/reset", timeout=args.timeout)
    srv = {name: rospy.ServiceProxy(node + "/" + name, cls, persistent=name == "step")
           for name, cls in (("pause", Empty), ("unpause", Empty), ("reset", Empty),
                             ("step", Step), ("set_ragdoll_state", SetRagdollState),
                             ("injury/reset", ResetInjury))}
    was_paused = srv["step"](steps=0).success  # refused while the simulation runs
    srv["pause"]()
    recorder = Recorder(node)
    recorder.wait_connected(args.timeout)

    srv["reset"]()
    pose = spawn_pose(node)
    twist = Twist()
    twist.linear.x, twist.angular.y = args.push, args.tip
    call(srv["set_ragdoll_state"], "~set_ragdoll_state", ragdoll=args.ragdoll, pose=pose,
         twist=twist)
    start = call(srv["injury/reset"], "~injury/reset", ragdoll=args.ragdoll).injury
    ragdoll = start.ragdoll
    print("fall: ragdoll '%s' at (%.3f, %.3f, %.3f) m pushed with %.2f m/s along x and %.2f "
          "rad/s about y, at most %.2f s of sim time"
          % (ragdoll, pose.position.x, pose.position.y, pose.position.z, args.push, args.tip,
             args.duration))

    rate = float(rospy.get_param(node + "/physics_rate", 1000.0))
    chunk = max(1, int(round(0.25 * rate)))  # a quarter second per call: a rest record ends it
    left = int(round(args.duration * rate))
    while left > 0 and recorder.rest_record(ragdoll) is None:
        res = call(srv["step"], "~step", steps=min(chunk, left))
        left -= res.steps_done
    time.sleep(0.1)  # the last ~injury message, if the fall ended at rest
    record = recorder.rest_record(ragdoll)
    if record is None:
        record = call(srv["injury/reset"], "~injury/reset", ragdoll=ragdoll).injury
    if not was_paused:
        srv["unpause"]()

    print("injury record of '%s' (reason %s): %.3f to %.3f s of sim time"
          % (ragdoll, record.reason, record.start_time, record.end_time))
    print("head '%s': HIC15 = %.9g (window %.4f to %.4f s), HIC36 = %.9g, peak %.2f g at %.4f s"
          % (record.head_link, record.hic15, record.hic15_t1, record.hic15_t2, record.hic36,
             record.peak_g, record.peak_time))
    hit = recorder.hardest_head_impact(ragdoll, record.head_link)
    if hit is None:
        print("the head hit nothing above ~impacts/min_impulse or ~impacts/min_speed")
    else:
        print("hardest head impact: '%s' at (%.3f, %.3f, %.3f) m, closing speed %.2f m/s, "
              "impulse %.2f N s, peak force %.0f N"
              % (hit.other, hit.point.x, hit.point.y, hit.point.z, hit.closing_speed,
                 hit.impulse, hit.peak_force))
    return 0


if __name__ == "__main__":
    try:
        sys.exit(main())
    except (RuntimeError, rospy.ROSException, rospy.ServiceException) as e:
        print("stairs_fall_hic: %s" % e, file=sys.stderr)
        sys.exit(1)
