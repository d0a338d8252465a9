#!/usr/bin/python3
"""bench_compare_report.py RAW [--md FILE]

The Markdown table of scripts/bench_compare.sh: for each scene and thread count, the steps/s of
the old and the new binary (median and min-max over the rounds), new / old (the ratio of the
medians, and min-max of the per-round ratios: both ran back to back in each round) and each
binary's quality line. Scenes with a bar of the wide solver's issue show it beside the ratio.
Standard library only.
"""
import argparse
import statistics
import sys
from collections import OrderedDict

from bench_raw import fnum, parse, sync_lines

# new / old bars of the wide solver's issue (scene label -> least ratio of steps/s)
BARS = {"p": 1.35, "g1": 1.2}
QUALITY = ("max_anchor_err_m", "max_ground_pen_m", "max_limit_viol_rad")


def fmt_sps(x):
    return "{:,.0f}".format(x) if x >= 100 else "{:.1f}".format(x)


def label_of(run):
    return run.get("label") or run.get("scenario", "?")


def scene_name(label):
    return "g N=%s" % label[1:] if label.startswith("g") and len(label) > 1 else label


def quality(runs):
    """The quality fields, once if every round agrees, else min-max."""
    out = []
    for k in QUALITY:
        vals = sorted({r.get(k, "-") for r in runs}, key=fnum)
        out.append(vals[0] if len(vals) == 1 else "%s–%s" % (vals[0], vals[-1]))
    return " / ".join(out)


def same_state(runs):
    """With OPTS=hash=1: "yes" when every run of both binaries ends on the same state hash."""
    hashes = {side: {r["state_hash"] for r in runs if r.get("side") == side and "state_hash" in r}
              for side in ("old", "new")}
    if not hashes["old"] or not hashes["new"]:
        return "-"
    return "yes" if len(hashes["old"] | hashes["new"]) == 1 else "no"


def rows(runs, failures):
    """One row per (scene, threads) in the order they ran."""
    keys = list(OrderedDict.fromkeys((label_of(r), r.get("run_threads", r.get("threads", "?")))
                                     for r in runs))
    keys += [k for k in OrderedDict.fromkeys((f.get("label", "?"), f.get("run_threads", "?"))
                                            for f in failures) if k not in keys]
    out = []
    for label, t in keys:
        mine = [r for r in runs if label_of(r) == label and
                r.get("run_threads", r.get("threads")) == t]
        by = {side: {r.get("round", "?"): fnum(r["steps_per_s"]) for r in mine if r.get("side") == side}
              for side in ("old", "new")}
        nfail = sum(1 for f in failures if f.get("label") == label and f.get("run_threads") == t)
        row = [scene_name(label), t]
        for side in ("old", "new"):
            v = list(by[side].values())
            row.append("%s (%s–%s)" % (fmt_sps(statistics.median(v)), fmt_sps(min(v)), fmt_sps(max(v)))
                       if v else "-")
        common = [r for r in by["old"] if r in by["new"] and by["old"][r] > 0]
        bar = BARS.get(label)
        if common:
            med = statistics.median(by["new"][r] for r in common) / statistics.median(
                by["old"][r] for r in common)
            per = [by["new"][r] / by["old"][r] for r in common]
            row.append("%.2f (%.2f–%.2f)" % (med, min(per), max(per)))
            row.append("≥ %.2f: %s" % (bar, "met" if med >= bar else "not met") if bar else "")
        else:
            row += ["-", "≥ %.2f" % bar if bar else ""]
        for side in ("old", "new"):
            row.append(quality([r for r in mine if r.get("side") == side]) if by[side] else "-")
        row.append(same_state(mine))
        row.append(str(nfail) if nfail else "")
        out.append(row)
    return out


def report(meta, runs, failures):
    L = ["## Old against new, interleaved", ""]
    L.append("Old: `%s`%s; new: `%s`%s. Rounds: %s, old and new back to back in each (the first "
             "of the two swapping every round), sleeping off, OMP_NUM_THREADS=1, steps: %s; "
             "%s, nproc %s, load average %s at the start, %s at the end." % (
                 meta.get("old_bin", "?"), " --opt " + meta["old_opts"] if meta.get("old_opts") else "",
                 meta.get("new_bin", "?"), " --opt " + meta["new_opts"] if meta.get("new_opts") else "",
                 meta.get("rounds", "?"), meta.get("steps", "scene"), meta.get("date", "?"),
                 meta.get("nproc", "?"), meta.get("loadavg_start", "?"), meta.get("loadavg_end", "?")))
    L.append("")
    sync = sync_lines(meta)
    if sync:
        L += sync + [""]
    L.append("Steps/s: median (min–max) over the rounds. new ÷ old: the ratio of the medians "
             "(min–max of the per-round ratios). Quality: max_anchor_err_m / max_ground_pen_m / "
             "max_limit_viol_rad. Same state (with `OPTS=hash=1`): every run of both binaries "
             "gave the same state hash, bit for bit.")
    L.append("")
    header = ["scene", "threads", "old steps/s", "new steps/s", "new ÷ old", "bar",
              "quality old", "quality new", "same state", "failed runs"]
    body = rows(runs, failures)
    L.append("| " + " | ".join(header) + " |")
    L.append("|" + "|".join("---" for _ in header) + "|")
    L += ["| " + " | ".join(str(c) for c in row) + " |" for row in body]
    L.append("")
    return "\n".join(L)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("raw")
    ap.add_argument("--md", default=None, help="also write the table here")
    a = ap.parse_args()
    with open(a.raw) as f:
        meta, runs, failures = parse(f)
    if not runs and not failures:
        print("bench_compare_report: no result lines in %s" % a.raw, file=sys.stderr)
        return 1
    text = report(meta, runs, failures)
    print(text)
    if a.md:
        with open(a.md, "w") as f:
            f.write(text)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
