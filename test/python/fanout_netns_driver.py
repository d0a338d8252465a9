"""Driver of test_netns, run inside host 1: waits for both hosts' workers, runs the falls.

Usage: fanout_netns_driver.py SCHEDULER N OUT.csv
"""

import sys
import time

import fanout_support as fs


def main():
    from distributed import Client
    from ragdoll_sim.batch import fanout
    scheduler, n, out = sys.argv[1], int(sys.argv[2]), sys.argv[3]
    with Client(scheduler, timeout=20, set_as_default=False) as client:
        client.wait_for_workers(2, timeout=30)
        workers = sorted(client.scheduler_info()["workers"])
    print(f"scheduler {scheduler}: workers {', '.join(workers)}")
    rows = []
    t0 = time.time()
    fanout.run(fs.scenario(), range(n), rows.extend, scheduler=scheduler, task=fs.run_chunk)
    elapsed = time.time() - t0
    fs.write_csv(rows, out)
    with Client(scheduler, timeout=20, set_as_default=False) as client:
        done = client.run(lambda dask_worker: dask_worker.state.executed_count)
    print(f"{n} falls in {elapsed:.1f} s; chunks per worker: "
          + ", ".join(f"{w} {done[w]}" for w in sorted(done)))


if __name__ == "__main__":
    main()
