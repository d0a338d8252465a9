"""A dask-worker killed mid-run loses nothing: its chunks rerun on the other worker.

Starts a dask-scheduler and 2 dask-worker processes on 127.0.0.1, runs 60 short falls through
fanout.run in chunks of 3, SIGKILLs one worker's process group (nanny and worker) while it holds
a chunk that has not come back, and checks that every index arrives exactly once with the rows
of the single-process run.
"""

import collections
import os
import time

import fanout_support as fs
from ragdoll_sim.batch import fanout

N = 60
CHUNK = 3


def test_killed_worker_loses_nothing(tmp_path):
    scen = fs.scenario()
    log = str(tmp_path / "chunks.log")
    port = fs.free_port()
    address = f"tcp://127.0.0.1:{port}"
    env = fs.worker_env({fs.LOG_ENV: log, "DASK_DISTRIBUTED__SCHEDULER__ALLOWED_FAILURES":
                         str(fanout.ALLOWED_FAILURES)})
    procs = {}
    try:
        procs["scheduler"] = fs.start(
            [fs.DASK_SCHEDULER, "--host", "127.0.0.1", "--port", str(port), "--no-dashboard"],
            tmp_path / "scheduler.log", env)
        for name in ("w1", "w2"):
            procs[name] = fs.start(
                [fs.DASK_WORKER, address, "--nthreads", "1", "--nworkers", "1", "--name", name,
                 "--host", "127.0.0.1", "--no-dashboard",
                 "--local-directory", str(tmp_path / name)],
                tmp_path / f"{name}.log", env)
        assert fs.wait_for_workers(address, 2) == 2, fs.tail(tmp_path / "scheduler.log")
        victim = procs["w1"]

        rows, delivered = [], []
        state = {"killed_after": None}

        def on_rows(chunk_rows):
            rows.extend(chunk_rows)
            delivered.append([r["index"] for r in chunk_rows])
            if state["killed_after"] is None and len(delivered) >= 2:
                kill_while_busy(victim, log, delivered)
                state["killed_after"] = len(delivered)

        t0 = time.time()
        fanout.run(scen, range(N), on_rows,
                   scheduler=address, chunk_size=CHUNK, task=fs.logged_run_chunk)
        elapsed = time.time() - t0
        assert state["killed_after"] is not None, "the run ended before a worker was killed"
        assert victim.poll() is not None, "the killed worker is still running"

        starts = collections.Counter(first for _, _, first, _ in fs.read_log(log))
        reruns = sorted(first for first, n in starts.items() if n > 1)
        counts = collections.Counter(r["index"] for r in rows)
        duplicates = sorted(i for i, n in counts.items() if n > 1)
        missing = sorted(set(range(N)) - set(counts))
        print(f"\nkilled-worker: {N} runs in {len(delivered)} chunks of {CHUNK}, "
              f"2 workers, {elapsed:.1f} s; killed w1 (pgid {victim.pid}) after "
              f"{state['killed_after']} chunks came back; chunks rerun: {len(reruns)} "
              f"(first runs {reruns}); indices delivered: {len(counts)}; "
              f"duplicates: {len(duplicates)}; missing: {len(missing)}")
        assert not duplicates, f"indices delivered twice: {duplicates}"
        assert not missing, f"indices never delivered: {missing}"
        assert len(reruns) >= 1, "no chunk of the killed worker was rerun"
        assert fs.canonical(rows) == fs.canonical(fs.run_chunk(scen, list(range(N))))
    finally:
        for proc in procs.values():
            fs.kill_group(proc)
        left = [name for name, p in procs.items() if fs._group_alive(p.pid)]
        assert not left, f"processes left behind: {left}"


def kill_while_busy(victim, log, delivered, timeout=10):
    """SIGKILL victim's process group once it has started a chunk that has not come back."""
    done = {chunk[0] for chunk in delivered}
    deadline = time.time() + timeout
    while time.time() < deadline:
        mine = [first for pgid, _, first, _ in fs.read_log(log) if pgid == victim.pid]
        if mine and mine[-1] not in done:
            fs.kill_group(victim)
            return
        time.sleep(0.005)
    raise AssertionError(f"worker {victim.pid} never held a chunk to lose: {fs.read_log(log)}")
