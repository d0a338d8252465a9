"""The ratio table and the issue's bars in bench/RESULTS.md (bench_report.py imports it).

Ours runs twice in every round of `make bench`: sleeping off (engine ragdoll_sim, the headline:
the peers' benches do not sleep) and sleeping on (ragdoll_sim_sleep), so the table gives both
ratios against each peer and against the faster of Bullet and ODE; the default solver runs the
float lanes (SolverSettings::lanes = 0). Ours with every row in double (--opt lanes=1, engine
ragdoll_sim_lanes1) runs the same way and gets a table and bars of its own. The bars are printed
as lines with the measured value beside each, so a reader sees at once which hold.
"""
import statistics
from collections import namedtuple

OURS = "ragdoll_sim"
OURS_SLEEP = "ragdoll_sim_sleep"  # ours with sleeping on, scenes a, b, c
OURS_1T = "ragdoll_sim_1thread"  # ours on one thread, scene g
OURS_L1 = "ragdoll_sim_lanes1"  # ours with SolverSettings::lanes = 1 (every row in double)
OURS_L1_SLEEP = OURS_L1 + "_sleep"
OURS_L1_1T = OURS_L1 + "_1thread"
# An engine of ours: its runs sleeping off, sleeping on and on one thread, its name in the
# tables and its bench_ragdoll --opt.
Ours = namedtuple("Ours", "off on one name opt")
OURS_VARIANTS = [Ours(OURS, OURS_SLEEP, OURS_1T, "ours", ""),
                 Ours(OURS_L1, OURS_L1_SLEEP, OURS_L1_1T, "ours lanes=1", "lanes=1")]
OURS_ALL = tuple(e for v in OURS_VARIANTS for e in (v.off, v.on, v.one))
FASTER_OF = ("bullet", "ode")  # "the faster of Bullet and ODE", per round
SLEEP_SCENES = ("a", "b", "c", "g")  # a line of ours with sleep=1 in these is OURS_SLEEP
# Speed bars of the wide solver's issue: (scene, peer or FASTER_OF, least ratio of steps/s).
SPEED_BARS = [("b", "mujoco", 8.0), ("b", FASTER_OF, 6.0), ("c", "mujoco", 7.0)]
SCALING_SPREAD_BAR = 0.30  # one-thread cost per body-step within +-30 % of its mean
SCALING_SPREAD_NS = (4, 256)  # over N = 4..256
THREADS_BAR = 1.7  # two threads >= 1.7x one thread
THREADS_MIN_N = 16  # for N >= 16


def fmt(x):
    return "-" if x != x else "{:.2f}".format(x)


def per_round(groups, key):
    g = groups.get(key)
    return dict(g.by_round) if g else {}


def faster_of(groups, scene, n, peers):
    """Steps/s per round of the faster of the peers that ran (the larger steps/s in each round)."""
    rounds = {}
    for p in peers:
        for r, sps in per_round(groups, (p, scene, n)).items():
            rounds[r] = max(rounds.get(r, 0.0), sps)
    return rounds


def ratio_rounds(num, den):
    """Ratio of the medians and min-max of the per-round ratios of two {round: steps/s}."""
    common = [r for r in num if r in den and den[r] > 0]
    if not common:
        return float("nan"), float("nan"), float("nan")
    med = statistics.median(num[r] for r in common) / statistics.median(den[r] for r in common)
    per = [num[r] / den[r] for r in common]
    return med, min(per), max(per)


def cell(groups, ours, scene, n, peer, peers):
    num = per_round(groups, (ours, scene, n))
    den = faster_of(groups, scene, n, peers) if peer == FASTER_OF else per_round(
        groups, (peer, scene, n))
    med, lo, hi = ratio_rounds(num, den)
    return (med, lo, hi), ("-" if med != med else "%s (%s–%s)" % (fmt(med), fmt(lo), fmt(hi)))


def table(groups, peers, names, scene_order, label, failed, variant=OURS_VARIANTS[0]):
    """The ratio table of one engine of ours (OURS_VARIANTS): one row per scene it and a peer
    both ran, for every peer a column sleep off and one sleep on, then the faster of Bullet and
    ODE."""
    off, on, who = variant.off, variant.on, variant.name
    scenes = sorted({(s, n) for (e, s, n) in groups if e in (off, on) and
                     any((p, s, n) in groups for p in peers)},
                    key=lambda t: (scene_order.index(t[0]) if t[0] in scene_order else 99, t[1] or 0))
    fast = [p for p in peers if p in FASTER_OF]
    columns = [(p, names.get(p, p)) for p in peers]
    if len(fast) == len(FASTER_OF):
        columns.append((FASTER_OF, "the faster of %s" % " and ".join(names.get(p, p) for p in fast)))
    header = ["scene"]
    for _, name in columns:
        header += ["%s ÷ %s, sleep off" % (who, name), "sleep on"]
    rows = []
    for s, n in scenes:
        row = [label(s, n)]
        for peer, _ in columns:
            for ours in (off, on):
                text = cell(groups, ours, s, n, peer, fast)[1]
                if text == "-" and peer != FASTER_OF and (ours, s, n) in groups and failed(peer, s, n):
                    text = "%s failed" % names.get(peer, peer)
                row.append(text)
        rows.append(row)
    return header, rows


