"""Running one ORB-SLAM3 example program on one sequence and reading what it leaves behind.

The programs are ORB-SLAM3's own mono_euroc and stereo_euroc (Examples/Monocular,
Examples/Stereo of a build the user made; docs/slam.md says how). They write into their working
directory: f_<name>.txt / kf_<name>.txt (every tracked frame / keyframe of the largest map:
"t[ns] tx ty tz qx qy qz qw"), and, when ORB-SLAM3 is compiled with -DREGISTER_TIMES,
TrackingTimeStats.txt with one row per frame whose columns include the time of the ORB
extraction inside Frame's constructor ("ORB ext") and the whole TrackMonocular / TrackStereo
call ("Total"), both measured by ORB-SLAM3 itself, the same way for every extractor.
"""
import os
import re
import subprocess
import time

import numpy as np

PROGRAMS = {"mono": "Examples/Monocular/mono_euroc", "stereo": "Examples/Stereo/stereo_euroc"}
RUN_NAME = "run"


def program_path(orbslam3_root, sensor):
    path = os.path.join(orbslam3_root, PROGRAMS[sensor])
    if not os.access(path, os.X_OK):
        raise FileNotFoundError(f"{path} is not an executable: give the ORB-SLAM3 folder whose examples were built")
    return path


def missing_libraries(program):
    """The shared libraries the program needs and the loader cannot find (ldd's "not found"), e.g.
    Pangolin's when ORB-SLAM3 was built against an installed Pangolin and LD_LIBRARY_PATH does not
    name its folder. Empty for a program ldd cannot read (a script) or when there is no ldd."""
    try:
        listing = subprocess.run(["ldd", program], capture_output=True, text=True, timeout=60)
    except (OSError, subprocess.TimeoutExpired):
        return []
    return [line.split("=>")[0].strip() for line in listing.stdout.splitlines() if "not found" in line]


def write_settings(base_settings, extra_keys, out_path):
    """A copy of the sequence's settings with extra (or replaced) top-level keys."""
    lines = open(base_settings).read().splitlines()
    keys = dict(extra_keys)
    kept = [line for line in lines if line.split(":")[0].strip() not in keys]
    kept += [f"{key}: {value}" for key, value in keys.items()]
    with open(out_path, "w") as f:
        f.write("\n".join(kept) + "\n")


def run(program, vocabulary, settings, sequence, workdir, timeout):
    """Runs the program on a slambench.sequences.Sequence in workdir; returns (return code, wall
    seconds). Output goes to workdir/log.txt."""
    os.makedirs(workdir, exist_ok=True)
    command = [program, vocabulary, settings, sequence.euroc, sequence.times, RUN_NAME]
    start = time.monotonic()
    with open(os.path.join(workdir, "log.txt"), "w") as log:
        try:
            code = subprocess.run(command, cwd=workdir, stdout=log, stderr=subprocess.STDOUT, timeout=timeout).returncode
        except subprocess.TimeoutExpired:
            code = "timeout"
    return code, time.monotonic() - start


def read_trajectory(path):
    """(times in seconds, N x 3 positions) of a EuRoC-style trajectory ORB-SLAM3 saved; empty if none."""
    if not os.path.exists(path) or os.path.getsize(path) == 0:
        return np.zeros(0), np.zeros((0, 3))
    data = np.atleast_2d(np.loadtxt(path))
    return data[:, 0] / 1e9, data[:, 1:4]


def read_ground_truth(path):
    """(times in seconds, N x 3 positions) of a TUM ground truth file."""
    data = np.loadtxt(path)
    return data[:, 0], data[:, 1:4]


def read_times(workdir):
    """Per-frame (ORB extraction ms, tracking ms) from TrackingTimeStats.txt, or None."""
    path = os.path.join(workdir, "TrackingTimeStats.txt")
    if not os.path.exists(path):
        return None
    rows = [line.split(",") for line in open(path) if line.strip() and not line.startswith("#")]
    table = np.array([[float(v) for v in row] for row in rows if len(row) >= 9])
    if table.size == 0:
        return None
    return table[:, 2], table[:, 8]


def read_log(workdir):
    text = open(os.path.join(workdir, "log.txt"), errors="replace").read()
    maps = len(re.findall(r"Creation of new map with id", text))
    return dict(
        lost=len(re.findall(r"Fail to track local map!", text)),
        map_resets=max(0, maps - 1),  # the Atlas creates the first map at start-up
        initialisations=len(re.findall(r"New Map created with", text)),
        crashed=bool(re.search(r"Segmentation fault|core dumped|terminate called", text)),
    )
