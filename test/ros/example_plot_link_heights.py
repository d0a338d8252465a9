#!/usr/bin/python3
"""rostest: examples/plot_link_heights.py writes a valid, non-empty PNG of a recorded fall."""
import os
import re
import struct
import sys
import tempfile
import unittest

import rospy
import rostest

from example_run import FLOAT, numbers_after, run_example


def png_size(path):
    """(width, height) from a PNG's IHDR chunk; raises ValueError when it is no PNG."""
    with open(path, "rb") as f:
        head = f.read(24)
    if head[:8] != b"\x89PNG\r\n\x1a\n" or head[12:16] != b"IHDR":
        raise ValueError("%s is not a PNG" % path)
    return struct.unpack(">II", head[16:24])


class PlotLinkHeights(unittest.TestCase):
    def test_writes_png(self):
        rospy.wait_for_service("/ragdoll_sim/step", timeout=30.0)
        with tempfile.TemporaryDirectory() as tmp:
            png = os.path.join(tmp, "heights.png")
            code, out, err = run_example("plot_link_heights.py", png, "--duration", 1.0)
            self.assertEqual(code, 0, out + err)
            self.assertTrue(os.path.isfile(png), out + err)
            width, height = png_size(png)
            self.assertGreater(width, 100)
            self.assertGreater(height, 100)
            self.assertGreater(os.path.getsize(png), 10000)  # lines, not a blank canvas
            import matplotlib
            matplotlib.use("Agg")
            import matplotlib.image
            pixels = matplotlib.image.imread(png)
            self.assertGreater(float(pixels.std()), 0.01)
        counts = numbers_after("wrote %s:" % png, out)
        self.assertTrue(counts and counts[0] >= 10, out)  # links
        samples = numbers_after("links,", out)
        self.assertTrue(samples and samples[0] >= 10, out)
        # The ragdoll fell: its highest link went down.
        m = re.search(r"highest link at the start: (\S+), " + FLOAT + " m; at the end " + FLOAT,
                      out)
        self.assertIsNotNone(m, out)
        self.assertLess(float(m.group(3)), float(m.group(2)) - 0.1, out)


if __name__ == "__main__":
    rospy.init_node("example_plot_link_heights_test")
    rostest.rosrun("ragdoll_sim", "example_plot_link_heights", PlotLinkHeights, sys.argv)
