"""`ragdoll_batch report`: plots (PNG, matplotlib's Agg backend) and a Markdown summary of a
results CSV: the HIC15 histogram, push size against HIC15, a heat map of where and how the
ragdolls came to rest, and summary.md (counts, HIC percentiles, rest classes, broken joints,
NaN runs).
"""
import os

REST_CLASSES = ["upright", "supine", "prone", "side", "other"]
PERCENTILES = [5, 25, 50, 75, 95, 99]


def read_results(path):
    """The results CSV as a DataFrame sorted by run index."""
    import pandas as pd
    df = pd.read_csv(path, keep_default_na=False, na_values={"time_to_rest": ["nan"]})
    for c in df.columns:
        if c not in ("push_link", "rest_class", "broken_joints"):
            df[c] = pd.to_numeric(df[c], errors="coerce")
    df["broken_joints"] = df["broken_joints"].astype(str)
    return df.sort_values("index").reset_index(drop=True)


def _plots(df, out):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    import numpy as np

    paths = []
    ok = df[df["nan"] == 0]

    fig, ax = plt.subplots(figsize=(6, 4))
    hic = ok["hic15"].to_numpy(dtype=float)
    ax.hist(hic[np.isfinite(hic)], bins=30, color="#4477aa")
    ax.set_xlabel("HIC15")
    ax.set_ylabel("runs")
    ax.set_title("HIC15 of %d runs" % len(hic))
    fig.tight_layout()
    paths.append(os.path.join(out, "hic_histogram.png"))
    fig.savefig(paths[-1], dpi=100)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(6, 4))
    for cls in REST_CLASSES:
        sel = ok[ok["rest_class"] == cls]
        if len(sel):
            ax.scatter(sel["push_size"], sel["hic15"], s=10, label=cls)
    ax.set_xlabel("push size (N s)")
    ax.set_ylabel("HIC15")
    ax.set_title("push size vs HIC15, by rest pose")
    if len(ok):
        ax.legend(fontsize=8)
    fig.tight_layout()
    paths.append(os.path.join(out, "push_vs_hic.png"))
    fig.savefig(paths[-1], dpi=100)
    plt.close(fig)

    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4.5))
    x = ok["rest_x"].to_numpy(dtype=float)
    y = ok["rest_y"].to_numpy(dtype=float)
    keep = np.isfinite(x) & np.isfinite(y)
    if keep.any():
        h = left.hist2d(x[keep], y[keep], bins=25, cmap="viridis", cmin=1)
        fig.colorbar(h[3], ax=left, label="runs")
    left.set_xlabel("rest x (m)")
    left.set_ylabel("rest y (m)")
    left.set_title("where the root link came to rest")
    # rest class against push size (quintiles of the drawn sizes)
    sizes = ok["push_size"].to_numpy(dtype=float)
    edges = np.unique(np.quantile(sizes, np.linspace(0, 1, 6))) if len(sizes) else np.array([0.0])
    if len(edges) < 2:
        edges = np.array([edges[0], edges[0] + 1.0])
    counts = np.zeros((len(REST_CLASSES), len(edges) - 1))
    bins = np.clip(np.searchsorted(edges, sizes, side="right") - 1, 0, len(edges) - 2)
    for cls_i, cls in enumerate(REST_CLASSES):
        for b in bins[(ok["rest_class"] == cls).to_numpy()]:
            counts[cls_i, b] += 1
    im = right.imshow(counts, aspect="auto", cmap="magma", origin="lower")
    fig.colorbar(im, ax=right, label="runs")
    right.set_yticks(range(len(REST_CLASSES)))
    right.set_yticklabels(REST_CLASSES)
    right.set_xticks(range(len(edges) - 1))
    right.set_xticklabels(["%.0f-%.0f" % (edges[i], edges[i + 1]) for i in range(len(edges) - 1)],
                          fontsize=8)
    right.set_xlabel("push size (N s)")
    right.set_title("rest pose by push size")
    fig.tight_layout()
    paths.append(os.path.join(out, "rest_heatmap.png"))
    fig.savefig(paths[-1], dpi=100)
    plt.close(fig)
    return paths


