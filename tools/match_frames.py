#!/usr/bin/env python3
"""Detect and match SIFT features between video frames, writing raw matches as JSON.

Purpose
-------
Produces point correspondences between pairs of frames of a real rolling-shutter
video, for use as test data by the Rust solver (``solver/tests/data/cc9pro/``).
The matches are deliberately *not* filtered with a geometric model (no fundamental
or essential matrix RANSAC): the downstream estimator does its own robust
estimation, so outliers are expected and wanted.

Pipeline per pair ``(N1, N2)``:

1. Load ``RE_frame-N1.jpg`` and ``RE_frame-N2.jpg`` from ``--frames-dir`` as
   grayscale.
2. Detect SIFT keypoints (``--nfeatures``) with a mask that excludes image rows
   ``>= --mask-from-row`` (in the cc9pro recording these rows show the car's
   dashboard, which moves with the camera). Keypoints whose sub-pixel row is
   ``>= --mask-from-row`` are dropped as well.
3. Match descriptors with a brute-force L2 matcher (2 nearest neighbours in both
   directions), keep matches passing Lowe's ratio test (``--ratio``, applied to
   the frame-1 -> frame-2 direction) that are also mutual best matches.
4. Remove identical matches (same rounded coordinates); if more than
   ``--max-matches`` remain, keep the ones with the lowest ratio.
5. Sort by (v1, u1, v2, u2) and write ``OUT/matches-N1-N2.json`` atomically.

Output shape (pixel coordinates as OpenCV gives them: u = column, v = row,
origin at the centre of the top-left pixel, rounded to 3 decimals)::

    {"source": "...", "frames": [N1, N2], "image_size": [width, height],
     "detector": "SIFT nfeatures=4000, ratio 0.8, mutual, mask rows >= 390",
     "matches": [
    [[u1, v1], [u2, v2]],
    ...
    ]}

The output is deterministic: the same input frames and options give
byte-identical files (with the same OpenCV build).

Usage
-----
::

    python tools/match_frames.py --frames-dir /path/to/cc9pro/frames \\
        --pair 100 101 --pair 104 107 --out-dir solver/tests/data/cc9pro
    python tools/match_frames.py --frames-dir DIR --pairs-file pairs.txt --out-dir OUT \\
        [--mask-from-row 390] [--max-matches 1200] [--ratio 0.8] [--nfeatures 4000]

``--pairs-file`` holds one ``N1 N2`` pair per line; ``#`` starts a comment.
``--pair`` and ``--pairs-file`` may be combined. Exit code 2 on bad arguments or
a missing/unreadable frame file.

Dependencies: Python 3.11, ``opencv-python-headless`` (with SIFT, OpenCV >= 4.4)
and ``numpy`` (see ``tools/requirements.txt``).

Data licence and attribution
----------------------------
The cc9pro frames come from the public repository
``lhaippp/gyro-video-stabilization`` (recording ``20200109_145447``, Xiaomi Mi
CC9 Pro), MIT licence, copyright (c) 2023 Li Haipeng. The match files derived
from them carry that attribution in their ``source`` field and remain under the
same MIT licence; keep the attribution wherever the data or derived data are used.
"""

from __future__ import annotations

import argparse
import json
import os
import sys
import tempfile

import cv2
import numpy as np

SOURCE = "cc9pro 20200109_145447 (lhaippp/gyro-video-stabilization, MIT)"


class ToolError(Exception):
    """A user-facing error that ends the run with exit code 2."""


def parse_pairs_file(path: str) -> list[tuple[int, int]]:
    try:
        with open(path, encoding="utf-8") as f:
            lines = f.read().splitlines()
    except OSError as e:
        raise ToolError(f"cannot read pairs file {path!r}: {e.strerror}") from e
    pairs = []
    for lineno, line in enumerate(lines, 1):
        text = line.split("#", 1)[0].strip()
        if not text:
            continue
        parts = text.split()
        try:
            if len(parts) != 2:
                raise ValueError
            pairs.append((int(parts[0]), int(parts[1])))
        except ValueError:
            raise ToolError(
                f"{path}:{lineno}: expected two frame numbers 'N1 N2', got {line.strip()!r}"
            ) from None
    return pairs


