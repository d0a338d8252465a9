#!/usr/bin/python3
"""bench_report.py RAW [--md RESULTS.md] [--png scaling.png]

Turns the raw result lines of scripts/bench.sh (bench/results_raw.txt: one key=value line per
run, plus "# meta key=value" and "# FAILED ..." lines) into a Markdown report and a plot of the
scaling scene g. Standard library + matplotlib only. Nothing in it is specific to one sitting:
every number comes from RAW.
"""
import argparse
import os
import statistics
import sys
from collections import OrderedDict, defaultdict

import bench_flops_report  # flops per body-step and the peak
import bench_raw  # the raw lines
import bench_ratios  # ours / peers, sleep off and on; the bars
import bench_scale_report  # scenes f, w, v, l
from bench_ratios import OURS, OURS_ALL, OURS_L1, OURS_L1_SLEEP, OURS_SLEEP, OURS_VARIANTS
from bench_raw import fnum

ENGINE_ORDER = list(OURS_ALL) + ["mujoco", "bullet", "ode"]
SCENE_ORDER = ["a", "b", "c", "g", "p", "s", "f", "w", "v"]
SCENE_DESC = {
    "a": "1 ragdoll standing, pelvis at 1.5 m, 10 000 steps",
    "b": "32 ragdolls standing, 4 x 8 grid, 1.5 m pitch, 3 000 steps",
    "c": "8 ragdolls prone in a column, yaw k*45 deg, 5 000 steps",
    "g": "scaling: N ragdolls standing (pose of b) on a grid, 1.5 m pitch, 3 000 steps",
    "p": "ours only: 64 ragdolls dropped prone into a 3 m x 3 m pit, 8 000 steps",
    "s": "ours only: 4 x 4 x 3 pile of 0.4 m boxes (sleeping), 3 000 steps",
    **bench_scale_report.SCENE_DESC,
}
# quality metrics shown for every run group (all printed by every engine)
QUALITY = ["max_anchor_err_m", "max_ground_pen_m", "max_limit_viol_rad", "pelvis_z_3s_mean",
           "ground_pen_3s_m", "anchor_err_3s_m", "vmax_3s", "nan"]
OURS_EXTRA = ["substeps", "sleep", "max_contacts", "us_per_step_first_1s", "us_per_step_last_1s",
              "awake_bodies_end", "awake_body_steps", "resting_body_steps", "pit_outside_end",
              "pelvis_z_end_max"]
OURS_EXTRA_MEDIAN = {"us_per_step_first_1s", "us_per_step_last_1s"}  # timings: median


def family(engine):
    """'mujoco-2.2.2' -> 'mujoco'; 'ragdoll_sim' -> 'ragdoll_sim'."""
    return engine.split("-", 1)[0]


def parse(path):
    with open(path) as f:
        meta, runs, failures = bench_raw.parse(f)
    for d in runs:
        # ours with sleeping on in the scenes that also run with it off
        if (d["engine"] == OURS and d.get("sleep") == "1" and
                d.get("scenario") in bench_ratios.SLEEP_SCENES):
            d["engine"] = OURS_SLEEP
    return meta, runs, failures


def group_key(d):
    n = int(d.get("ragdolls", "0") or 0)
    return (family(d["engine"]), d["scenario"], n if d["scenario"] == "g" else None)


def sort_key(key):
    e, s, n = key
    ei = ENGINE_ORDER.index(e) if e in ENGINE_ORDER else len(ENGINE_ORDER)
    si = SCENE_ORDER.index(s) if s in SCENE_ORDER else len(SCENE_ORDER)
    return (si, n or 0, ei, e)


def scene_label(s, n):
    return "g N=%d" % n if s == "g" else s


def fmt_sps(x):
    if x != x:
        return "-"
    if x >= 100:
        return "{:,.0f}".format(x)
    return "{:.1f}".format(x)


def fmt_ratio(x):
    return "-" if x != x else "{:.2f}".format(x)


def same_or_range(vals, numeric=True):
    """One value if all runs agree (deterministic engines), else min-max."""
    uniq = sorted(set(vals), key=fnum if numeric else str)
    if len(uniq) == 1:
        return uniq[0]
    if numeric:
        xs = [fnum(v) for v in vals]
        return "%s–%s (varies)" % (min(vals, key=fnum), max(vals, key=fnum)) if all(
            x == x for x in xs) else " / ".join(uniq)
    return " / ".join(uniq)


