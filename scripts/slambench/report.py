"""The benchmark's table (Markdown) and plots (ATE per family; trajectories against ground truth)."""
import os

import numpy as np


def _fmt(stat, scale=1.0, digits=1, spread=True):
    if stat is None:
        return "-"
    median, low, high = (stat[k] * scale for k in ("median", "min", "max"))
    if not np.isfinite(median):
        return "fail"
    text = f"{median:.{digits}f}"
    if spread:
        text += f" ({low:.{digits}f}-{high:.{digits}f})" if np.isfinite(high) else f" ({low:.{digits}f}-fail)"
    return text


def table(summaries, variants):
    """summaries[(family, sensor, variant)] -> summarise() dicts. One row per cell."""
    lines = ["| family | sensor | extractor | runs | ATE mm, median (min-max) | keyframe ATE mm | frames tracked % | lost | map resets | keyframes | extractor ms/frame | tracking ms/frame median | p95 |",
             "|---|---|---|---|---|---|---|---|---|---|---|---|---|"]
    for (family, sensor, variant), s in summaries.items():
        lines.append("| " + " | ".join([
            family, sensor, variant, f"{s['runs']}" + (f" ({s['failed']} failed)" if s["failed"] else ""),
            _fmt(s.get("ate"), 1000), _fmt(s.get("ate_kf"), 1000, spread=False), _fmt(s.get("tracked_share"), 100, 0),
            _fmt(s.get("lost"), 1, 0, False), _fmt(s.get("map_resets"), 1, 0, False), _fmt(s.get("keyframes"), 1, 0),
            _fmt(s.get("extract_ms_median"), 1, 1, False), _fmt(s.get("track_ms_median"), 1, 1, False),
            _fmt(s.get("track_ms_p95"), 1, 1, False)]) + " |")
    return "\n".join(lines) + "\n"


def plot_ate(summaries_runs, families, variants, sensor, out_path):
    """ATE of every run, per family, variants side by side (log scale; failures drawn at the top)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    crowded = len(families) > 8
    fig, ax = plt.subplots(figsize=(max(10, 0.75 * len(families)), 4.8 if crowded else 4.2))
    width = 0.8 / max(1, len(variants))
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    finite = [r["ate"] * 1000 for runs in summaries_runs.values() for r in runs if r.get("ate") is not None]
    ceiling = max(finite) * 2 if finite else 1.0
    for v, variant in enumerate(variants):
        for f, family in enumerate(families):
            runs = summaries_runs.get((family, sensor, variant), [])
            values = [r["ate"] * 1000 if r.get("ate") is not None else ceiling for r in runs]
            x = f + (v - (len(variants) - 1) / 2) * width
            ax.scatter(np.full(len(values), x), values, color=colours[v % len(colours)], s=18, label=variant if f == 0 else None)
            if values:
                ax.hlines(np.median(values), x - width / 2.5, x + width / 2.5, color=colours[v % len(colours)])
    ax.set_xticks(range(len(families)))
    pooled = all(family.startswith("pooled/") for family in families)
    ax.set_xticklabels([family.removeprefix("pooled/") for family in families], rotation=35 if crowded else 0,
                       ha="right" if crowded else "center", fontsize=9)
    ax.set_yscale("log")
    ax.set_ylabel("ATE, mm (all frames; failures at the top)")
    ax.set_title(f"ORB-SLAM3 {sensor}: ATE per run{' (every seed)' if pooled else ''}, median as a bar "
                 f"({'Sim(3)' if sensor == 'mono' else 'SE(3)'} alignment)")
    ax.legend(fontsize=8, ncol=max(1, (len(variants) + 3) // 4))
    ax.grid(True, which="both", axis="y", alpha=0.3)
    for boundary in range(1, len(families)):
        ax.axvline(boundary - 0.5, color="grey", lw=0.5, alpha=0.4)
    fig.tight_layout()
    fig.savefig(out_path, dpi=90)
    plt.close(fig)


def plot_trajectories(aligned_by_variant, family, sensor, out_path):
    """Top view (x, y) of ground truth and each variant's median-ATE run, aligned."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(5.5, 4.5))
    drew_truth = False
    for variant, path in aligned_by_variant.items():
        if path is None or not os.path.exists(path):
            continue
        data = np.load(path)
        if not drew_truth:
            ax.plot(data[:, 3], data[:, 4], color="black", lw=2.5, alpha=0.35, label="ground truth")
            drew_truth = True
        ax.plot(data[:, 0], data[:, 1], lw=1, label=variant)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("x, m")
    ax.set_ylabel("y, m")
    ax.set_title(f"{family}, {sensor}: median-ATE run of each extractor", fontsize=9)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out_path, dpi=80)
    plt.close(fig)
