"""Each variant against the reference extractor (stock ORB-SLAM3), judged by the targets docs/slam.md sets.

One table per variant, one row per family and sensor, from the cells' summaries (pooled over the
seeds where there are several): the share of frames tracked beside the reference's, the median
ATE as a ratio of the reference's, how many times faster the extractor is and the tracking time
per frame as a ratio; then the verdict on each target. The targets are written here once:
"""
import numpy as np

# The paper's four hard families and the scene the entropy mask was made for.
HARD_FAMILIES = ("light_change", "weak_texture", "fast_rotation", "low_light", "blank_walls")
# Families where the extractor should change nothing.
PLAIN_FAMILIES = ("baseline", "motion_blur")
HARD_ATE_RATIO = 0.8          # median ATE at most this times the reference's ...
HARD_CELLS_AT_RATIO = 7       # ... in at least this many of the hard cells (5 families x 2 sensors),
HARD_ATE_CEILING = 1.1        # and never above this.
PLAIN_ATE_TOLERANCE = 0.05    # baseline and motion_blur: at most 5% above the reference (lower is no fault).
EXTRACTOR_SPEEDUP = 4.0       # extractor at least 4x faster in every cell,
# and tracking time per frame lower than the reference's in every cell.


def _median(summary, field):
    value = (summary or {}).get(field)
    return None if value is None else value["median"]


def ate_ratio(summary, reference):
    """Median ATE over the reference's; inf when the variant's median run failed and the
    reference's did not, 1 when both failed, None when a cell is missing."""
    mine, theirs = _median(summary, "ate"), _median(reference, "ate")
    if mine is None or theirs is None:
        return None
    if not np.isfinite(theirs) or theirs == 0:
        return 1.0 if mine == theirs else (0.0 if mine < theirs else np.inf)
    return mine / theirs if np.isfinite(mine) else np.inf


def family_of(cell_family):
    """"pooled/low_light" or "s23/low_light" -> "low_light"."""
    return cell_family.rsplit("/", 1)[-1]


def rows(summaries, variant, reference):
    """(family, sensor) -> figures of `variant` against `reference`, over the pooled rows when
    there are any (several seeds), else over every family."""
    cells = {(f, s) for (f, s, v) in summaries if v == variant}
    pooled = {c for c in cells if c[0].startswith("pooled/")}
    out = {}
    for family, sensor in sorted(pooled or cells, key=lambda c: (c[1], c[0])):
        mine, theirs = summaries.get((family, sensor, variant)), summaries.get((family, sensor, reference))
        if theirs is None:
            continue
        extract = (_median(mine, "extract_ms_median"), _median(theirs, "extract_ms_median"))
        track = (_median(mine, "track_ms_median"), _median(theirs, "track_ms_median"))
        seeds = sorted(f for (f, s, v) in summaries if v == variant and s == sensor and not f.startswith("pooled/")
                       and "/" in f and family_of(f) == family_of(family))
        out[(family_of(family), sensor)] = dict(
            seed_ratios=[(f.split("/", 1)[0], ate_ratio(summaries[(f, sensor, variant)], summaries.get((f, sensor, reference))))
                         for f in seeds] if family.startswith("pooled/") else [],
            runs=(mine["runs"], theirs["runs"]),
            tracked=(_median(mine, "tracked_share"), _median(theirs, "tracked_share")),
            ate=(_median(mine, "ate"), _median(theirs, "ate")),
            ate_ratio=ate_ratio(mine, theirs),
            extractor_speedup=extract[1] / extract[0] if None not in extract and extract[0] > 0 else None,
            tracking_ratio=track[0] / track[1] if None not in track and track[1] > 0 else None)
    return out


