"""The "Scale of worlds" section of bench/RESULTS.md (bench_report.py imports it).

Scenes f, w, v (bench_ragdoll, bench/static_world.hpp): the bundled ragdoll (urdf/ragdoll.urdf)
dropped on the plane alone (f), among 10 000 static boxes each its own body (w), and among the
same boxes as shapes of one static body (v); sleep off, so every step is a full one. Each round
runs f, w, v back to back: the ratios w/f and v/f come from runs made under the same load.
Scene l (bench_world_load): a generated SDF world of dynamic primitives loaded with
loadWorldString (parse) and put into a World (build).
"""
import statistics
from bench_raw import fnum

SCALE_SCENES = ("f", "w", "v")
SCENE_DESC = {
    "f": "ours only: the bundled ragdoll on the plane, sleep off (scale of worlds, below)",
    "w": "ours only: f among 10 000 static boxes, each its own body",
    "v": "ours only: f among 10 000 static boxes, shapes of one body",
}
TARGET_RATIO = 0.75  # issue 56: >= 0.75 x the plane's speed
TARGET_LOAD_S = 5.0  # issue 56: a world of 3 000 dynamic primitives loads in < 5 s


def split_runs(runs):
    """(runs of the other scenes, runs of scene l): l lines have no step fields."""
    return ([r for r in runs if r.get("scenario") != "l"],
            [r for r in runs if r.get("scenario") == "l"])


def section(runs, load_runs, meta):
    ours = [r for r in runs if r.get("engine") == "ragdoll_sim" and r.get("scenario") in SCALE_SCENES]
    if not ours and not load_runs:
        return []
    L = ["## Scale of worlds (ours)", ""]
    if "scale_sitting" in meta:
        L += ["These scenes ran in a sitting of their own: %s." % meta["scale_sitting"], ""]
    if ours:
        L += ["The bundled ragdoll (urdf/ragdoll.urdf) dropped standing, pelvis at 1.5 m, 5 000 "
              "steps, sleep off: **f** on the plane alone; **w** among 10 000 static 0.5 m boxes "
              "on a 100 x 100 grid, 2 m pitch (bench/static_world.hpp), each its own body; **v** "
              "the same boxes as shapes of one static body. The ragdoll lands on the plane "
              "between four boxes (the same trajectory in all three), so the ratio is what the "
              "static shapes cost per step. Each round runs f, w, v back to back; the ratio is "
              "the median of the per-round ratios (min–max); target >= %.2f." % TARGET_RATIO, ""]
        by_round = {}
        for r in ours:
            by_round.setdefault(r.get("round", "0"), {})[r["scenario"]] = fnum(r["steps_per_s"])
        rows = []
        for s in SCALE_SCENES:
            sps = [d[s] for d in by_round.values() if s in d]
            if not sps:
                continue
            ratios = [d[s] / d["f"] for d in by_round.values() if s in d and d.get("f")]
            ratio = ("%.2f (%.2f–%.2f)" % (statistics.median(ratios), min(ratios), max(ratios))
                     if ratios else "-")
            shapes = {"f": "0", "w": "10 000 (10 000 bodies)", "v": "10 000 (1 body)"}[s]
            rows.append("| %s | %s | %d | %.0f (%.0f–%.0f) | %s |" % (
                s, shapes, len(sps), statistics.median(sps), min(sps), max(sps), ratio))
        L += ["| scene | static boxes | runs | steps/s median (min–max) | ÷ f |",
              "|---|---|---|---|---|"] + rows + [""]
    if load_runs:
        L += ["Scene **l**: a generated SDF world of N dynamic primitives (boxes, spheres, "
              "cylinders in turn, each its own model with <inertial>, <collision> and <visual>), "
              "`sizes` sizes per kind (0: every model its own), loaded by loadWorldString "
              "(parse) and put into a started Scene by Scene::loadWorld (build); medians over the "
              "rounds; target load < %.0f s for 3 000." % TARGET_LOAD_S, ""]
        groups = {}
        for r in load_runs:
            groups.setdefault((int(r["objects"]), int(r["sizes"])), []).append(r)
        rows = []
        for (n, sizes), rs in sorted(groups.items()):
            med = {k: statistics.median(fnum(r[k]) for r in rs)
                   for k in ("parse_s", "build_s", "load_s", "first_step_s")}
            rows.append("| %d | %d | %d | %.2f | %.2f | %.2f | %.3f |" % (
                n, sizes, len(rs), med["parse_s"], med["build_s"], med["load_s"],
                med["first_step_s"]))
        L += ["| primitives | sizes | runs | parse_s | build_s | load_s | first_step_s |",
              "|---|---|---|---|---|---|---|"] + rows + [""]
    return L
