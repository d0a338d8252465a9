"""Driver of test_netns, run inside host 1: `ragdoll_batch run` against both hosts' workers.

Usage: fanout_netns_driver.py SCHEDULER SCENARIO RUNS OUT.csv
Waits for the two workers, runs the CLI with --scheduler, then prints the chunks each worker ran.
"""

import os
import subprocess
import sys
import time

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


def main():
    from distributed import Client
    scheduler, scenario, runs, out = sys.argv[1:5]
    with Client(scheduler, timeout=20, set_as_default=False) as client:
        client.wait_for_workers(2, timeout=30)
        workers = sorted(client.scheduler_info()["workers"])
    print(f"scheduler {scheduler}, workers: {', '.join(workers)}")
    cmd = ["ragdoll_batch", "run", os.path.relpath(scenario, ROOT), "--runs", runs,
           "--out", os.path.basename(out), "--scheduler", scheduler]
    print("$ " + " ".join(cmd))
    t0 = time.time()
    r = subprocess.run([sys.executable, os.path.join(ROOT, "scripts", "ragdoll_batch"), "run",
                        scenario, "--runs", runs, "--out", out, "--scheduler", scheduler],
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(r.stdout.rstrip())
    if r.returncode != 0:
        return r.returncode
    elapsed = time.time() - t0
    with Client(scheduler, timeout=20, set_as_default=False) as client:
        done = client.run(lambda dask_worker: dask_worker.state.executed_count)
    print(f"{elapsed:.1f} s; chunks run per worker: "
          + ", ".join(f"{w} {done[w]}" for w in sorted(done)))
    return 0


if __name__ == "__main__":
    sys.exit(main())