def load_gray(frames_dir: str, n: int) -> np.ndarray:
    path = os.path.join(frames_dir, f"RE_frame-{n}.jpg")
    if not os.path.isfile(path):
        raise ToolError(f"frame file not found: {path}")
    img = cv2.imread(path, cv2.IMREAD_GRAYSCALE)
    if img is None or img.size == 0:
        raise ToolError(f"cannot read frame file (not a decodable image?): {path}")
    return img


def make_sift(nfeatures: int):
    if hasattr(cv2, "SIFT_create"):
        return cv2.SIFT_create(nfeatures=nfeatures)
    try:
        return cv2.xfeatures2d.SIFT_create(nfeatures=nfeatures)  # old contrib builds
    except AttributeError:
        raise ToolError("this OpenCV build has no SIFT (need OpenCV >= 4.4)") from None


def detect(sift, img: np.ndarray, mask_from_row: int):
    """SIFT keypoint coordinates (K x 2, float64 u, v) and descriptors (K x 128)."""
    mask = np.zeros(img.shape, dtype=np.uint8)
    mask[: max(0, min(mask_from_row, img.shape[0])), :] = 255
    kps, desc = sift.detectAndCompute(img, mask)
    if desc is None or not kps:
        return np.zeros((0, 2)), np.zeros((0, 128), dtype=np.float32)
    pts = np.array([kp.pt for kp in kps], dtype=np.float64)
    keep = pts[:, 1] < mask_from_row  # guard sub-pixel positions at the mask edge
    return pts[keep], np.ascontiguousarray(desc[keep], dtype=np.float32)


def knn2(matcher, query: np.ndarray, train: np.ndarray):
    """For each query row: (best index, best distance, second distance or inf)."""
    n = len(query)
    best = np.full(n, -1, dtype=np.int64)
    d1 = np.full(n, np.inf)
    d2 = np.full(n, np.inf)
    if n == 0 or len(train) == 0:
        return best, d1, d2
    for i, ms in enumerate(matcher.knnMatch(query, train, k=2)):
        if len(ms) >= 1:
            best[i] = ms[0].trainIdx
            d1[i] = ms[0].distance
        if len(ms) >= 2:
            d2[i] = ms[1].distance
    return best, d1, d2


def match_pair(sift, img1, img2, mask_from_row: int, ratio: float, max_matches: int):
    pts1, desc1 = detect(sift, img1, mask_from_row)
    pts2, desc2 = detect(sift, img2, mask_from_row)
    matcher = cv2.BFMatcher(cv2.NORM_L2, crossCheck=False)
    fwd, fd1, fd2 = knn2(matcher, desc1, desc2)
    bwd, _, _ = knn2(matcher, desc2, desc1)

    candidates: dict[tuple[float, float, float, float], float] = {}
    for i in range(len(pts1)):
        j = int(fwd[i])
        if j < 0 or int(bwd[j]) != i:  # not a mutual best match
            continue
        # Lowe ratio test; a missing second neighbour counts as passing (r = 0).
        r = float(fd1[i] / fd2[i]) if np.isfinite(fd2[i]) and fd2[i] > 0 else 0.0
        if not r < ratio:
            continue
        key = (
            round(float(pts1[i, 0]), 3),
            round(float(pts1[i, 1]), 3),
            round(float(pts2[j, 0]), 3),
            round(float(pts2[j, 1]), 3),
        )
        if key not in candidates or r < candidates[key]:
            candidates[key] = r  # deduplicate identical matches, keep the best ratio

    ranked = sorted(candidates.items(), key=lambda kv: (kv[1], kv[0]))
    if max_matches >= 0:
        ranked = ranked[:max_matches]
    keys = sorted((k for k, _ in ranked), key=lambda k: (k[1], k[0], k[3], k[2]))
    return keys, len(pts1), len(pts2), len(candidates)


def fmt_num(x: float) -> str:
    return json.dumps(x if x != 0 else 0.0)  # no "-0.0"


