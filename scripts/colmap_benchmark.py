#!/usr/bin/python3
"""aief's COLMAP route against COLMAP's own SIFT on real photographs with ground-truth cameras, in
the same run (docs/colmap.md).

  colmap_benchmark.py --scene DATA/castle-P19 --scene DATA/entry-P10 ... --out OUT
                      [--n-features 8000] [--threads 2] [--aief build/aief] [--colmap colmap]
                      [--method NAME=aief[:EXTRACT FLAGS][;MATCH FLAGS]] [--method NAME=sift[:FLAGS]]

A scene is a folder in Strecha's layout (images/, gt_dense_cameras/*.camera: openMVG's
SfM_quality_evaluation holds castle-P19, castle-P30, entry-P10, Herz-Jesus-P25 and fountain-P11);
the data are not part of this repository. Methods default to
  aief-default=aief   aief-quality=aief:--mode quality
  aief-sfm=aief:--descriptor box --n-levels 5 --n-features 10400;--matcher guided
    (docs/colmap.md's recipe for SfM)   sift=sift
aief's route: extract --batch --format h5, match --pairs over every pair, colmap, then COLMAP's
matches_importer (two-view verification) and mapper; SIFT's: feature_extractor (CPU,
SIMPLE_RADIAL, --SiftExtraction.max_num_features = --n-features), exhaustive_matcher, mapper. Every
method gets --n-features keypoints an image unless its flags say otherwise.

Per scene and method: keypoints an image, registered images, 3D points, mean track length, mean
reprojection error (COLMAP's: the mean of the points' errors), the share of the database's matches
that survived the verification (two_view_geometries rows / matches rows), the median camera
position error after the similarity (Umeyama) that maps the model's centres onto the ground truth,
as % of the largest distance between two ground-truth centres, the median rotation error in
degrees, and each step's seconds. Writes OUT/results.json and OUT/table.md. Steps already done
with the same command and inputs are kept (OUT/SCENE/METHOD/*.done.json); the script installs
nothing and says which binary is missing.
"""
import argparse
import json
import os
import platform
import shutil
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from colmapbench import metrics, pipelines, report  # noqa: E402
from colmapbench.runner import StepFailed  # noqa: E402
from colmapbench.scenes import read_scene  # noqa: E402

# The default and quality modes as they come, the recipe docs/colmap.md recommends for SfM, SIFT.
DEFAULT_METHODS = ["aief-default=aief", "aief-quality=aief:--mode quality",
                   "aief-sfm=aief:--descriptor box --n-levels 5 --n-features 10400;--matcher guided",
                   "sift=sift"]


def find_binary(given, name, how):
    path = shutil.which(given)
    if path is None:
        sys.exit(f"colmap_benchmark: {given!r} not found: {how}")
    return path


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--scene", action="append", required=True, help="a scene folder (Strecha's layout)")
    parser.add_argument("--out", required=True)
    parser.add_argument("--n-features", type=int, default=8000, help="keypoints an image, every method")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--aief", default="aief", help="the aief binary (default: aief on PATH)")
    parser.add_argument("--colmap", default="colmap", help="the colmap binary (default: colmap on PATH)")
    parser.add_argument("--method", action="append", help="NAME=aief[:EXTRACT FLAGS][;MATCH FLAGS] "
                        "or NAME=sift[:FLAGS]; default: " + "  ".join(DEFAULT_METHODS))
    parser.add_argument("--timeout", type=float, default=7200.0, help="seconds a step may take")
    args = parser.parse_args()
    try:
        methods = [pipelines.parse_method(text) for text in (args.method or DEFAULT_METHODS)]
        scenes = [read_scene(folder) for folder in args.scene]
    except ValueError as error:
        parser.error(str(error))
    if len({m.name for m in methods}) != len(methods):
        parser.error("two methods of the same name")
    binaries = {"colmap": find_binary(args.colmap, "colmap", "install COLMAP (Debian: apt-get install "
                                      "colmap) or name it with --colmap")}
    if any(m.kind == "aief" for m in methods):
        binaries["aief"] = find_binary(args.aief, "aief", "build aief (cmake --build build --target "
                                       "aief_cli) and name it with --aief build/aief")
    environment = dict(os.environ, QT_QPA_PLATFORM="offscreen")  # COLMAP without a display
    sift_method = next((m.name for m in methods if m.kind == "sift"), None)
    rows = []
    for scene in scenes:
        scene_folder = os.path.join(args.out, scene.name)
        images = pipelines.stage_images(scene, os.path.join(scene_folder, "images"))
        pipelines.write_pairs(os.path.join(scene_folder, "pairs.txt"), scene.images)
        for method in methods:
            run = pipelines.run_aief if method.kind == "aief" else pipelines.run_sift
            print(f"{scene.name} / {method.name} ...", flush=True)
            row = {"scene": scene.name, "method": method.name, "kind": method.kind,
                   "extract_flags": method.extract, "match_flags": method.match}
            try:
                model, models, database, seconds = run(method, scene, images, scene_folder, binaries,
                                                       args.n_features, args.threads, environment)
            except StepFailed as error:
                print(f"  failed: {error}", flush=True)
                row["error"] = str(error).splitlines()[0]
                rows.append(row)
                continue
            verified, imported = metrics.verified_share(database)
            row.update({"keypoints_per_image": metrics.keypoints_per_image(database),
                        "models": models, "matches_imported": imported, "matches_verified": verified,
                        "verified_pct": 100.0 * verified / imported if imported else None})
            if model is None:
                row.update({"images": len(scene.images), "registered": 0, "points": 0})
            else:
                row.update(metrics.model_summary(model, scene))
            row.update({f"{step}_s": value for step, value in seconds.items()
                        if step in ("extract", "match", "verify", "mapper")})
            row["colmap_export_s"] = seconds.get("colmap_export")
            rows.append(row)
            print("  " + ", ".join(f"{k} {v:.3g}" if isinstance(v, float) else f"{k} {v}"
                                   for k, v in row.items() if k not in ("scene", "method", "kind")), flush=True)
    if sift_method:
        report.relate_to_sift(rows, sift_method)
    os.makedirs(args.out, exist_ok=True)
    about = {"date_utc": time.strftime("%Y-%m-%d %H:%M", time.gmtime()), "machine": platform.machine(),
             "cpus": os.cpu_count(), "processor": platform.processor(), "features": args.n_features,
             "threads": args.threads, "binaries": binaries}
    with open(os.path.join(args.out, "results.json"), "w") as handle:
        json.dump({"about": about, "rows": rows}, handle, indent=1)
    with open(os.path.join(args.out, "table.md"), "w") as handle:
        handle.write(report.markdown_table(rows))
    print(report.markdown_table(rows))


if __name__ == "__main__":
    main()
