#!/usr/bin/env python3
"""Batch throughput against the single-run rate (docs/benchmarks.md, "Batch throughput").

    bench/bench_batch.py [--bench-fall build/bench_fall] [--runs 30] [--rounds 3]

Each round, one after the other: bench_fall (C++, seconds per 3 s fall, the single-run rate);
`ragdoll_batch run bench/fall_3s.yaml --workers 1` (the same fall, 1 core); two such processes
on disjoint ranges at once (2 cores); `--workers 2` (a local Dask cluster, 2 cores). Each batch
mode runs twice, with 2 and with --runs runs per core: "total" is the runs per minute per core of
the long one, start-up included (Python, the model and world parsed, the Dask cluster started);
"marginal" is (runs_long - runs_short) / (time_long - time_short) per core, the rate once
started; "cpu_marginal" the same per CPU minute (user + system time of every process, Dask's
workers included): on a busy machine the wall rates of 2 processes fall with the load, the CPU
rates show what the batch itself costs. Prints the medians over the rounds and the ratios to
bench_fall's (wall rates to its wall rate, CPU rates to its rate per CPU minute).
Needs the workspace sourced (ragdoll_sim importable).
"""
import argparse
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
SCENARIO = os.path.join(ROOT, "bench", "fall_3s.yaml")
BATCH = [sys.executable, os.path.join(ROOT, "scripts", "ragdoll_batch"), "run", SCENARIO]


def cpu_children():
    """CPU seconds (user + system) of the finished child processes and their descendants."""
    r = resource.getrusage(resource.RUSAGE_CHILDREN)
    return r.ru_utime + r.ru_stime


def timed(cmds):
    """(wall s, CPU s) of the commands started together, each checked; the CPU time includes
    their descendants (Dask's worker processes)."""
    c0 = cpu_children()
    t0 = time.perf_counter()
    procs = [subprocess.Popen(c, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
             for c in cmds]
    for p in procs:
        _, err = p.communicate()
        if p.returncode != 0:
            sys.exit("failed: %s\n%s" % (" ".join(p.args), err))
    return time.perf_counter() - t0, cpu_children() - c0


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--bench-fall", default=os.path.join(ROOT, "build", "bench_fall"))
    ap.add_argument("--runs", type=int, default=30, help="runs per core per measurement")
    ap.add_argument("--rounds", type=int, default=3)
    a = ap.parse_args()
    n = a.runs
    modes = {  # name -> (cores, commands for k runs per core writing to files named by tag)
        "batch_1": (1, lambda k, f: [BATCH + ["--runs", "0:%d" % k, "--workers", "1",
                                              "--out", f("one")]]),
        "batch_2proc": (2, lambda k, f: [
            BATCH + ["--runs", "0:%d" % k, "--workers", "1", "--out", f("a")],
            BATCH + ["--runs", "%d:%d" % (k, 2 * k), "--workers", "1", "--out", f("b")]]),
        "batch_dask2": (2, lambda k, f: [BATCH + ["--runs", "0:%d" % (2 * k), "--workers", "2",
                                                  "--out", f("dask")]]),
    }
    results = {"bench_fall": [], "bench_fall_cpu": []}
    for m in modes:
        for kind in ("total", "marginal", "cpu_marginal"):
            results[m + "_" + kind] = []
    short = 2
    with tempfile.TemporaryDirectory() as tmp:
        for r in range(a.rounds):
            c0 = cpu_children()
            out = subprocess.run([a.bench_fall, "--runs", str(n)], capture_output=True, text=True,
                                 check=True).stdout
            s = float(re.search(r"s_per_fall_median=([0-9.]+)", out).group(1))
            results["bench_fall"].append(60.0 / s)
            results["bench_fall_cpu"].append(60.0 * n / (cpu_children() - c0))
            for m, (cores, cmds) in modes.items():
                def f(k):
                    return lambda name: os.path.join(tmp, "%s_%s_%d_%d.csv" % (m, name, k, r))
                t_short, c_short = timed(cmds(short, f(short)))
                t_long, c_long = timed(cmds(n, f(n)))
                results[m + "_total"].append(60.0 * n / t_long)
                results[m + "_marginal"].append(60.0 * (n - short) / (t_long - t_short))
                results[m + "_cpu_marginal"].append(60.0 * cores * (n - short) / (c_long - c_short))
            print("round %d: %s  (load %.1f)" % (r + 1, "  ".join(
                "%s %.1f" % (k, v[-1]) for k, v in results.items()), os.getloadavg()[0]),
                flush=True)
    ref = statistics.median(results["bench_fall"])
    ref_cpu = statistics.median(results["bench_fall_cpu"])
    print("median runs/min per core (wall), per CPU minute (cpu):")
    for k, v in results.items():
        m = statistics.median(v)
        cpu = "cpu" in k
        print("  %-26s %7.1f  (%.2fx bench_fall%s)" % (k, m, m / (ref_cpu if cpu else ref),
                                                     "_cpu" if cpu else ""))


if __name__ == "__main__":
    main()
