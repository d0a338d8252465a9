"""The "Flops per body-step" section of bench/RESULTS.md (bench_report.py imports it), from the
"# meta" lines of scripts/flops.sh.

valgrind's lackey counts the IR's arithmetic by type: F64 (in the x87 build every scalar
operation, double or float alike, since valgrind models the x87 registers as doubles), F32 (ops
whose result is a float: the conversions to float), V128 and V256 (SSE and AVX lanes, up to 4
and 8 float operations each, masks and integer lanes included). flops_per_body_step is
F64 + F32 + 4 V128 + 8 V256, an upper bound.
"""
import statistics
from bench_raw import fnum

FLOAT_PER_DOUBLE = 2  # SSE and AVX units do twice as many float as double operations a cycle


def section(meta, ours_groups, md_table, label):
    if "flops_per_body_step" not in meta or not ours_groups:
        return []
    flops = fnum(meta["flops_per_body_step"])
    peak = fnum(meta.get("peak_gflops"))
    peak_f = fnum(meta.get("peak_gflops_float", peak * FLOAT_PER_DOUBLE))
    kinds = [(k, meta.get("flops_%s_per_body_step" % k.lower())) for k in ("F64", "F32", "V128", "V256")]
    L = ["## Flops per body-step and the machine's peak", ""]
    L.append("Counted by `scripts/flops.sh`: bench_ragdoll built with x87 arithmetic and Eigen's "
             "vectorisation off, so that valgrind's lackey counts every scalar operation "
             "(conversions and negations too), scene a with sleeping off, steps %s, options "
             "`%s`, commit %s." % (
                 meta.get("flops_window", "?").replace("a:", ""), meta.get("flops_opts") or "-",
                 meta.get("flops_commit", meta.get("commit", "?"))))
    if all(v is not None for _, v in kinds):
        L.append("Arithmetic ops per body-step by lackey's type: %s. F64 holds every scalar "
                 "operation, float ones too (valgrind runs the x87 registers as doubles); F32 "
                 "only the conversions to float; a V128 (SSE) op is up to 4 float operations and "
                 "a V256 (AVX) op up to 8, masks included. Flops per body-step = F64 + F32 + "
                 "4 V128 + 8 V256 = %.0f, an upper bound." % (
                     ", ".join("%s %s" % (k, v) for k, v in kinds), flops))
    if "lanes=1" in (meta.get("flops_opts") or ""):
        L.append("The count is of the double rows (`lanes=1`): the float lanes solve the same rows, "
                 "so it is the solver's work, and the GFLOP/s below are that work per second at "
                 "each run's speed; counted in the lanes themselves, lackey would add their "
                 "padding lanes, selects and conversions.")
    L.append("Peak: %s = %.1f GFLOP/s in double; in float %.1f GFLOP/s, assuming %d float "
             "operations per cycle for each double one (an SSE or AVX register holds twice as "
             "many floats)." % (meta.get("peak_basis", "?").replace("_", " "), peak, peak_f,
                                FLOAT_PER_DOUBLE))
    L.append("")
    rows = []
    for (e, s, n), g in ours_groups:
        if any(r.get("sleep") == "1" for r in g.runs):
            continue  # asleep for part of their steps: the rate is not the solver's
        bsps = statistics.median(fnum(r.get("body_steps_per_s")) for r in g.runs)
        gf = flops * bsps / 1e9
        rows.append([label(s, n), "%.0f" % flops, "%.0f" % bsps, "%.2f" % gf,
                     "%.2f %%" % (100.0 * gf / peak), "%.2f %%" % (100.0 * gf / peak_f)])
    L.append(md_table(["scene", "flops/body-step", "body-steps/s", "GFLOP/s",
                       "fraction of double peak", "fraction of float peak"], rows))
    L.append("")
    L.append("The flops per body-step are those of scene a while its ragdoll is awake and on the "
             "ground; scenes with more contacts per body cost more. Runs with sleeping on are "
             "left out: sleeping bodies cost no flops.")
    L.append("")
    return L
