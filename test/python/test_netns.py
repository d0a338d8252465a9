"""Multi-host fan-out on one machine: two network namespaces joined by a veth pair as "hosts".

Host 1 runs dask-scheduler, a dask-worker and the driver; host 2 runs a dask-worker that reaches
the scheduler only over the veth pair. 200 short falls must give the CSV of the single-process
run. Root only (ip netns); skipped with the reason otherwise. Namespaces and processes are
removed in finally, and the test checks that none is left.
"""

import os
import shutil
import subprocess
import sys
import time

import pytest

import fanout_support as fs

N = 200
PORT = 8786  # each namespace has its own ports, so the default is free there
SUBNET = "10.59.59.{}/30"  # only inside the two namespaces: no clash with the machine's own


def ip(*args):
    return subprocess.run(["ip", *args], capture_output=True, text=True)


def must(*args):
    r = ip(*args)
    assert r.returncode == 0, f"ip {' '.join(args)}: {r.stderr.strip()}"


def netns_list():
    return ip("netns", "list").stdout


@pytest.fixture
def hosts():
    """Two namespaces (host 1 at .1, host 2 at .2 of a /30) joined by a veth pair, loopback up."""
    if os.geteuid() != 0:
        pytest.skip("test_netns needs root: it creates network namespaces with `ip netns add`")
    if shutil.which("ip") is None:
        pytest.skip("test_netns needs the `ip` command (iproute2)")
    pid = os.getpid()
    names = [f"rd59-h1-{pid}", f"rd59-h2-{pid}"]
    links = [f"rdv1-{pid}", f"rdv2-{pid}"]  # interface names have at most 15 characters
    r = ip("netns", "add", names[0])
    if r.returncode != 0:
        pytest.skip(f"`ip netns add` was refused ({r.stderr.strip()}): this needs "
                    "CAP_SYS_ADMIN (a container without it cannot create network namespaces)")
    try:
        must("netns", "add", names[1])
        r = ip("link", "add", links[0], "netns", names[0], "type", "veth",
               "peer", "name", links[1], "netns", names[1])
        if r.returncode != 0:
            pytest.skip(f"a veth pair was refused ({r.stderr.strip()}): this needs the kernel's "
                        "veth driver")
        addresses = []
        for k, (ns, link) in enumerate(zip(names, links)):
            must("-n", ns, "link", "set", "lo", "up")
            must("-n", ns, "addr", "add", SUBNET.format(k + 1), "dev", link)
            must("-n", ns, "link", "set", link, "up")
            addresses.append(SUBNET.format(k + 1).split("/")[0])
        yield list(zip(names, addresses))
    finally:
        for ns in names:
            ip("netns", "del", ns)
        left = [ns for ns in names if ns in netns_list()]
        assert not left, f"network namespaces left behind: {left}"


def in_ns(ns):
    return ["ip", "netns", "exec", ns]


def test_two_hosts_give_the_single_process_csv(hosts, tmp_path):
    (h1, addr1), (h2, addr2) = hosts
    scheduler = f"tcp://{addr1}:{PORT}"
    env = fs.worker_env()
    procs = {}
    t0 = time.time()
    try:
        procs["scheduler"] = fs.start(
            [fs.DASK_SCHEDULER, "--host", addr1, "--port", str(PORT), "--no-dashboard"],
            tmp_path / "scheduler.log", env, prefix=in_ns(h1))
        for name, ns, addr in (("host1-worker", h1, addr1), ("host2-worker", h2, addr2)):
            procs[name] = fs.start(
                [fs.DASK_WORKER, scheduler, "--nthreads", "1", "--nworkers", "1", "--name", name,
                 "--host", addr, "--no-dashboard", "--local-directory", str(tmp_path / name)],
                tmp_path / f"{name}.log", env, prefix=in_ns(ns))

        out = tmp_path / "falls.csv"
        driver = subprocess.run(
            in_ns(h1) + [sys.executable, os.path.join(fs.HERE, "fanout_netns_driver.py"),
                         scheduler, fs.SCENARIO, f"0:{N}", str(out)],
            capture_output=True, text=True, env=env, timeout=50)
        logs = {name: fs.tail(tmp_path / f"{name}.log") for name in procs}
        assert driver.returncode == 0, f"{driver.stdout}\n{driver.stderr}\n{logs}"
        print(f"\n(in host 1, namespace {h1}; host 2 is {h2})\n{driver.stdout}")

        reference = tmp_path / "reference.csv"
        single = subprocess.run(fs.ragdoll_batch("run", fs.SCENARIO, "--runs", f"0:{N}",
                                                 "--out", str(reference), "--workers", "1"),
                                capture_output=True, text=True, env=env, timeout=50)
        assert single.returncode == 0, single.stderr
        got, want = fs.csv_lines(out), fs.csv_lines(reference)
        assert got[0] == want[0], "the header differs"
        assert len(got) == N + 1, f"{len(got) - 1} rows, expected {N}"
        assert sorted(got[1:]) == sorted(want[1:]), "the rows differ from the single-process run"
        print(f"falls.csv has the {N} rows of the single-process run (--workers 1), "
              f"{time.time() - t0:.1f} s in all")
    finally:
        for proc in procs.values():
            fs.kill_group(proc)
        left = [name for name, p in procs.items() if fs._group_alive(p.pid)]
        assert not left, f"processes left behind: {left}"