class Group:
    def __init__(self, key, runs):
        self.key = key
        self.runs = runs
        self.engine_name = runs[0]["engine"]
        self.sps = [fnum(r["steps_per_s"]) for r in runs]
        self.us = [fnum(r["us_per_body_step"]) for r in runs]
        self.by_round = {r.get("round", str(i)): fnum(r["steps_per_s"]) for i, r in enumerate(runs)}

    @property
    def sps_med(self):
        return statistics.median(self.sps)

    @property
    def us_med(self):
        return statistics.median(self.us)

    def field(self, k, numeric=True):
        vals = [r.get(k, "-") for r in self.runs]
        return same_or_range(vals, numeric)


def build_groups(runs):
    g = defaultdict(list)
    for r in runs:
        g[group_key(r)].append(r)
    return OrderedDict((k, Group(k, g[k])) for k in sorted(g, key=sort_key))


def ratio(groups, scene, n, peer, ours=OURS):
    """Our speed / the peer's speed (steps/s): ratio of the medians, and min-max of the
    per-round ratios (both engines ran back to back in the same round)."""
    ours, other = groups.get((ours, scene, n)), groups.get((peer, scene, n))
    if not ours or not other:
        return float("nan"), float("nan"), float("nan")
    med = ours.sps_med / other.sps_med
    per = [ours.by_round[r] / other.by_round[r] for r in ours.by_round if r in other.by_round]
    return med, (min(per) if per else float("nan")), (max(per) if per else float("nan"))


def md_table(header, rows):
    out = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    out += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return "\n".join(out)


def failure_for(failures, engine, scene, n):
    for f in failures:
        if f.get("engine") == engine and f.get("scenario") == scene and (
                scene != "g" or int(f.get("ragdolls", "0")) == n):
            return f
    return None


