#!/usr/bin/python3
"""ORB-SLAM3 with its own extractor and with the aief drop-in, on scripts/make_sequences.py's
sequences: ATE, frames tracked, losses, keyframes, tracking and extraction time (docs/slam.md).

  slam_benchmark.py --stock ORB_SLAM3_STOCK --aief ORB_SLAM3_AIEF --vocabulary VOC.txt \
                    --sequences SEQ_DIR [--sequences SEQ_DIR_2 ...] --out OUT [--runs 5] [--families a,b]
                    [--sensors mono,stereo]
                    [--variant NAME=BUILD[:KEY=VALUE;KEY=VALUE]]...

--stock / --aief: ORB-SLAM3 folders whose Examples/Monocular/mono_euroc and
Examples/Stereo/stereo_euroc were built (stock, and with the drop-in; compile with
-DREGISTER_TIMES for the timing columns). Variants default to "stock=stock" and
"aief=aief:ORBextractor.threads=1"; extra keys go into a copy of the sequence's settings file.
Runs are interleaved across variants and cells (run 1 of every cell, then run 2...) so that the
load of the machine falls on all of them alike and a stopped benchmark leaves every cell with as
many runs as possible; finished runs are kept and skipped when re-run.
Sequences as scripts/make_sequences.py writes them (EuRoC and TUM files together in a family
folder) or split into its euroc/ and tum/ sub-folders (slambench/sequences.py); an incomplete one
is named with what it lacks, and a program that cannot load its libraries is refused before any
run (set LD_LIBRARY_PATH), so nothing runs that cannot be scored.
--sequences once per seed (each a folder of family folders, e.g. make_sequences.py OUT/s23 --seed
23): cells are then named SEED/family (SEED the folder's name) and the report adds a "pooled/family"
row per sensor and variant, the median and range over the runs of every seed together.
Writes OUT/results.json, OUT/table.md, OUT/targets.md (each variant against the first stock one,
by the targets of docs/slam.md), OUT/plots/*.png (ATE per run: per cell, and per family over the
seeds as ate_SENSOR_pooled.png; trajectories).
"""
import argparse
import dataclasses
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from slambench import evaluate, orbslam3, report, targets, sequences as sequence_files  # noqa: E402


def parse_variant(text):
    name, _, rest = text.partition("=")
    build, _, keys = rest.partition(":")
    if not name or build not in ("stock", "aief"):
        raise argparse.ArgumentTypeError(f"variant {text!r}: expected NAME=stock|aief[:KEY=VALUE;...]")
    extra = {}
    for item in filter(None, keys.split(";")):
        key, sep, value = item.partition("=")
        if not sep:
            raise argparse.ArgumentTypeError(f"variant {text!r}: {item!r} is not KEY=VALUE")
        extra[key] = value
    return name, build, extra


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--stock", required=True)
    parser.add_argument("--aief", required=True)
    parser.add_argument("--vocabulary", required=True)
    parser.add_argument("--sequences", required=True, action="append",
                        help="a folder of family folders; once per seed to run several seeds and pool them")
    parser.add_argument("--out", required=True)
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--families", default=None, help="default: every folder of --sequences")
    parser.add_argument("--sensors", default="mono,stereo")
    parser.add_argument("--variant", action="append", type=parse_variant)
    parser.add_argument("--timeout", type=float, default=600.0)
    parser.add_argument("--report-only", action="store_true", help="summarise the runs already in OUT")
    args = parser.parse_args()
    variants = args.variant or [("stock", "stock", {}), ("aief", "aief", {"ORBextractor.threads": "1"})]
    sensors = args.sensors.split(",")
    if unknown := [s for s in sensors if s not in orbslam3.PROGRAMS]:
        parser.error(f"unknown sensors {unknown}; known: {sorted(orbslam3.PROGRAMS)}")
    if not os.path.exists(args.vocabulary):
        parser.error(f"no vocabulary at {args.vocabulary}")
    builds = {"stock": args.stock, "aief": args.aief}
    programs = {}
    if not args.report_only:
        try:
            programs = {(build, sensor): orbslam3.program_path(root, sensor) for build, root in builds.items() for sensor in sensors
                        if any(v[1] == build for v in variants)}
        except FileNotFoundError as error:
            parser.error(str(error))
        for program in sorted(set(programs.values())):
            if missing := orbslam3.missing_libraries(program):
                parser.error(f"{program} cannot load {', '.join(missing)}: set LD_LIBRARY_PATH to the folders holding them "
                             "(e.g. Pangolin's lib/ when ORB-SLAM3 was built against an installed Pangolin)")
    try:
        found = find_seeds(args.sequences, args.families.split(",") if args.families else None, sensors)
    except sequence_files.SequenceError as error:
        parser.error(str(error))
    families = [sequence.name for sequence in found]
    by_name = {sequence.name: sequence for sequence in found}

    # Run k of every cell before run k + 1 of any: stopped early, every cell has as many runs as possible.
    for run in range(args.runs if not args.report_only else 0):
        for family in families:
            sequence = by_name[family]
            for sensor in sensors:
                for name, build, extra in variants:
                    workdir = os.path.join(args.out, "runs", family, sensor, name, f"{run:02d}")
                    if os.path.exists(os.path.join(workdir, "result.json")):
                        continue
                    os.makedirs(workdir, exist_ok=True)
                    settings = os.path.join(workdir, "settings.yaml")
                    orbslam3.write_settings(sequence.settings[sensor], extra, settings)
                    code, seconds = orbslam3.run(programs[(build, sensor)], os.path.abspath(args.vocabulary), settings, sequence, workdir, args.timeout)
                    result = evaluate.evaluate_run(workdir, sequence.ground_truth, sensor, code, seconds)
                    json.dump(result, open(os.path.join(workdir, "result.json"), "w"), indent=1)
                    ate = "fail" if result["ate"] is None else f"{result['ate'] * 1000:.1f} mm"
                    print(f"{family} {sensor} {name} run {run}: ATE {ate}, tracked {result['tracked_share']:.0%}, "
                          f"keyframes {result['keyframes']}, {seconds:.0f} s", flush=True)
    reference = next((name for name, build, _ in variants if build == "stock"), None)
    write_report(args.out, families, sensors, [v[0] for v in variants], by_name, reference)


