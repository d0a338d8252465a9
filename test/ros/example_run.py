"""Runs one of examples/ as the user would and hands back what it printed (example_* rostests)."""
import os
import re
import subprocess

import rospkg

FLOAT = r"([-+]?(?:\d+\.?\d*(?:[eE][-+]?\d+)?|nan|inf))"


def run_example(name, *args, timeout=30.0):
    """Runs examples/NAME with ARGS under /usr/bin/python3; returns (exit code, stdout, stderr)."""
    path = os.path.join(rospkg.RosPack().get_path("ragdoll_sim"), "examples", name)
    done = subprocess.run(["/usr/bin/python3", path] + [str(a) for a in args],
                          capture_output=True, text=True, timeout=timeout)
    print(done.stdout + done.stderr)  # in the rostest's log
    return done.returncode, done.stdout, done.stderr


def numbers_after(label, text):
    """The floats following `label` (e.g. 'HIC15 =' or 'velocity change: ('), or []."""
    m = re.search(re.escape(label) + r"\s*" + FLOAT + r"(?:\s*,\s*" + FLOAT + r")?(?:\s*,\s*"
                  + FLOAT + r")?", text)
    return [float(g) for g in m.groups() if g is not None] if m else []