def speed_bar_lines(groups, peers, names):
    fast = [p for p in peers if p in FASTER_OF]
    out = []
    for scene, peer, bar in SPEED_BARS:
        if peer == FASTER_OF and len(fast) < len(FASTER_OF) or peer != FASTER_OF and peer not in peers:
            continue
        pname = ("the faster of %s" % " and ".join(names.get(p, p) for p in fast)
                 if peer == FASTER_OF else names.get(peer, peer))
        for v in OURS_VARIANTS:
            (med, lo, hi), text = cell(groups, v.off, scene, None, peer, fast)
            if med != med:
                continue
            on_text = cell(groups, v.on, scene, None, peer, fast)[1]
            out.append("- %s: %s ÷ %s ≥ %.0fx: sleep off %s, %s; sleep on %s" % (
                scene, v.name, pname, bar, text, "met" if med >= bar else "not met", on_text))
    return out


def scaling_bar_lines(groups, own_threads, variant=OURS_VARIANTS[0]):
    """One-thread cost per body-step over N = 4..256 (mean, largest deviation) and the speed of
    one engine of ours on OWN_THREADS threads over one thread for N >= 16, both from scene g;
    the lines of the engines other than the default start with their name."""
    off, one = variant.off, variant.one
    lead = variant.opt + ", " if variant.opt else ""
    out = []
    lo_n, hi_n = SCALING_SPREAD_NS
    pts = sorted((n, g.us_med) for (e, s, n), g in groups.items()
                 if e == one and s == "g" and lo_n <= n <= hi_n)
    if len(pts) > 1:
        mean = sum(u for _, u in pts) / len(pts)
        worst_n, worst = max(pts, key=lambda t: abs(t[1] / mean - 1))
        dev = worst / mean - 1
        out.append("- %sone thread, cost per body-step for N = %s: mean %.3f µs, largest deviation "
                   "%+.0f %% (N = %d); bar ±%.0f %%: %s" % (
                       lead, ", ".join(str(n) for n, _ in pts), mean, 100 * dev, worst_n,
                       100 * SCALING_SPREAD_BAR,
                       "met" if abs(dev) <= SCALING_SPREAD_BAR else "not met"))
    ns = sorted(n for (e, s, n) in groups if e == off and s == "g" and n >= THREADS_MIN_N and
                (one, "g", n) in groups)
    for n in ns:
        med, lo, hi = ratio_rounds(per_round(groups, (off, "g", n)),
                                   per_round(groups, (one, "g", n)))
        out.append("- %s%s threads ÷ one thread, N = %d: %s (%s–%s); bar ≥ %.1fx: %s" % (
            lead, own_threads, n, fmt(med), fmt(lo), fmt(hi), THREADS_BAR,
            "met" if med >= THREADS_BAR else "not met"))
    return out


def section(groups, engines, names, scene_order, md_table, label, failed):
    peers = [e for e in engines if e not in OURS_ALL]
    L = []
    for variant in OURS_VARIANTS:
        if not (variant.off in engines or variant.on in engines) or not peers:
            continue
        if not L:
            L += ["## Speed of ours relative to each peer", "",
                  "ragdoll_sim steps/s ÷ peer steps/s (> 1: ours is faster), ours with sleeping "
                  "off (the peers' benches do not sleep) and, beside it, with sleeping on (the "
                  "engine's default), both run in the same alternating rounds. First the ratio "
                  "of the medians, then in brackets the min–max of the per-round ratios; the "
                  "faster of Bullet and ODE is the one with more steps/s in each round.", ""]
        if variant.opt:
            L += ["The same for \"%s\": ours with `--opt %s` (engines %s and %s), run in the "
                  "same rounds:" % (variant.name, variant.opt, variant.off, variant.on), ""]
        header, rows = table(groups, peers, names, scene_order, label, failed, variant)
        L += [md_table(header, rows), ""]
    return L


def bars_section(groups, engines, names, meta):
    peers = [e for e in engines if e not in OURS_ALL]
    L = []
    bars = speed_bar_lines(groups, peers, names)
    scaling = [l for v in OURS_VARIANTS
               for l in scaling_bar_lines(groups, meta.get("own_threads", "?"), v)]
    if bars or scaling:
        L += ["## Bars of the wide solver's issue", ""]
        L += ["Speed against the peers (scene, ratio of the medians with the per-round min–max):",
              ""] + bars + [""] if bars else []
        ones = [v for v in OURS_VARIANTS if any(k[0] == v.one for k in groups)]
        L += ["Scaling, scene g, sleeping off (%s):" % ", ".join(
                  "%s: %s with threads=1" % (v.one, v.name) for v in ones),
              ""] + scaling + [""] if scaling else []
    return L