def verdicts(figures):
    """The targets, each as (name, met: bool or None when not measured, why)."""
    result = []
    tracked = [(c, f) for c, f in figures.items() if None not in f["tracked"]]
    behind = [f"{c[0]} {c[1]}" for c, f in tracked if f["tracked"][0] < f["tracked"][1]]
    result.append(("frames tracked >= reference in every cell", not behind if tracked else None,
                   "behind in " + ", ".join(behind) if behind else f"{len(tracked)} cells"))
    hard = {c: f["ate_ratio"] for c, f in figures.items() if c[0] in HARD_FAMILIES and f["ate_ratio"] is not None}
    good = sum(1 for r in hard.values() if r <= HARD_ATE_RATIO)
    worst = max(hard.values(), default=None)
    result.append((f"hard families: ATE <= {HARD_ATE_RATIO}x in >= {HARD_CELLS_AT_RATIO} of "
                   f"{2 * len(HARD_FAMILIES)} cells, never above {HARD_ATE_CEILING}x",
                   (good >= HARD_CELLS_AT_RATIO and worst <= HARD_ATE_CEILING) if len(hard) == 2 * len(HARD_FAMILIES) else None,
                   f"{good} of {len(hard)} measured cells at or below {HARD_ATE_RATIO}x, worst {worst:.2f}x" if hard else "not measured"))
    plain = {c: f["ate_ratio"] for c, f in figures.items() if c[0] in PLAIN_FAMILIES and f["ate_ratio"] is not None}
    off = [f"{c[0]} {c[1]} {r:.2f}x" for c, r in plain.items() if r > 1 + PLAIN_ATE_TOLERANCE]
    result.append((f"baseline and motion_blur: ATE at most {PLAIN_ATE_TOLERANCE:.0%} above the reference's",
                   (not off) if len(plain) == 2 * len(PLAIN_FAMILIES) else None,
                   ("outside in " + ", ".join(off)) if off else f"{len(plain)} cells"))
    speed = {c: f["extractor_speedup"] for c, f in figures.items() if f["extractor_speedup"] is not None}
    result.append((f"extractor >= {EXTRACTOR_SPEEDUP:g}x faster in every cell",
                   all(s >= EXTRACTOR_SPEEDUP for s in speed.values()) if speed else None,
                   f"{min(speed.values()):.1f}-{max(speed.values()):.1f}x" if speed else "not timed"))
    track = {c: f["tracking_ratio"] for c, f in figures.items() if f["tracking_ratio"] is not None}
    result.append(("tracking time per frame lower in every cell", all(t < 1 for t in track.values()) if track else None,
                   f"{min(track.values()):.2f}-{max(track.values()):.2f}x the reference's" if track else "not timed"))
    return result


def _number(value, digits=2, suffix=""):
    if value is None:
        return "-"
    return "fail" if not np.isfinite(value) else f"{value:.{digits}f}{suffix}"


def markdown(summaries, variants, reference):
    """Every variant but the reference, each as a table of cells and a list of verdicts."""
    text = [f"# Against `{reference}`, pooled over the seeds\n"]
    for variant in variants:
        if variant == reference:
            continue
        figures = rows(summaries, variant, reference)
        if not figures:
            continue
        text.append(f"## `{variant}`\n")
        text.append(f"| family | sensor | runs | tracked % ({variant} / {reference}) | ATE mm ({variant} / {reference}) | "
                    "ATE ratio | per seed | extractor speed-up | tracking time ratio |")
        text.append("|---|---|---|---|---|---|---|---|---|")
        for (family, sensor), f in figures.items():
            tracked = "/".join(_number(None if t is None else 100 * t, 0) for t in f["tracked"])
            ate = "/".join(_number(None if a is None else 1000 * a, 1) for a in f["ate"])
            text.append(f"| {family} | {sensor} | {f['runs'][0]}/{f['runs'][1]} | {tracked} | {ate} | "
                        f"{_number(f['ate_ratio'])} | {', '.join(f'{seed} {_number(r)}' for seed, r in f['seed_ratios']) or '-'} | "
                        f"{_number(f['extractor_speedup'], 1, 'x')} | {_number(f['tracking_ratio'])} |")
        text.append("")
        for name, met, why in verdicts(figures):
            mark = "not measured" if met is None else ("met" if met else "NOT met")
            text.append(f"- {name}: **{mark}** ({why})")
        text.append("")
    return "\n".join(text) + "\n"
