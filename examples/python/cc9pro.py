#!/usr/bin/env python3
"""The real phone recording end to end in Python: OpenCV SIFT matches -> rspose.

Matches the frame pairs of `solver/tests/data/cc9pro/pairs.txt` in the Xiaomi Mi CC9 Pro
recording (OpenCV SIFT, ratio test, mutual best matches, the dashboard rows masked: the
matcher of `tools/match_frames.py`, imported from there), cuts each pair's gyro samples from
the recording's log as `rspose make-pair` does (`rspose.GyroLog.excerpt`), estimates every
method on all pairs at once (`rspose.estimate_many`, all cores), and prints the table of
docs/REAL_DATA.md: each method's median / max rotation difference to the
gyro-integrated rotation between the frames, and its median inlier ratio.

Usage:
    python examples/python/cc9pro.py RECORDING_DIR [--pairs FILE] [--calibration FILE] [--preset P]

RECORDING_DIR holds frames/RE_frame-N.jpg, gyro.txt (gx,gy,gz,t) and framestamp.txt: in
this project's workplace `../shared/realdata/cc9pro`; elsewhere recording 20200109_145447 of
the public repository lhaippp/gyro-video-stabilization (MIT licence, copyright 2023 Li
Haipeng), which is not copied into this repository. Needs `python -m pip install ./python`
and `python -m pip install -r examples/python/requirements.txt`.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

REPO = Path(__file__).resolve().parents[2]
DATA = REPO / "solver" / "tests" / "data" / "cc9pro"
sys.path.insert(0, str(REPO / "tools"))

try:
    import rspose
except ImportError:
    sys.exit("cc9pro.py: the rspose package is not installed: python -m pip install ./python")
try:
    import match_frames  # tools/match_frames.py: the matcher the committed pairs were made with
except ImportError as e:
    sys.exit(f"cc9pro.py: {e}: python -m pip install -r examples/python/requirements.txt")

# The settings the committed pairs were matched with (tools/match_frames.py's defaults).
NFEATURES, RATIO, MASK_FROM_ROW, MAX_MATCHES = 4000, 0.8, 390, 1200


def read_recording(directory: Path, time_column: int):
    """The gyro samples as [t, wx, wy, wz] (gyro axes) and the frame times (frame N is line N)."""
    for name in ("frames", "gyro.txt", "framestamp.txt"):
        if not (directory / name).exists():
            sys.exit(
                f"cc9pro.py: {directory / name} not found: give the recording's directory "
                "(frames/, gyro.txt, framestamp.txt), e.g. ../shared/realdata/cc9pro"
            )
    log = np.loadtxt(directory / "gyro.txt", delimiter=",", ndmin=2)
    rates = [c for c in range(4) if c != time_column]
    samples = np.column_stack([log[:, time_column], log[:, rates]])
    frame_times = np.loadtxt(directory / "framestamp.txt", ndmin=1)
    return samples, frame_times


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    p.add_argument("recording", type=Path, help="directory with frames/, gyro.txt, framestamp.txt")
    p.add_argument("--pairs", type=Path, default=DATA / "pairs.txt", help="frame pairs 'N1 N2'")
    p.add_argument("--calibration", type=Path, default=DATA / "calibration.json",
                   help="rig calibration (camera, camera_from_gyro, time_offset)")
    p.add_argument("--preset", choices=["default", "paper"], default="default")
    args = p.parse_args(argv)

    calibration = json.loads(args.calibration.read_text())
    camera = rspose.Camera(**calibration["camera"])
    samples, frame_times = read_recording(args.recording, calibration.get("gyro_time_column", 3))
    frame_pairs = match_frames.parse_pairs_file(str(args.pairs))

    start = time.perf_counter()
    sift = match_frames.make_sift(NFEATURES)
    pairs = []
    for n1, n2 in frame_pairs:
        img1 = match_frames.load_gray(str(args.recording / "frames"), n1)
        img2 = match_frames.load_gray(str(args.recording / "frames"), n2)
        keys, *_ = match_frames.match_pair(sift, img1, img2, MASK_FROM_ROW, RATIO, MAX_MATCHES)
        m = np.array(keys, dtype=float).reshape(-1, 4)
        log = rspose.GyroLog.excerpt(
            samples,
            [frame_times[n1 - 1], frame_times[n2 - 1]],
            duration=camera.height * camera.readout,
            camera_from_gyro=calibration.get("camera_from_gyro"),
            time_offset=calibration.get("time_offset", 0.0),
        )
        pairs.append(rspose.Pair(m[:, 0:2], m[:, 2:4], camera, gyro_log=log))
        print(f"frames {n1}-{n2}: {len(m)} SIFT matches", file=sys.stderr)
    print(f"matched {len(pairs)} pairs in {time.perf_counter() - start:.1f} s", file=sys.stderr)

    references = [pair.gyro_relative_rotation() for pair in pairs]
    print("| method | median / max rotation difference (deg) | median inliers |")
    print("|---|---|---|")
    for method in rspose.methods():
        if method == "grsrp-gravity":
            continue  # the recording has no accelerometer log
        estimates = rspose.estimate_many(pairs, method, preset=args.preset)
        errors = [rspose.rotation_error_deg(r, e.rotation) for r, e in zip(references, estimates)]
        ratios = [e.inlier_ratio for e in estimates]
        print(f"| `{method}` | {np.median(errors):.3f} / {np.max(errors):.3f} "
              f"| {100 * np.median(ratios):.1f} % |")
    print("grsrp-gravity left out: the recording has no accelerometer log", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
