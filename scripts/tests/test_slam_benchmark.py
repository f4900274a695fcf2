"""scripts/slam_benchmark.py end to end, with stand-ins for ORB-SLAM3's example programs.

The stand-in writes what mono_euroc / stereo_euroc leave in their working directory: the
trajectories of the tracked frames and keyframes (EuRoC format, ns), TrackingTimeStats.txt (as
-DREGISTER_TIMES builds write it) and the log lines the benchmark counts. It reports the ground
truth moved by a known similarity, with every fifth frame dropped, so the expected figures are
known exactly.
"""
import json
import os
import stat
import subprocess
import sys

import numpy as np
import pytest

SCRIPTS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")

STAND_IN = r'''#!{python}
import os, sys
import numpy as np
vocabulary, settings, sequence, times, name = sys.argv[1:6]
gt = np.loadtxt(os.path.join(sequence, "groundtruth.txt"))
keep = [i for i in range(len(gt)) if i % 5 != 4]
scale = {scale}
with open(f"f_{{name}}.txt", "w") as f:
    for i in keep:
        t, p = gt[i, 0], gt[i, 1:4]
        f.write(f"{{t * 1e9:.6f}} {{scale * p[0] + 1:.9f}} {{scale * p[2]:.9f}} {{-scale * p[1]:.9f}} 0 0 0 1\n")
with open(f"kf_{{name}}.txt", "w") as f:
    for i in keep[::4]:
        t, p = gt[i, 0], gt[i, 1:4]
        f.write(f"{{t * 1e9:.6f}} {{scale * p[0] + 1:.9f}} {{scale * p[2]:.9f}} {{-scale * p[1]:.9f}} 0 0 0 1\n")
with open("TrackingTimeStats.txt", "w") as f:
    f.write("#Image Rect[ms], Image Resize[ms], ORB ext[ms], Stereo match[ms], IMU preint[ms], Pose pred[ms], LM track[ms], KF dec[ms], Total[ms]\n")
    for i in range(len(gt)):
        f.write(f"0,0,{{ {extract} + i % 2 }},0,0,0,0,0,{{ {track} + i % 2 }}\n")
print("Creation of new map with id: 0")
print("Fail to track local map!")
print("Creation of new map with id: 1")
'''


def stand_in(root, scale, extract, track):
    for sensor, path in (("mono", "Examples/Monocular/mono_euroc"), ("stereo", "Examples/Stereo/stereo_euroc")):
        program = os.path.join(root, path)
        os.makedirs(os.path.dirname(program), exist_ok=True)
        with open(program, "w") as f:
            f.write(STAND_IN.format(python=sys.executable, scale=scale if sensor == "mono" else 1.0, extract=extract, track=track))
        os.chmod(program, os.stat(program).st_mode | stat.S_IEXEC)
    return str(root)


def test_benchmark_runs_every_cell_and_reports_the_known_figures(tmp_path):
    sequences = tmp_path / "sequences"
    subprocess.run([sys.executable, os.path.join(SCRIPTS, "make_sequences.py"), str(sequences), "--seed", "5", "--seconds", "1",
                    "--width", "96", "--height", "72", "--families", "baseline"], check=True, capture_output=True)
    stock = stand_in(tmp_path / "stock", scale=0.5, extract=10, track=20)
    aief = stand_in(tmp_path / "aief", scale=2.0, extract=2, track=10)
    vocabulary = tmp_path / "voc.txt"
    vocabulary.write_text("stand-in\n")
    out = tmp_path / "out"
    result = subprocess.run([sys.executable, os.path.join(SCRIPTS, "slam_benchmark.py"), "--stock", stock, "--aief", aief,
                             "--vocabulary", str(vocabulary), "--sequences", str(sequences), "--out", str(out), "--runs", "2"],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    summary = json.load(open(out / "results.json"))
    assert set(summary) == {f"baseline|{sensor}|{variant}" for sensor in ("mono", "stereo") for variant in ("stock", "aief")}
    for key, cell in summary.items():
        assert cell["runs"] == 2 and cell["failed"] == 0
        assert cell["ate"]["max"] < 1e-6  # a similarity (mono) or a rigid motion (stereo) of the truth
        assert cell["tracked_share"]["median"] == pytest.approx(0.8)
        assert cell["lost"]["median"] == 1 and cell["map_resets"]["median"] == 1
        assert cell["keyframes"]["median"] == 2
    assert summary["baseline|mono|stock"]["extract_ms_median"]["median"] == pytest.approx(10.5)
    assert summary["baseline|mono|aief"]["track_ms_median"]["median"] == pytest.approx(10.5)
    # The aief variant gets ORBextractor.threads: 1 in its copy of the settings.
    settings = (out / "runs" / "baseline" / "stereo" / "aief" / "00" / "settings.yaml").read_text()
    assert "ORBextractor.threads: 1" in settings and "Camera2.fx" in settings
    table = (out / "table.md").read_text()
    assert "| baseline | mono | stock | 2 |" in table
    for name in ("ate_mono.png", "ate_stereo.png", "trajectory_baseline_mono.png", "trajectory_baseline_stereo.png"):
        assert (out / "plots" / name).stat().st_size > 1000
    # Finished runs are kept: a second call runs nothing and reports the same.
    again = subprocess.run([sys.executable, os.path.join(SCRIPTS, "slam_benchmark.py"), "--stock", stock, "--aief", aief,
                            "--vocabulary", str(vocabulary), "--sequences", str(sequences), "--out", str(out), "--runs", "2"],
                           capture_output=True, text=True)
    assert again.returncode == 0 and "run 0" not in again.stdout
    assert json.load(open(out / "results.json")) == summary


def test_a_missing_program_is_a_clear_error(tmp_path):
    (tmp_path / "seq").mkdir()
    (tmp_path / "voc.txt").write_text("x")
    result = subprocess.run([sys.executable, os.path.join(SCRIPTS, "slam_benchmark.py"), "--stock", str(tmp_path), "--aief", str(tmp_path),
                             "--vocabulary", str(tmp_path / "voc.txt"), "--sequences", str(tmp_path / "seq"), "--out", str(tmp_path / "o")],
                            capture_output=True, text=True)
    assert result.returncode != 0 and "mono_euroc" in result.stderr
