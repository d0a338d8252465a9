#!/usr/bin/python3
"""Poke the running ragdoll_sim node's ragdoll on the head and show how the head responds.

Finds the node (its ~step service) and its launch-time ragdoll (~ragdoll_name, else the URDF
robot name of robot_description in the node's namespace), reads the head's velocity with
~get_link_state, publishes one impulse at the head's centre of mass on ~apply_impulse and reads
the velocity again once the impulse has acted. A paused node applies impulses too (they change
the link's momentum at once; the joints act at the next step), so there the change is exactly
impulse / head mass; on a running node the joints and contacts act on it as well.

Run, with a node up (e.g. `roslaunch ragdoll_sim sim.launch rviz:=false paused:=true`):
    rosrun ragdoll_sim poke_head.py                      # 5 N s along +x on the head
    examples/poke_head.py                                # the same, from the source tree
    rosrun ragdoll_sim poke_head.py --impulse 0 3 0 --link head --node /sim_a/ragdoll_sim
"""
import argparse
import math
import re
import sys
import time

import rospy
from ragdoll_sim.msg import ApplyImpulse
from ragdoll_sim.srv import GetLinkState


def ragdoll_name(node):
    """The name of the node's launch-time ragdoll: ~ragdoll_name, else its URDF robot name."""
    name = rospy.get_param(node + "/ragdoll_name", "")
    if name:
        return name
    urdf = rospy.get_param(rospy.names.namespace(node) + "robot_description", "")
    found = re.search(r"<robot[^>]*\bname\s*=\s*[\"']([^\"']+)", urdf)
    return found.group(1) if found else ""


def link_state(get_link, ragdoll, link):
    """The link origin's linear velocity (m/s, world), its centre of mass and the sim time (s)."""
    res = get_link(ragdoll=ragdoll, link=link)
    if not res.success:
        raise RuntimeError("~get_link_state refused: " + res.message)
    v = res.twist.linear
    return (v.x, v.y, v.z), res.com, res.sim_time


def main(argv=None):
    """Pokes the head once; prints the impulse sent and the head's velocity before and after."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--node", default="/ragdoll_sim", help="the node's private namespace")
    parser.add_argument("--link", default="head", help="the link to poke")
    parser.add_argument("--impulse", type=float, nargs=3, default=[5.0, 0.0, 0.0],
                        metavar=("X", "Y", "Z"), help="impulse in world axes (N s)")
    parser.add_argument("--timeout", type=float, default=10.0, help="s to wait for the node")
    args = parser.parse_args(rospy.myargv(argv)[1:] if argv is None else argv)
    rospy.init_node("poke_head", anonymous=True)
    node = args.node.rstrip("/")

    rospy.wait_for_service(node + "/step", timeout=args.timeout)
    ragdoll, link = ragdoll_name(node), args.link
    if not ragdoll:
        raise RuntimeError("%s has no ~ragdoll_name and no robot_description" % node)
    get_link = rospy.ServiceProxy(node + "/get_link_state", GetLinkState, persistent=True)
    before, com, t0 = link_state(get_link, ragdoll, link)

    pub = rospy.Publisher(node + "/apply_impulse", ApplyImpulse, queue_size=1)
    deadline = time.monotonic() + args.timeout
    while pub.get_num_connections() == 0:  # a message sent before the node connects is lost
        if time.monotonic() > deadline:
            raise RuntimeError("the node does not subscribe to %s/apply_impulse" % node)
        time.sleep(0.01)
    # At the centre of mass: the head moves without spinning (a world point (0, 0, 0) would be
    # the world's origin, far from the head).
    cmd = ApplyImpulse(ragdoll=ragdoll, link=link, frame="world", point=com)
    cmd.impulse.x, cmd.impulse.y, cmd.impulse.z = args.impulse
    pub.publish(cmd)
    print("sent: impulse (%.3f, %.3f, %.3f) N s on %s/%s at its centre of mass (%.3f, %.3f, %.3f)"
          " m, sim time %.3f s" % (tuple(args.impulse) + (ragdoll, link, com.x, com.y, com.z, t0)))

    # The node applies it at its next loop iteration: wait until the velocity moved.
    after, _, t1 = link_state(get_link, ragdoll, link)
    while math.dist(after, before) < 1e-6 and time.monotonic() < deadline:
        time.sleep(0.01)
        after, _, t1 = link_state(get_link, ragdoll, link)
    dv = tuple(a - b for a, b in zip(after, before))
    print("head velocity before: (%.4f, %.4f, %.4f) m/s" % before)
    print("head velocity after:  (%.4f, %.4f, %.4f) m/s at sim time %.3f s" % (after + (t1,)))
    print("velocity change: (%.4f, %.4f, %.4f) m/s, |dv| = %.4f m/s"
          % (dv + (math.sqrt(sum(d * d for d in dv)),)))
    return 0 if math.dist(after, before) >= 1e-6 else 1


if __name__ == "__main__":
    try:
        sys.exit(main())
    except (RuntimeError, rospy.ROSException) as e:
        print("poke_head: %s" % e, file=sys.stderr)
        sys.exit(1)
