"""Where a sequence's files are.

A family folder holds the EuRoC layout (mav0/ and times.txt, which ORB-SLAM3's mono_euroc and
stereo_euroc read) and the TUM ground truth (groundtruth.txt), either together at its top (as
scripts/slamseq/layouts.py writes them) or split into euroc/ and tum/ sub-folders; the settings files
(mono.yaml, stereo.yaml) in any of the three. find() says which file is missing where, instead of
a FileNotFoundError later.
"""
import os
from dataclasses import dataclass

SUBFOLDERS = ("", "euroc", "tum")


class SequenceError(Exception):
    pass


@dataclass
class Sequence:
    name: str
    euroc: str        # the folder given to the programs: mav0/ and times.txt
    times: str
    ground_truth: str
    settings: dict    # sensor -> settings file


def _first(folder, relative):
    for sub in SUBFOLDERS:
        path = os.path.join(folder, sub, relative)
        if os.path.exists(path):
            return path
    return None


def find(folder, sensors=("mono", "stereo")):
    """The sequence in `folder`, or SequenceError listing every file missing and where it was looked for."""
    folder = os.path.abspath(folder)
    missing = []
    times = _first(folder, "times.txt")
    euroc = os.path.dirname(times) if times else None
    if times is None:
        missing.append("times.txt")
    elif not os.path.isdir(os.path.join(euroc, "mav0", "cam0", "data")):
        missing.append(f"mav0/cam0/data beside {times}")
    ground_truth = _first(folder, "groundtruth.txt")
    if ground_truth is None:
        missing.append("groundtruth.txt")
    settings = {}
    for sensor in sensors:
        settings[sensor] = _first(folder, f"{sensor}.yaml")
        if settings[sensor] is None:
            missing.append(f"{sensor}.yaml")
    if missing:
        places = ", ".join(os.path.join(folder, sub) or folder for sub in SUBFOLDERS)
        raise SequenceError(f"{folder}: no {', '.join(missing)} (looked in {places})")
    return Sequence(os.path.basename(folder), euroc, times, ground_truth, settings)


def find_all(root, names=None, sensors=("mono", "stereo")):
    """The sequences under root: the named ones (each must be complete), else every complete folder.
    SequenceError when a named one is incomplete, or when no folder is a sequence (saying why)."""
    if not os.path.isdir(root):
        raise SequenceError(f"{root} is not a folder")
    if names:
        return [find(os.path.join(root, name), sensors) for name in names]
    found, reasons = [], []
    for name in sorted(os.listdir(root)):
        if not os.path.isdir(os.path.join(root, name)):
            continue
        try:
            found.append(find(os.path.join(root, name), sensors))
        except SequenceError as error:
            reasons.append(str(error))
    if not found:
        raise SequenceError(f"no sequence under {root}" + (": " + "; ".join(reasons) if reasons else " (no folders)"))
    return found