def render(frames, image_size, detector: str, keys) -> str:
    head = (
        "{"
        f'"source": {json.dumps(SOURCE)}, '
        f'"frames": {json.dumps(list(frames))}, '
        f'"image_size": {json.dumps(list(image_size))}, '
        f'"detector": {json.dumps(detector)}, '
        '"matches": ['
    )
    rows = [
        f"[[{fmt_num(u1)}, {fmt_num(v1)}], [{fmt_num(u2)}, {fmt_num(v2)}]]"
        for (u1, v1, u2, v2) in keys
    ]
    body = ("\n" + ",\n".join(rows) + "\n") if rows else ""
    return head + body + "]}\n"


def write_atomic(path: str, text: str) -> None:
    directory = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix=".tmp-", suffix=".json", dir=directory)
    try:
        with os.fdopen(fd, "w", encoding="utf-8", newline="\n") as f:
            f.write(text)
            f.flush()
            os.fsync(f.fileno())
        os.chmod(tmp, 0o644)
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        description="SIFT + ratio test + mutual matching between video frames "
        "(no geometric filtering); one JSON file per pair.",
    )
    p.add_argument("--frames-dir", required=True, help="directory holding RE_frame-N.jpg")
    p.add_argument(
        "--pair", nargs=2, type=int, action="append", default=[], metavar=("N1", "N2"),
        help="frame numbers of a pair (repeatable)",
    )
    p.add_argument("--pairs-file", help="file with one 'N1 N2' pair per line, '#' comments")
    p.add_argument("--out-dir", required=True, help="output directory (created if missing)")
    p.add_argument("--mask-from-row", type=int, default=390,
                   help="ignore image rows >= this (default 390: the dashboard)")
    p.add_argument("--max-matches", type=int, default=1200,
                   help="keep at most this many matches, lowest ratio first (default 1200)")
    p.add_argument("--ratio", type=float, default=0.8, help="Lowe ratio threshold (default 0.8)")
    p.add_argument("--nfeatures", type=int, default=4000,
                   help="SIFT features per frame (default 4000)")
    p.add_argument("-q", "--quiet", action="store_true", help="no per-pair summary on stderr")
    return p


def main(argv: list[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.mask_from_row <= 0:
        parser.error("--mask-from-row must be positive")
    if args.max_matches < 1:
        parser.error("--max-matches must be at least 1")
    if not 0.0 < args.ratio <= 1.0:
        parser.error("--ratio must be in (0, 1]")
    if args.nfeatures < 0:
        parser.error("--nfeatures must be >= 0 (0 = unlimited)")

    try:
        pairs = [tuple(p) for p in args.pair]
        if args.pairs_file:
            pairs += parse_pairs_file(args.pairs_file)
        pairs = list(dict.fromkeys(pairs))  # drop repeated pairs, keep order
        if not pairs:
            parser.error("no pairs given (use --pair N1 N2 and/or --pairs-file FILE)")
        if not os.path.isdir(args.frames_dir):
            raise ToolError(f"frames directory not found: {args.frames_dir}")
        # Check every input before writing anything.
        for n1, n2 in pairs:
            for n in (n1, n2):
                load_gray(args.frames_dir, n)
        os.makedirs(args.out_dir, exist_ok=True)

        detector = (
            f"SIFT nfeatures={args.nfeatures}, ratio {args.ratio:g}, mutual, "
            f"mask rows >= {args.mask_from_row}"
        )
        sift = make_sift(args.nfeatures)
        for n1, n2 in pairs:
            img1 = load_gray(args.frames_dir, n1)
            img2 = load_gray(args.frames_dir, n2)
            if img1.shape != img2.shape:
                raise ToolError(
                    f"frames {n1} and {n2} differ in size: {img1.shape[::-1]} vs {img2.shape[::-1]}"
                )
            keys, k1, k2, n_cand = match_pair(
                sift, img1, img2, args.mask_from_row, args.ratio, args.max_matches
            )
            h, w = img1.shape
            out = os.path.join(args.out_dir, f"matches-{n1}-{n2}.json")
            write_atomic(out, render((n1, n2), (w, h), detector, keys))
            if not args.quiet:
                print(
                    f"{n1}-{n2}: keypoints {k1}/{k2}, candidates {n_cand}, "
                    f"written {len(keys)} -> {out}",
                    file=sys.stderr,
                )
    except ToolError as e:
        print(f"match_frames.py: error: {e}", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
