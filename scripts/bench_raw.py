"""The raw lines of the benchmark scripts (bench.sh, bench_compare.sh): one `key=value` line per
run (`engine=...`), `# meta key=value`, `# FAILED ...` and `# ensemble ...` lines. Standard
library only; shared by the report scripts.
"""
from collections import OrderedDict


def parse_kv(text):
    """'a=1 b=x' -> OrderedDict(a='1', b='x'); tokens without '=' are skipped."""
    d = OrderedDict()
    for tok in text.split():
        if "=" in tok:
            k, v = tok.split("=", 1)
            d[k] = v
    return d


def fnum(x):
    """float(x), or NaN for a missing or non-numeric field."""
    try:
        return float(x)
    except (TypeError, ValueError):
        return float("nan")


def parse(lines):
    """(meta, runs, failures) of raw lines; `# ensemble` lines go to meta['ensembles']."""
    meta, runs, failures = OrderedDict(), [], []
    for raw in lines:
        line = raw.strip()
        if line.startswith("# meta "):
            k, _, v = line[len("# meta "):].partition("=")
            meta[k.strip()] = v.strip()
        elif line.startswith("# FAILED"):
            failures.append(parse_kv(line[len("# FAILED"):]))
        elif line.startswith("# ensemble "):
            meta.setdefault("ensembles", []).append(parse_kv(line[len("# ensemble "):]))
        elif line.startswith("engine="):
            runs.append(parse_kv(line))
    return meta, runs, failures


def sync_lines(meta):
    """The two-thread handoffs and the cores' ceiling measured before each round (bench.sh,
    bench_compare.sh: `# meta sync_round_R`), as list items; none in an older raw file."""
    rounds = sorted((int(k[len("sync_round_"):]), parse_kv(v))
                    for k, v in meta.items() if k.startswith("sync_round_"))
    if not rounds:
        return []
    cells = ["round %d %s / %s" % (r, kv.get("region_us", "?"), kv.get("barrier_us", "?"))
             for r, kv in rounds]
    out = ["- two-thread handoffs before each round (an empty parallel region / a TeamBarrier "
           "wait, µs; `bench_ragdoll sync`): " + ", ".join(cells) + ". Where they cost more, "
           "the threads talk over a slower link (on a VM: vCPUs on different core complexes) "
           "and that round's two-thread figures are lower."]
    ceilings = [(r, kv) for r, kv in rounds if "ceiling" in kv]
    if ceilings:
        cells = ["round %d %s (%s + %s)" % (r, kv["ceiling"], kv.get("core0", "?"),
                                            kv.get("core1", "?")) for r, kv in ceilings]
        out.append("- two-thread ceiling before each round (`bench_ragdoll sync`: scene g with 8 "
                   "ragdolls on each of two threads at once, each thread's speed over one "
                   "thread's alone, summed): " + ", ".join(cells) + ". What two threads can "
                   "gain over one on work that fits each core's cache; a larger world can gain "
                   "more, its halves fitting caches its whole does not.")
    return out
