"""Helpers shared by the fan-out tests: a short scenario, a logging task, Dask processes."""

import os
import signal
import socket
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))
SCENARIO = os.path.join(HERE, "data", "fanout_short.yaml")
#: Environment variable naming the file where logged_run_chunk appends one line per chunk start.
LOG_ENV = "RAGDOLL_FANOUT_TEST_LOG"
DASK_SCHEDULER = "/usr/bin/dask-scheduler"
DASK_WORKER = "/usr/bin/dask-worker"


def scenario():
    """The validated short-fall scenario the fan-out tests run."""
    from ragdoll_sim.batch import scenario as scenario_mod
    return scenario_mod.load(SCENARIO)


def run_chunk(scen, indices):
    """The real runner's run_chunk (the reference of every comparison)."""
    from ragdoll_sim.batch import runner
    return runner.run_chunk(scen, indices)


def logged_run_chunk(scen, indices):
    """run_chunk that first appends 'pgid pid first last' to the file named by $LOG_ENV."""
    path = os.environ.get(LOG_ENV)
    if path:
        line = f"{os.getpgid(0)} {os.getpid()} {indices[0]} {indices[-1]}\n"
        fd = os.open(path, os.O_WRONLY | os.O_APPEND | os.O_CREAT, 0o644)
        try:
            os.write(fd, line.encode())
        finally:
            os.close(fd)
    return run_chunk(scen, indices)


def failing_run_chunk(scen, indices):
    """run_chunk that raises ValueError for run 13, to test how a failing run is reported."""
    if 13 in indices:
        raise ValueError("push out of range for run 13")
    return run_chunk(scen, indices)


def read_log(path):
    """The chunk starts logged by logged_run_chunk: list of (pgid, pid, first, last)."""
    if not os.path.exists(path):
        return []
    with open(path) as f:
        return [tuple(int(x) for x in line.split()) for line in f if line.strip()]


def canonical(rows):
    """Rows as exact text (repr keeps every float bit, NaN included), sorted by run index."""
    return [repr(r) for r in sorted(rows, key=lambda r: r["index"])]


def free_port():
    """A TCP port on 127.0.0.1 that is free now."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def worker_env(extra=None):
    """The caller's environment, with this folder on PYTHONPATH so workers find this module."""
    env = dict(os.environ)
    env["PYTHONPATH"] = os.pathsep.join(p for p in (HERE, os.environ.get("PYTHONPATH")) if p)
    env.update(extra or {})
    return env


def start(cmd, log_path, env, prefix=()):
    """Start cmd (after prefix, e.g. `ip netns exec NS`) in its own process group, output to log."""
    log = open(log_path, "wb")
    try:
        return subprocess.Popen(list(prefix) + list(cmd), stdout=log, stderr=subprocess.STDOUT,
                                env=env, start_new_session=True)
    finally:
        log.close()


def kill_group(proc):
    """SIGKILL proc's whole process group (a dask-worker's nanny and its worker) and reap it."""
    if proc is None or proc.poll() is not None and not _group_alive(proc.pid):
        return
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except ProcessLookupError:
        pass
    try:
        proc.wait(timeout=10)
    except subprocess.TimeoutExpired:
        pass
    deadline = time.time() + 5
    while _group_alive(proc.pid) and time.time() < deadline:
        time.sleep(0.05)


def _group_alive(pgid):
    try:
        os.killpg(pgid, 0)
        return True
    except ProcessLookupError:
        return False
    except PermissionError:
        return True


def wait_for_workers(address, n, timeout=30):
    """Block until n workers joined the scheduler at address; returns their count."""
    from distributed import Client
    with Client(address, timeout=timeout, set_as_default=False) as client:
        client.wait_for_workers(n, timeout=timeout)
        return len(client.scheduler_info()["workers"])


def tail(path, n=30):
    """The last n lines of a log file, for failure messages."""
    try:
        with open(path, errors="replace") as f:
            return "".join(f.readlines()[-n:])
    except OSError:
        return ""


def ragdoll_batch(*args):
    """The command line of scripts/ragdoll_batch with args, run by this Python."""
    return [sys.executable, os.path.join(ROOT, "scripts", "ragdoll_batch"), *args]


def csv_lines(path):
    """A CSV file's lines: header first."""
    with open(path) as f:
        return f.read().splitlines()