def report(meta, runs, failures, png_name):
    runs, load_runs = bench_scale_report.split_runs(runs)
    groups = build_groups(runs)
    engines = [e for e in ENGINE_ORDER if any(k[0] == e for k in groups)]
    engines += sorted({k[0] for k in groups} - set(engines))
    peers = [e for e in engines if e not in OURS_ALL]
    names = {k[0]: g.engine_name for k, g in groups.items()}
    L = []
    L.append("# Benchmark results: ragdoll_sim vs MuJoCo, Bullet, ODE")
    L.append("")
    L.append("Generated by `make bench` (scripts/bench.sh + scripts/bench_report.py) from "
             "`bench/results_raw.txt`; do not edit by hand.")
    L.append("")
    L.append("## Machine and sitting")
    L.append("")
    for k, label in [("date", "date (UTC)"), ("commit", "git commit"), ("worktree", "work tree"),
                     ("nproc", "nproc"), ("cpu", "CPU (/proc/cpuinfo)"),
                     ("compiler", "g++"),
                     ("flags_ours", "flags of ours"), ("flags_peers", "flags of the peers"),
                     ("rounds", "rounds"), ("own_threads", "threads of ours (WorldDef::threads; islands in parallel once 48 bodies are awake (kParallelMin, constants.hpp); the peers are single-threaded)"), ("omp_num_threads", "OMP_NUM_THREADS"),
                     ("engines", "engines"),
                     ("loadavg_start", "load average at start"),
                     ("loadavg_end", "load average at end"), ("total_s", "run time (s)")]:
        if k in meta:
            L.append("- %s: %s" % (label, meta[k].replace("_", " ") if k == "worktree" else meta[k]))
    L += bench_raw.sync_lines(meta)
    L.append("")
    L.append("All engines ran in this one sitting, alternating: in every round each scene is run by "
             "every engine back to back (the engine order rotates from round to round). Steps/s is "
             "the median over the rounds with the min–max in brackets; µs/body-step is the median. "
             "Only the step calls are timed (peers' README: `wall_s`). Absolute timings on a "
             "shared 2-core machine are noisy; compare engines through the ratios, which come "
             "from the same sitting. A quality metric is shown once when all rounds agree, as a "
             "range otherwise.")
    L.append("")
    L.append("Scenes (dt = 1 ms, ground z = 0, friction 0.8, ragdoll15.urdf of ../shared/peers):")
    L.append("")
    for s in SCENE_ORDER:
        if any(k[1] == s for k in groups):
            L.append("- **%s**: %s" % (s, SCENE_DESC.get(s, "")))
    L.append("")

    # ---- main table
    L.append("## All runs: engine × scene")
    L.append("")
    header = ["engine", "scene", "bodies", "steps", "runs", "steps/s median (min–max)",
              "µs/body-step", "max_anchor_err_m", "max_ground_pen_m",
              "max_limit_viol_rad (joint@step)", "pelvis_z_3s_mean (min–max)", "ground_pen_3s_m",
              "anchor_err_3s_m", "vmax_3s", "nan"]
    rows = []
    for k, g in groups.items():
        e, s, n = k
        rows.append([
            names[e], scene_label(s, n), g.field("bodies"), g.field("steps"), len(g.runs),
            "%s (%s–%s)" % (fmt_sps(g.sps_med), fmt_sps(min(g.sps)), fmt_sps(max(g.sps))),
            "%.2f" % g.us_med, g.field("max_anchor_err_m"), g.field("max_ground_pen_m"),
            "%s (%s)" % (g.field("max_limit_viol_rad"), g.field("worst_limit", numeric=False)),
            "%s (%s–%s)" % (g.field("pelvis_z_3s_mean"), g.field("pelvis_z_3s_min"),
                            g.field("pelvis_z_3s_max")),
            g.field("ground_pen_3s_m"), g.field("anchor_err_3s_m"), g.field("vmax_3s"),
            g.field("nan"),
        ])
    L.append(md_table(header, rows))
    L.append("")

    # ---- ratios (sleep off and on) and the bars
    L += bench_ratios.section(groups, engines, names, SCENE_ORDER, md_table, scene_label,
                              lambda e, s, n: failure_for(failures, e, s, n) is not None)

    # ---- scaling
    ns = sorted({n for (e, s, n) in groups if s == "g"} |
                {int(f.get("ragdolls", 0)) for f in failures if f.get("scenario") == "g"})
    if ns:
        L.append("## Scaling (scene g): µs per body-step vs number of ragdolls")
        L.append("")
        L.append("Median µs/body-step (min–max over the rounds), and median steps/s. Flat means "
                 "linear cost in the number of bodies. Plot: `%s`." % png_name)
        L.append("")
        header = ["ragdolls", "bodies"]
        g_engines = [e for e in engines if any(k[0] == e and k[1] == "g" for k in groups)]
        for e in g_engines:
            header += ["%s µs/body-step" % names[e], "%s steps/s" % names[e]]
        g_ours = [v for v in OURS_VARIANTS if v.off in engines]
        header += ["%s ÷ %s (steps/s)" % (v.name, names[p]) for v in g_ours for p in peers]
        rows = []
        for n in ns:
            bodies = next((g.field("bodies") for (e, s, m), g in groups.items()
                           if s == "g" and m == n), "-")
            row = [n, bodies]
            for e in g_engines:
                g = groups.get((e, "g", n))
                if g:
                    row += ["%.2f (%.2f–%.2f)" % (g.us_med, min(g.us), max(g.us)),
                            fmt_sps(g.sps_med)]
                else:
                    f = failure_for(failures, e, "g", n)
                    row += ["failed" if f else "-", "-"]
            for v in g_ours:
                for p in peers:
                    med, lo, hi = ratio(groups, "g", n, p, v.off)
                    row.append("-" if med != med else "%s (%s–%s)" % (
                        fmt_ratio(med), fmt_ratio(lo), fmt_ratio(hi)))
            rows.append(row)
        spread = ["spread about the mean over N", ""]
        for e in g_engines:
            us = [groups[(e, "g", n)].us_med for n in ns if (e, "g", n) in groups]
            mean = sum(us) / len(us) if us else 0.0
            spread += ["%+.0f %% to %+.0f %%" % (100 * (min(us) / mean - 1), 100 * (max(us) / mean - 1))
                       if len(us) > 1 else "-", ""]
        spread += [""] * (len(header) - len(spread))
        rows.append(spread)
        L.append(md_table(header, rows))
        L.append("")
        ones = [v.one for v in OURS_VARIANTS if v.one in engines]
        if ones:
            L.append("%s ours with `threads=1`: islands run in parallel only from 48 awake "
                     "bodies (kParallelMin), so N = 1 (one 15-body island) always runs on one core "
                     "while larger N use all of them; on one thread every N gets the same, and the "
                     "line shows the cost of the algorithm alone." % (
                         " and ".join("`%s`" % e for e in ones) + (" are" if len(ones) > 1 else " is")))
            L.append("")
        L.append("The peers run scene g through `bench/peers_scaling/scaling_<engine>.cpp`: the "
                 "unmodified peer bench source from ../shared/peers with `make_scene`/`parse_args` "
                 "of ragdoll_common.hpp wrapped to add scene g; the grid is "
                 "`bench/scaling_grid.hpp`, the same one bench_ragdoll uses.")
        L.append("")
    L += bench_ratios.bars_section(groups, engines, names, meta)

    # ---- our extras
    ours_groups = [(k, g) for k, g in groups.items() if k[0] == OURS]
    extra_label = {OURS: "", OURS_SLEEP: " (sleep on)", OURS_L1: " (lanes=1)",
                   OURS_L1_SLEEP: " (lanes=1, sleep on)"}
    extra_groups = [(k, g) for k, g in groups.items() if k[0] in extra_label]
    if extra_groups:
        L.append("## ragdoll_sim: extra fields")
        L.append("")
        L.append("Cost per step in the first and the last simulated second (µs, median; "
                 "sleeping bodies cost nothing), contact count at the end, bodies awake at the "
                 "end and awake bodies summed over the steps (what sleeping left to solve: the "
                 "same for every run of one binary, while a change of round-off alone can move "
                 "it, in b by ~20 %: docs/benchmarks.md); scene p: ragdolls whose pelvis ended "
                 "outside the pit, and the highest pelvis at the end (m).")
        L.append("")
        rows = []
        for (e, s, n), g in extra_groups:
            rows.append([scene_label(s, n) + extra_label[e]] + [
                "%.1f" % statistics.median(fnum(r.get(k)) for r in g.runs)
                if k in OURS_EXTRA_MEDIAN else g.field(k) for k in OURS_EXTRA])
        L.append(md_table(["scene"] + OURS_EXTRA, rows))
        L.append("")

    L += bench_scale_report.section(runs, load_runs, meta)
    L += bench_flops_report.section(meta, ours_groups, md_table, scene_label)

    # ---- chaotic scenes as perturbed copies (scripts/bench_ensemble.sh)
    if meta.get("ensembles"):
        L.append("## Scenes b and c as yaw-perturbed copies (ours)")
        L.append("")
        L.append("Scenes b and c are chaotic: round-off alone gives another trajectory, so the "
                 "single run above is one sample. `scripts/bench_ensemble.sh` runs the scene as "
                 "copies whose ragdolls are all turned by a tiny yaw (copy 1 is the scene "
                 "itself) and counts the copies that meet each bar of the joints issue. The "
                 "peer benches have no yaw option. Awake body-steps (bodies awake after each "
                 "step, summed) are what sleeping left to solve: against the scene's own count "
                 "(extra fields above) they show where the timed trajectory lies in the spread." +
                 (" A scene with an option in brackets ran with that `--opt` (lanes=1: ours "
                  "with every row in double)." if any(e.get("opts", "-") != "-"
                                                  for e in meta["ensembles"]) else ""))
        L.append("")
        rows = []
        for e in meta["ensembles"]:
            n = int(e.get("copies", "0"))
            opts = e.get("opts", "-")
            rows.append([e.get("scene", "?") + ("" if opts == "-" else " (%s)" % opts), str(n),
                         "%s of %d (%s)" % (e.get("at_rest_3s", "?"), n, e.get("vmax_3s", "?")),
                         "%s of %d (max %s)" % (e.get("anchor_ok", "?"), n, e.get("max_anchor_err_m", "?")),
                         "%s of %d (max %s)" % (e.get("pen_ok", "?"), n, e.get("max_ground_pen_m", "?")),
                         "%s of %d (max %s)" % (e.get("limit_ok", "?"), n, e.get("max_limit_viol_rad", "?")),
                         e.get("nan_copies", "?"), e.get("steps_per_s_median", "?"),
                         "%s (%s)" % (e.get("awake_body_steps_median", "?"),
                                      e.get("awake_body_steps", "?")),
                         "%s of %d" % (e.get("asleep_end", "?"), n)])
        L.append(md_table(["scene", "copies", "at rest at 3 s (vmax_3s range, m/s)",
                           "anchor <= 1 mm", "penetration <= 5 mm", "limit <= 0.05 rad",
                           "copies with NaN", "steps/s median",
                           "awake body-steps median (range)", "all asleep at the end"], rows))
        L.append("")

    # ---- failures
    if failures:
        L.append("## Failed runs")
        L.append("")
        rows = []
        for f in failures:
            rows.append([f.get("engine", "?"), scene_label(f.get("scenario", "?"),
                                                          int(f.get("ragdolls", "0") or 0)),
                         f.get("round", "?"), f.get("rc", "?"),
                         "`%s`" % f.get("reason", "").replace("_", " ")])
        L.append(md_table(["engine", "scene", "round", "exit status", "last stderr line"], rows))
        L.append("")
        if any(f.get("engine") == "mujoco" and f.get("scenario") == "g" for f in failures):
            L.append("MuJoCo: the peer bench sets `njmax` = 250 constraint rows per ragdoll, and "
                     "MuJoCo 2.2.2 preallocates dense njmax × njmax arrays in mjData (`efc_AR`, "
                     "`efc_AR_colind`, see mjxmacro.h) in one buffer whose size is an int number "
                     "of bytes; from about 42 ragdolls on that passes 2 GiB and `mj_makeData` "
                     "fails (\"could not create mjData\"). The peer's settings are kept as they "
                     "are, so MuJoCo has no number there.")
            L.append("")

    L.append("## How to run")
    L.append("")
    L.append("```sh\nmake bench                      # ROUNDS=3, all scenes, scaling N = 1 4 16 64 256\n"
             "ROUNDS=5 make bench\n"
             "SCALING_NS=\"1 4 16\" OWN_SCENES= make bench   # quicker\n"
             "ENGINES=\"ragdoll_sim mujoco bullet ode\" make bench   # without ours lanes=1\n"
             "/usr/bin/python3 scripts/bench_report.py bench/results_raw.txt --md bench/RESULTS.md "
             "--png bench/scaling.png   # report only\n"
             ".ws/bench/bench_ragdoll g --ragdolls 64 --urdf ../shared/peers/ragdoll15.urdf\n"
             ".ws/bench/peers/scaling_ode g --ragdolls 64 --urdf ../shared/peers/ragdoll15.urdf\n"
             "scripts/bench_compare.sh OLD_BIN NEW_BIN 5   # two binaries interleaved, new ÷ old\n```")
    L.append("")
    L.append("Other settings: PEERS_DIR, SCENES, OWN_SCENES, SCALING_NS, SCALING_STEPS, ENGINES, "
             "SLEEP_ON, FLOPS_OPTS, "
             "RUN_TIMEOUT (see the header of scripts/bench.sh). Engine stderr of the last sitting: "
             "`.ws/bench/bench_stderr.log`.")
    L.append("")
    return "\n".join(L), groups, engines, names


