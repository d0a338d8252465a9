#!/usr/bin/python3
"""rostest: examples/stairs_fall_hic.py on stairs.launch: the HIC15 it prints is a positive
finite number, the one of the injury record the node published."""
import math
import sys
import threading
import time
import unittest

import rospy
import rostest
from ragdoll_sim.msg import Injury

from example_run import numbers_after, run_example


class StairsFallHic(unittest.TestCase):
    def test_printed_hic_is_the_nodes_record(self):
        records = []
        lock = threading.Lock()

        def on_injury(msg):
            with lock:
                records.append(msg)

        rospy.Subscriber("/ragdoll_sim/injury", Injury, on_injury)
        rospy.wait_for_service("/ragdoll_sim/injury/reset", timeout=30.0)
        time.sleep(0.5)  # our subscription connected
        code, out, err = run_example("stairs_fall_hic.py", "--duration", 2.0)
        self.assertEqual(code, 0, out + err)
        hic = numbers_after("HIC15 =", out)
        peak = numbers_after("peak", out)
        self.assertEqual(len(hic), 1, out)
        self.assertTrue(math.isfinite(hic[0]) and hic[0] > 0.0, out)
        self.assertTrue(peak and peak[0] > 1.0, out)
        time.sleep(0.3)
        with lock:
            last = records[-1] if records else None
        self.assertIsNotNone(last, "no ~injury record published")
        self.assertIn(last.reason, ("rest", "reset"))
        # The record that ended the fall is the last one the node published.
        self.assertAlmostEqual(hic[0], last.hic15, delta=1e-6 * max(1.0, last.hic15), msg=out)
        self.assertIn("head '%s': HIC15" % last.head_link, out)


if __name__ == "__main__":
    rospy.init_node("example_stairs_fall_hic_test")
    rostest.rosrun("ragdoll_sim", "example_stairs_fall_hic", StairsFallHic, sys.argv)
