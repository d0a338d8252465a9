#!/usr/bin/python3
"""rostest: examples/poke_head.py on a paused node: the head's velocity changes by J / m_head."""
import math
import re
import sys
import unittest

import rospy
import rostest
from ragdoll_sim.srv import GetLinkState

from example_run import numbers_after, run_example

IMPULSE = 5.0  # N s along +x


def head_mass():
    """The head link's mass (kg) from robot_description."""
    urdf = rospy.get_param("/robot_description")
    link = re.search(r'<link\s+name="head".*?</link>', urdf, re.S).group(0)
    return float(re.search(r'<mass\s+value="([^"]+)"', link).group(1))


class PokeHead(unittest.TestCase):
    def test_poke_changes_head_velocity(self):
        rospy.wait_for_service("/ragdoll_sim/step", timeout=30.0)
        code, out, err = run_example("poke_head.py", "--impulse", IMPULSE, 0, 0)
        self.assertEqual(code, 0, out + err)
        self.assertIn("sent: impulse (5.000, 0.000, 0.000) N s on ragdoll/head", out)
        dv = numbers_after("velocity change: (", out)
        self.assertEqual(len(dv), 3, out)
        # Paused: nothing but the impulse moved the head, which is one body.
        expected = IMPULSE / head_mass()
        self.assertAlmostEqual(dv[0], expected, delta=0.02 * expected, msg=out)
        self.assertLess(math.hypot(dv[1], dv[2]), 1e-6, out)
        # The node's own state agrees with what the example printed.
        res = rospy.ServiceProxy("/ragdoll_sim/get_link_state", GetLinkState)(
            ragdoll="", link="head")
        after = numbers_after("head velocity after:  (", out)
        self.assertAlmostEqual(res.twist.linear.x, after[0], delta=1e-3)


if __name__ == "__main__":
    rospy.init_node("example_poke_head_test")
    rostest.rosrun("ragdoll_sim", "example_poke_head", PokeHead, sys.argv)