def plot(groups, engines, names, path, failures=()):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7, 5.2), dpi=120)
    any_line = False
    for e in engines:
        pts = sorted((n, g) for (ee, s, n), g in groups.items() if ee == e and s == "g")
        if not pts:
            continue
        xs = [n for n, _ in pts]
        ys = [g.us_med for _, g in pts]
        lo = [g.us_med - min(g.us) for _, g in pts]
        hi = [max(g.us) - g.us_med for _, g in pts]
        failed = sorted({int(f.get("ragdolls", 0)) for f in failures
                         if f.get("engine") == e and f.get("scenario") == "g"} - set(xs))
        label = names[e] + (" (failed at N=%s)" % ", ".join(map(str, failed)) if failed else "")
        ax.errorbar(xs, ys, yerr=[lo, hi], marker="o", capsize=3,
                    linewidth=2.5 if e.startswith(OURS) else 1.5,
                    linestyle="--" if e.endswith("_1thread") else "-", label=label)
        any_line = True
    ax.set_xscale("log", base=2)
    ax.set_xlabel("ragdolls (15 bodies each)")
    ax.set_ylabel("µs per body-step (median, min–max)")
    ax.set_title("Scaling scene g: standing ragdolls on a 1.5 m grid")
    ax.set_ylim(bottom=0)
    ax.grid(True, which="both", alpha=0.3)
    if any_line:
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2, fontsize="small")
        xs = sorted({n for (e, s, n) in groups if s == "g"})
        ax.set_xticks(xs)
        ax.set_xticklabels([str(x) for x in xs])
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("raw")
    ap.add_argument("--md", default=None, help="write the Markdown report here (default: stdout)")
    ap.add_argument("--png", default=None, help="write the scaling plot here")
    a = ap.parse_args()
    meta, runs, failures = parse(a.raw)
    if not runs:
        print("bench_report: no result lines in %s" % a.raw, file=sys.stderr)
        return 1
    png_name = os.path.basename(a.png) if a.png else "scaling.png"
    text, groups, engines, names = report(meta, runs, failures, png_name)
    if a.md:
        with open(a.md, "w") as f:
            f.write(text)
        print("bench_report: wrote %s" % a.md)
    else:
        print(text)
    if a.png:
        if any(s == "g" for (_, s, _) in groups):
            plot(groups, engines, names, a.png, failures)
            print("bench_report: wrote %s" % a.png)
        else:
            print("bench_report: no scene g lines, no plot", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
