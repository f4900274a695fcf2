"""Writing a sequence: EuRoC and TUM layouts and ORB-SLAM3 settings files.

<family>/
  mav0/cam0/data/<ns>.png, mav0/cam1/data/<ns>.png, mav0/cam{0,1}/data.csv   EuRoC images
  mav0/state_groundtruth_estimate0/data.csv    T_world_cam0 (EuRoC columns: p, then q as w x y z)
  times.txt                                    one timestamp in ns a line (ORB-SLAM3's EuRoC_TimeStamps)
  rgb/ -> mav0/cam0/data, rgb.txt              TUM monocular (seconds)
  groundtruth.txt                              TUM: t tx ty tz qx qy qz qw, T_world_cam0
  depth/<ns>.png, depth.txt                    with --depth: cam0 depth, uint16, 5000 per metre (TUM's scale)
  mono.yaml, stereo.yaml                       ORB-SLAM3 settings (File.version 1.0; stereo as two pinholes)
  sequence.json                                family, seed, frames, camera, baseline
"""
import json
import os

import cv2
import numpy as np


def quaternion_wxyz(rotation):
    """Unit quaternion (w, x, y, z) of a rotation matrix, w >= 0."""
    m = rotation
    trace = np.trace(m)
    if trace > 0:
        s = 2.0 * np.sqrt(1.0 + trace)
        q = [0.25 * s, (m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s]
    else:
        i = int(np.argmax(np.diag(m)))
        j, k = (i + 1) % 3, (i + 2) % 3
        s = 2.0 * np.sqrt(1.0 + m[i, i] - m[j, j] - m[k, k])
        q = [0.0] * 4
        q[0] = (m[k, j] - m[j, k]) / s
        q[1 + i] = 0.25 * s
        q[1 + j] = (m[j, i] + m[i, j]) / s
        q[1 + k] = (m[k, i] + m[i, k]) / s
    q = np.array(q)
    return q if q[0] >= 0 else -q


def timestamp_ns(frame, fps, start=1.0):
    return int(round((start + frame / fps) * 1e9))


class SequenceWriter:
    def __init__(self, folder, with_depth):
        self.folder = folder
        self.with_depth = with_depth
        for sub in ("mav0/cam0/data", "mav0/cam1/data", "mav0/state_groundtruth_estimate0"):
            os.makedirs(os.path.join(folder, sub), exist_ok=True)
        if with_depth:
            os.makedirs(os.path.join(folder, "depth"), exist_ok=True)
        self.rows = []  # (ns, pose)

    def add(self, ns, pose, left, right, depth=None):
        cv2.imwrite(os.path.join(self.folder, "mav0/cam0/data", f"{ns}.png"), left)
        cv2.imwrite(os.path.join(self.folder, "mav0/cam1/data", f"{ns}.png"), right)
        if self.with_depth and depth is not None:
            scaled = np.clip(np.rint(np.nan_to_num(depth, posinf=0.0) * 5000.0), 0, 65535).astype(np.uint16)
            cv2.imwrite(os.path.join(self.folder, "depth", f"{ns}.png"), scaled)
        self.rows.append((ns, pose))

    def finish(self, camera, baseline, fps, info):
        join = lambda *parts: os.path.join(self.folder, *parts)

        def write(name, header, lines):
            with open(join(name), "w") as f:
                f.write(header)
                f.writelines(lines)

        for cam in ("cam0", "cam1"):
            write(os.path.join("mav0", cam, "data.csv"), "#timestamp [ns],filename\n",
                  (f"{ns},{ns}.png\n" for ns, _ in self.rows))
        write("times.txt", "", (f"{ns}\n" for ns, _ in self.rows))
        # (ns, t, q): the position and the quaternion (w, x, y, z) of each frame's T_world_cam0.
        poses = [(ns, pose[:3, 3], quaternion_wxyz(pose[:3, :3])) for ns, pose in self.rows]
        write("mav0/state_groundtruth_estimate0/data.csv",
              "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], q_RS_z []\n",
              (f"{ns},{t[0]:.9f},{t[1]:.9f},{t[2]:.9f},{q[0]:.9f},{q[1]:.9f},{q[2]:.9f},{q[3]:.9f}\n" for ns, t, q in poses))
        if not os.path.lexists(join("rgb")):
            os.symlink(os.path.join("mav0", "cam0", "data"), join("rgb"))
        write("rgb.txt", "# color images\n# timestamp filename\n",
              (f"{ns / 1e9:.6f} rgb/{ns}.png\n" for ns, _ in self.rows))
        write("groundtruth.txt", "# ground truth trajectory: T_world_cam0\n# timestamp tx ty tz qx qy qz qw\n",
              (f"{ns / 1e9:.6f} {t[0]:.9f} {t[1]:.9f} {t[2]:.9f} {q[1]:.9f} {q[2]:.9f} {q[3]:.9f} {q[0]:.9f}\n" for ns, t, q in poses))
        if self.with_depth:
            write("depth.txt", "# depth maps\n# timestamp filename\n",
                  (f"{ns / 1e9:.6f} depth/{ns}.png\n" for ns, _ in self.rows))
        write_settings(self.folder, camera, baseline, fps)
        with open(join("sequence.json"), "w") as f:
            json.dump(dict(info, frames=len(self.rows), fps=fps, baseline_m=baseline,
                           camera=dict(width=camera.width, height=camera.height, fx=camera.fx, fy=camera.fy, cx=camera.cx, cy=camera.cy)), f, indent=1)


def _camera_keys(prefix, camera):
    return "".join(f"{prefix}.{key}: {value:.6f}\n" for key, value in
                   (("fx", camera.fx), ("fy", camera.fy), ("cx", camera.cx), ("cy", camera.cy),
                    ("k1", 0.0), ("k2", 0.0), ("p1", 0.0), ("p2", 0.0)))


def _common_keys(camera, fps):
    return (f"Camera.width: {camera.width}\nCamera.height: {camera.height}\nCamera.fps: {fps}\nCamera.RGB: 1\n"
            "ORBextractor.nFeatures: 1000\nORBextractor.scaleFactor: 1.2\nORBextractor.nLevels: 8\n"
            "ORBextractor.iniThFAST: 20\nORBextractor.minThFAST: 7\n"
            "Viewer.KeyFrameSize: 0.05\nViewer.KeyFrameLineWidth: 1.0\nViewer.GraphLineWidth: 0.9\nViewer.PointSize: 2.0\n"
            "Viewer.CameraSize: 0.08\nViewer.CameraLineWidth: 3.0\nViewer.ViewpointX: 0.0\nViewer.ViewpointY: -0.7\n"
            "Viewer.ViewpointZ: -1.8\nViewer.ViewpointF: 500.0\n")


def write_settings(folder, camera, baseline, fps):
    """ORB-SLAM3 settings. The stereo rig is two pinholes with Stereo.T_c1_c2, not "Rectified"
    (that type crashes ORB-SLAM3 while printing the settings:
    https://github.com/UZ-SLAMLab/ORB_SLAM3/issues/585)."""
    header = '%YAML:1.0\nFile.version: "1.0"\nCamera.type: "PinHole"\n'
    with open(os.path.join(folder, "mono.yaml"), "w") as f:
        f.write(header + _camera_keys("Camera1", camera) + _common_keys(camera, fps))
    with open(os.path.join(folder, "stereo.yaml"), "w") as f:
        f.write(header + _camera_keys("Camera1", camera) + _camera_keys("Camera2", camera)
                + "Stereo.ThDepth: 60.0\nStereo.T_c1_c2: !!opencv-matrix\n  rows: 4\n  cols: 4\n  dt: f\n"
                f"  data: [1.0, 0.0, 0.0, {baseline:.6f}, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0]\n"
                + _common_keys(camera, fps))
