"""The benchmark's table (markdown) from its rows: one per scene and method."""

COLUMNS = [
    ("scene", "scene", "{}"),
    ("method", "method", "{}"),
    ("keypoints_per_image", "keypoints / image", "{:.0f}"),
    ("registered", "registered", "{}"),
    ("points", "3D points", "{}"),
    ("points_vs_sift", "points / SIFT's", "{:.2f}"),
    ("track_length", "track length", "{:.2f}"),
    ("reprojection_error_px", "reproj. error px", "{:.3f}"),
    ("verified_pct", "verified %", "{:.1f}"),
    ("position_error_median_pct", "position error % (median)", "{:.3f}"),
    ("rotation_error_median_deg", "rotation error deg (median)", "{:.3f}"),
    ("extract_s", "extract s", "{:.1f}"),
    ("extract_speedup", "extraction x SIFT's speed", "{:.0f}"),
    ("match_s", "match s", "{:.1f}"),
    ("verify_s", "verify s", "{:.1f}"),
    ("mapper_s", "mapper s", "{:.1f}"),
]


def _cell(row, key, form):
    value = row.get(key)
    if value is None:
        return "-"
    return form.format(value)


def relate_to_sift(rows, sift_method):
    """Adds points_vs_sift and extract_speedup to each row of a scene that has `sift_method`."""
    reference = {row["scene"]: row for row in rows if row["method"] == sift_method and "error" not in row}
    for row in rows:
        sift = reference.get(row["scene"])
        if sift is None or "error" in row:
            continue
        if sift.get("points"):
            row["points_vs_sift"] = row["points"] / sift["points"]
        if row.get("extract_s") and sift.get("extract_s"):
            row["extract_speedup"] = sift["extract_s"] / row["extract_s"]


def markdown_table(rows):
    lines = ["| " + " | ".join(title for _, title, _ in COLUMNS) + " |",
             "|" + "---|" * len(COLUMNS)]
    for row in rows:
        if "error" in row:
            lines.append(f"| {row['scene']} | {row['method']} | failed: {row['error']} |")
            continue
        lines.append("| " + " | ".join(_cell(row, key, form) for key, _, form in COLUMNS) + " |")
    return "\n".join(lines) + "\n"
