#!/usr/bin/python3
"""rostest: launch/multi_host.launch with both machines on this host. Both sims run apart: each
has its TF tree under its ~frame_prefix (objects of the same name too), each namespace's
services and commands act on its own ragdoll only, and no topic or frame is published by both."""
import math
import sys
import threading
import time
import unittest

import rosgraph
import rospy
import rostest
from geometry_msgs.msg import Pose
from ragdoll_sim.msg import ApplyImpulse
from ragdoll_sim.srv import GetLinkState, SpawnObject, Step
from std_srvs.srv import Empty
from tf2_msgs.msg import TFMessage

SIMS = ("sim_a", "sim_b")


class TfLog:
    """Every /tf child frame with its parent and the nodes that published it."""

    def __init__(self):
        self.lock = threading.Lock()
        self.frames = {}  # child -> (parent, {callerid})
        self.sub = rospy.Subscriber("/tf", TFMessage, self.on_tf, queue_size=100)

    def on_tf(self, msg):
        who = msg._connection_header.get("callerid", "?")
        with self.lock:
            for t in msg.transforms:
                parent, nodes = self.frames.setdefault(t.child_frame_id, (t.header.frame_id, set()))
                nodes.add(who)

    def snapshot(self):
        with self.lock:
            return {k: (p, set(n)) for k, (p, n) in self.frames.items()}


def proxies(sim):
    """The services of the node in namespace `sim`."""
    node = "/%s/ragdoll_sim/" % sim
    rospy.wait_for_service(node + "step", timeout=30.0)
    return {"step": rospy.ServiceProxy(node + "step", Step),
            "pause": rospy.ServiceProxy(node + "pause", Empty),
            "link": rospy.ServiceProxy(node + "get_link_state", GetLinkState),
            "spawn_object": rospy.ServiceProxy(node + "spawn_object", SpawnObject)}


def speed(res):
    v = res.twist.linear
    return math.sqrt(v.x * v.x + v.y * v.y + v.z * v.z)


class MultiHost(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tf = TfLog()
        cls.srv = {sim: proxies(sim) for sim in SIMS}

    def step_until_tf(self, sim, frame):
        """Steps `sim` until /tf carried `frame` (the node publishes at ~publish_rate)."""
        deadline = time.monotonic() + 5.0
        while frame not in self.tf.snapshot() and time.monotonic() < deadline:
            self.assertTrue(self.srv[sim]["step"](steps=10).success)
            time.sleep(0.05)
        return self.tf.snapshot()

    def test_1_tf_trees_apart(self):
        for sim in SIMS:
            frames = self.step_until_tf(sim, sim + "/head")
            mine = {k: p for k, (p, _) in frames.items() if k.startswith(sim + "/")}
            self.assertIn(sim + "/pelvis", mine)
            self.assertGreaterEqual(len(mine), 15, sorted(mine))
            self.assertEqual(set(mine.values()), {"world"}, mine)
        frames = self.tf.snapshot()
        bare = [k for k in frames if not k.startswith(SIMS)]
        self.assertEqual(bare, [], "frames without a sim's prefix")
        shared = {k: n for k, (_, n) in frames.items() if len(n) > 1}
        self.assertEqual(shared, {}, "frames published by two nodes")
        # Side by side: sim_a at y = -1, sim_b at y = +1 (spacing 2 m).
        ya = self.srv["sim_a"]["link"](ragdoll="", link="pelvis").pose.position.y
        yb = self.srv["sim_b"]["link"](ragdoll="", link="pelvis").pose.position.y
        self.assertAlmostEqual(ya, -1.0, delta=1e-6)
        self.assertAlmostEqual(yb, 1.0, delta=1e-6)

    def test_2_services_act_on_their_own_sim(self):
        a, b = self.srv["sim_a"], self.srv["sim_b"]
        ta, tb = a["step"](steps=0).sim_time, b["step"](steps=0).sim_time
        self.assertTrue(a["step"](steps=100).success)
        self.assertAlmostEqual(a["step"](steps=0).sim_time, ta + 0.1, delta=1e-9)
        self.assertEqual(b["step"](steps=0).sim_time, tb, "sim_b advanced with sim_a's ~step")
        # An impulse on sim_b's head moves sim_b's head only (both paused: nothing else moves).
        heads = {s: self.srv[s]["link"](ragdoll="", link="head") for s in SIMS}
        pub = rospy.Publisher("/sim_b/ragdoll_sim/apply_impulse", ApplyImpulse, queue_size=1)
        deadline = time.monotonic() + 5.0
        while pub.get_num_connections() == 0 and time.monotonic() < deadline:
            time.sleep(0.01)
        cmd = ApplyImpulse(link="head", frame="world", point=heads["sim_b"].com)
        cmd.impulse.x = 5.0
        pub.publish(cmd)
        while time.monotonic() < deadline:
            if speed(b["link"](ragdoll="", link="head")) > 0.5:
                break
            time.sleep(0.02)
        self.assertGreater(speed(b["link"](ragdoll="", link="head")), 0.5)
        self.assertEqual(a["link"](ragdoll="", link="head").twist, heads["sim_a"].twist)

    def test_3_same_object_name_in_both(self):
        for sim in SIMS:
            pose = Pose()
            pose.position.z, pose.orientation.w = 3.0, 1.0
            res = self.srv[sim]["spawn_object"](name="crate", shape="box",
                                                dimensions=[0.3, 0.3, 0.3], pose=pose, mass=5.0)
            self.assertTrue(res.success, res.message)
            frames = self.step_until_tf(sim, sim + "/crate/link")
            self.assertIn(sim + "/crate/link", frames, sorted(frames))
        frames = self.tf.snapshot()
        self.assertNotIn("crate/link", frames)
        for sim in SIMS:
            self.assertEqual(frames[sim + "/crate/link"][1], {"/%s/ragdoll_sim" % sim})

    def test_4_no_shared_topics(self):
        master = rosgraph.Master("/multi_host_test")
        publishers = {t: set(n) for t, n in master.getSystemState()[0]}
        subscribers = {t: set(n) for t, n in master.getSystemState()[1]}
        for topic in ("/clock", "/joint_states"):
            self.assertNotIn(topic, publishers, "%s has publishers" % topic)
        self.assertNotIn("/clicked_point", subscribers)
        for sim in SIMS:
            node = "/%s/ragdoll_sim" % sim
            for topic in ("/%s/joint_states" % sim, node + "/markers", node + "/link_states"):
                self.assertEqual(publishers.get(topic), {node}, topic)
            for topic in ("/%s/clicked_point" % sim, node + "/apply_impulse"):
                self.assertEqual(subscribers.get(topic), {node}, topic)
        self.assertEqual(publishers["/tf"] & {"/sim_a/ragdoll_sim", "/sim_b/ragdoll_sim"},
                         {"/sim_a/ragdoll_sim", "/sim_b/ragdoll_sim"})
        for sim in SIMS:
            self.assertTrue(rospy.has_param("/%s/robot_description" % sim))


if __name__ == "__main__":
    rospy.init_node("multi_host_test")
    rostest.rosrun("ragdoll_sim", "multi_host", MultiHost, sys.argv)