def find_seeds(roots, names, sensors):
    """The sequences of every root; with more than one root, each named ROOT/family after its root's
    folder (a seed), so that the cells of different seeds stay apart and can be pooled."""
    if len(roots) == 1:
        return sequence_files.find_all(roots[0], names, sensors)
    labels = [os.path.basename(os.path.normpath(root)) for root in roots]
    if len(set(labels)) != len(labels):
        raise sequence_files.SequenceError(f"--sequences folders must have different names (one per seed): {labels}")
    found = []
    for root, label in zip(roots, labels):
        found += [dataclasses.replace(sequence, name=f"{label}/{sequence.name}")
                  for sequence in sequence_files.find_all(root, names, sensors)]
    return found


def pooled_family(name):
    """"s23/baseline" -> "pooled/baseline"; None for a family of a single --sequences folder."""
    return "pooled/" + name.split("/", 1)[1] if "/" in name else None


def write_report(out, families, sensors, variant_names, sequences, reference):
    """sequences: family name -> slambench.sequences.Sequence; reference: the variant the others are
    judged against in targets.md (the first on the stock build), or None."""
    runs, summaries = {}, {}
    for family in families:
        for sensor in sensors:
            for name in variant_names:
                cell = evaluate.load_runs(os.path.join(out, "runs", family, sensor, name))
                if cell:
                    runs[(family, sensor, name)] = cell
                    summaries[(family, sensor, name)] = evaluate.summarise([result for _, result in cell])
    pooled = {}
    for (family, sensor, name), cell in runs.items():
        if pooled_family(family):
            pooled.setdefault((pooled_family(family), sensor, name), []).extend(result for _, result in cell)
    for key in sorted(pooled, key=lambda k: (k[0], k[1], variant_names.index(k[2]))):
        summaries[key] = evaluate.summarise(pooled[key])
    json.dump({"|".join(key): value for key, value in summaries.items()}, open(os.path.join(out, "results.json"), "w"), indent=1)
    open(os.path.join(out, "table.md"), "w").write(report.table(summaries, variant_names))
    if reference is not None:
        open(os.path.join(out, "targets.md"), "w").write(targets.markdown(summaries, variant_names, reference))
    plots = os.path.join(out, "plots")
    os.makedirs(plots, exist_ok=True)
    results_only = {key: [result for _, result in cell] for key, cell in runs.items()}
    pooled_families = list(dict.fromkeys(pooled_family(family) for family in families if pooled_family(family)))
    for sensor in sensors:
        if any(key[1] == sensor for key in runs):
            report.plot_ate(results_only, families, variant_names, sensor, os.path.join(plots, f"ate_{sensor}.png"))
        if any(key[1] == sensor for key in pooled):
            report.plot_ate(pooled, pooled_families, variant_names, sensor, os.path.join(plots, f"ate_{sensor}_pooled.png"))
        for family in families:
            file_name = family.replace("/", "_")
            aligned = {}
            for name in variant_names:
                workdir = evaluate.median_run(runs.get((family, sensor, name), []))
                if workdir:
                    aligned[name] = evaluate.save_aligned_trajectory(workdir, sequences[family].ground_truth, sensor,
                                                                      os.path.join(plots, f"aligned_{file_name}_{sensor}_{name}.npy"))
            if aligned:
                report.plot_trajectories(aligned, family, sensor, os.path.join(plots, f"trajectory_{file_name}_{sensor}.png"))
    print(open(os.path.join(out, "table.md")).read())


if __name__ == "__main__":
    main()