def _fmt(v):
    """A number for the tables: whole numbers from 100 up, else 3 significant digits."""
    if v != v:
        return "-"
    return "%.0f" % v if abs(v) >= 100 else "%.3g" % v


def summary(df, source=""):
    """The Markdown summary of a results DataFrame (read_results)."""
    import numpy as np
    n = len(df)
    nan_runs = df[df["nan"] != 0]
    ok = df[df["nan"] == 0]
    lines = ["# ragdoll_batch report" + (": %s" % source if source else ""), ""]
    lines.append("- runs: %d (indices %s)" % (
        n, "%d..%d" % (df["index"].min(), df["index"].max()) if n else "none"))
    lines.append("- NaN runs: %d%s" % (len(nan_runs), " (indices %s)" % ", ".join(
        str(i) for i in nan_runs["index"].head(20)) if len(nan_runs) else ""))
    rested = np.isfinite(ok["time_to_rest"].to_numpy(dtype=float))
    lines.append("- at rest by the end: %d of %d%s" % (
        rested.sum(), len(ok), ", median time to rest %.3g s" % np.median(
            ok["time_to_rest"].to_numpy(dtype=float)[rested]) if rested.any() else ""))
    lines += ["", "## Head (runs without NaN)", "",
              "| metric | " + " | ".join("p%d" % p for p in PERCENTILES) + " | max |",
              "|---|" + "---|" * (len(PERCENTILES) + 1)]
    for col, name in (("hic15", "HIC15"), ("head_peak_g", "peak g")):
        v = ok[col].to_numpy(dtype=float)
        v = v[np.isfinite(v)]
        cells = [_fmt(np.percentile(v, p)) if len(v) else "-" for p in PERCENTILES]
        cells.append(_fmt(v.max()) if len(v) else "-")
        lines.append("| %s | %s |" % (name, " | ".join(cells)))
    lines.append("")
    for limit in (250, 700, 1000):
        lines.append("- HIC15 above %d: %d runs" % (limit, int((ok["hic15"] > limit).sum())))
    lines += ["", "## Rest pose", "", "| class | runs | share |", "|---|---|---|"]
    for cls in REST_CLASSES:
        k = int((df["rest_class"] == cls).sum())
        lines.append("| %s | %d | %.1f %% |" % (cls, k, 100.0 * k / n if n else 0.0))
    broken = df["broken_joints"].fillna("")
    per_joint = {}
    for text in broken:
        for j in filter(None, text.split(";")):
            per_joint[j] = per_joint.get(j, 0) + 1
    lines += ["", "## Broken joints", "",
              "- runs with a broken joint: %d" % int((broken != "").sum())]
    for j, k in sorted(per_joint.items(), key=lambda kv: (-kv[1], kv[0])):
        lines.append("- %s: %d" % (j, k))
    forces = [c for c in df.columns if c.startswith("force_")]
    if forces:
        lines += ["", "## Peak contact force per link (N, runs without NaN)", "",
                  "| link | median | max |", "|---|---|---|"]
        for c in forces:
            v = ok[c].to_numpy(dtype=float)
            lines.append("| %s | %s | %s |" % (c[len("force_"):],
                                              _fmt(np.median(v)) if len(v) else "-",
                                              _fmt(v.max()) if len(v) else "-"))
    lines += ["", "Plots: hic_histogram.png, push_vs_hic.png, rest_heatmap.png", ""]
    return "\n".join(lines)


def write_report(results, out=None):
    """Writes the plots and summary.md of results CSV `results` into `out`; returns the paths."""
    if out is None:
        out = os.path.splitext(results)[0] + "_report"
    os.makedirs(out, exist_ok=True)
    df = read_results(results)
    paths = _plots(df, out)
    md = os.path.join(out, "summary.md")
    with open(md, "w") as f:
        f.write(summary(df, os.path.basename(results)))
    return paths + [md]
