"""Gyro-aided relative pose of rolling-shutter cameras (the Rust library ``rspose``).

Conventions (the Rust API's): pixels ``[u, v]`` with v the image row, row 0 read first;
bearing ``m = K^-1 [u, v, 1]``; a gyro reading is what a gyroscope reports, rotated into
camera axes (x right, y down, z forward; rad/s, bias removed); the relative pose refers to
row 0 of each image, ``R = R2 R1^T``, ``t = R2 (C1 - C2) / |.|``, so ``x2 = R x1 + t``.

Bad input raises ``ValueError`` (with the command line's message) or ``TypeError``; valid
input without an answer raises ``NoSolutionError``.
"""

from __future__ import annotations

import os
import pathlib
from collections.abc import Iterable, Mapping, Sequence
from typing import Any, Literal, Optional, Tuple, TypedDict, Union

import numpy as np
import numpy.typing as npt

__version__: str

ArrayLike = npt.ArrayLike
Method = Literal["gsrp", "nrsrp", "grsrp", "grsrp+", "rectified", "rectified+v", "grsrp-gravity"]
Preset = Literal["default", "paper"]
Rows = Literal["integrated", "constant"]
Threshold = Tuple[Literal["sampson_pixels", "algebraic"], float]
CameraLike = Union["Camera", Mapping[str, Any]]
CameraModel = Literal[
    "SIMPLE_PINHOLE", "PINHOLE", "SIMPLE_RADIAL", "RADIAL", "OPENCV", "OPENCV_FISHEYE", "FULL_OPENCV"
]
ReadoutDirection = Literal["top_to_bottom", "bottom_to_top", "left_to_right", "right_to_left"]
PathLike = Union[str, "os.PathLike[str]"]

class NoSolutionError(RuntimeError):
    """Valid input without an answer (every RANSAC hypothesis failed, degenerate geometry):
    the command line's exit code 1, ``no solution found``."""

class Camera:
    """A rolling-shutter camera: a COLMAP camera model (``model``, ``params`` in COLMAP's
    order), image size, ``readout`` the readout time per line (s/line; 0 for a global
    shutter) and ``readout_direction``. ``Camera(fx, fy, cx, cy, width, height, readout)``
    is a ``PINHOLE``; ``Camera.from_params`` any model (SIMPLE_PINHOLE, PINHOLE,
    SIMPLE_RADIAL, RADIAL, OPENCV, OPENCV_FISHEYE, FULL_OPENCV). A pixel's bearing is its
    undistorted normalised coordinates, its time ``readout_line(u, v) * readout``. Checked
    when a pair is made from it (``invalid field `camera.fx`: ...``)."""

    def __init__(
        self,
        fx: float,
        fy: float,
        cx: float,
        cy: float,
        width: float,
        height: float,
        readout: float,
        *,
        readout_direction: ReadoutDirection = "top_to_bottom",
    ) -> None: ...
    @staticmethod
    def from_params(
        model: CameraModel,
        width: float,
        height: float,
        params: Sequence[float],
        readout: float,
        readout_direction: ReadoutDirection = "top_to_bottom",
    ) -> Camera:
        """COLMAP's model and params, e.g. ``("OPENCV", 1920, 1080, [fx, fy, cx, cy, k1, k2,
        p1, p2], 3e-5)``; ``ValueError`` for an unknown model or a wrong number of params."""
    @staticmethod
    def paper() -> Camera:
        """1920 x 1080, f = 640 px, principal point at the centre, 60 µs per row."""
    @property
    def model(self) -> str: ...
    @property
    def params(self) -> list[float]: ...
    @property
    def fx(self) -> float: ...
    @property
    def fy(self) -> float: ...
    @property
    def cx(self) -> float: ...
    @property
    def cy(self) -> float: ...
    @property
    def width(self) -> float: ...
    @property
    def height(self) -> float: ...
    @property
    def readout(self) -> float: ...
    @property
    def readout_direction(self) -> str: ...
    @property
    def lines(self) -> float:
        """Lines per frame: ``height``, or ``width`` for a column readout."""
    def undistort_bearing(self, u: float, v: float) -> npt.NDArray[np.float64]:
        """``[x, y, 1]``, the pixel's undistorted normalised coordinates (``ValueError``
        where the distortion is not invertible)."""
    def readout_line(self, u: float, v: float) -> float:
        """``v``, ``height - 1 - v``, ``u`` or ``width - 1 - u`` by the readout direction."""
    def project(self, point: ArrayLike) -> Optional[npt.NDArray[np.float64]]:
        """The distorted pixel of a camera-frame point, or None."""
    def to_dict(self) -> dict[str, Any]:
        """The pair file's ``camera`` object (the pinhole short form for a PINHOLE read
        from the top)."""

class GyroLog:
    """Gyro samples around the two frames of a pair (the pair file's ``gyro_log``).

    ``samples``: N x 4 ``[t, wx, wy, wz]``, gyro clock (s) and gyro axes (rad/s), increasing
    t. ``frame_times``: the frame times of image 1 and 2 (s). ``camera_from_gyro``: ``M``
    with ``w_cam = M w_gyro`` (default identity). ``time_offset``: gyro time of an image's
    row 0 minus its frame time (s). The samples must cover each image's readout
    ``[t_k + time_offset, t_k + time_offset + height * readout]`` with no gap longer than a
    readout (checked when a pair is made from the log)."""

    def __init__(
        self,
        samples: ArrayLike,
        frame_times: ArrayLike,
        camera_from_gyro: Optional[ArrayLike] = None,
        time_offset: float = 0.0,
    ) -> None: ...
    @staticmethod
    def excerpt(
        samples: ArrayLike,
        frame_times: ArrayLike,
        duration: float,
        margin: float = 0.03,
        camera_from_gyro: Optional[ArrayLike] = None,
        time_offset: float = 0.0,
    ) -> GyroLog:
        """The samples of a long sorted log that a pair needs, as ``rspose make-pair`` keeps
        them: within ``margin`` s of both readouts (``duration`` = height x readout) and
        everything between, plus one sample beyond each end."""
    @property
    def samples(self) -> npt.NDArray[np.float64]: ...
    @property
    def frame_times(self) -> npt.NDArray[np.float64]: ...
    @property
    def camera_from_gyro(self) -> npt.NDArray[np.float64]: ...
    @property
    def time_offset(self) -> float: ...
    def __len__(self) -> int: ...

class GroundTruth:
    """Ground truth of a simulated pair."""

    @property
    def rotation(self) -> npt.NDArray[np.float64]:
        """R = R2 R1^T, 3 x 3."""
    @property
    def translation(self) -> npt.NDArray[np.float64]:
        """Unit t = R2 (C1 - C2) / |.|."""
    @property
    def omega(self) -> npt.NDArray[np.float64]:
        """True angular velocities, 2 x 3 (rad/s, camera axes)."""
    @property
    def velocity(self) -> npt.NDArray[np.float64]:
        """True linear velocities, 2 x 3 (m/s, world axes)."""
    @property
    def inliers(self) -> npt.NDArray[np.bool_]:
        """False for a simulated outlier."""

class Pair:
    """Two images (``camera`` for both or ``cameras``, one per image): matches, gyro readings or a gyro log, optional gravity and
    ground truth. The command line's pair file (``load_pair``, ``save``); made in Python it
    is checked by the same code with the same messages (``ValueError``)."""

    def __init__(
        self,
        x1: ArrayLike,
        x2: ArrayLike,
        camera: Optional[CameraLike] = None,
        gyro1: Optional[ArrayLike] = None,
        gyro2: Optional[ArrayLike] = None,
        *,
        cameras: Optional[Sequence[CameraLike]] = None,
        gyro_log: Optional[GyroLog] = None,
        gravity1: Optional[ArrayLike] = None,
        gravity2: Optional[ArrayLike] = None,
    ) -> None: ...
    @property
    def x1(self) -> npt.NDArray[np.float64]:
        """Pixels in image 1, N x 2."""
    @property
    def x2(self) -> npt.NDArray[np.float64]:
        """Pixels in image 2, N x 2."""
    @property
    def camera(self) -> Camera:
        """The camera of both images (``ValueError`` if they differ)."""
    @property
    def cameras(self) -> Tuple[Camera, Camera]:
        """The cameras of image 1 and image 2."""
    @property
    def gyro1(self) -> Optional[npt.NDArray[np.float64]]: ...
    @property
    def gyro2(self) -> Optional[npt.NDArray[np.float64]]: ...
    @property
    def gravity1(self) -> Optional[npt.NDArray[np.float64]]: ...
    @property
    def gravity2(self) -> Optional[npt.NDArray[np.float64]]: ...
    @property
    def gyro_log(self) -> Optional[GyroLog]: ...
    @property
    def ground_truth(self) -> Optional[GroundTruth]: ...
    @property
    def path(self) -> Optional[pathlib.Path]:
        """The file it was loaded from (errors of its estimates name it, as the CLI does)."""
    def estimate(
        self, method: Method = "grsrp+", *, rows: Rows = "integrated", preset: Preset = "default", **options: Any
    ) -> Estimate:
        """``estimate_relative_pose`` on this pair."""
    def gyro_relative_rotation(self) -> Optional[npt.NDArray[np.float64]]:
        """R = R2 R1^T integrated from the gyro log between the frames' first rows (the
        rotation reference of real recordings), or None."""
    def save(self, path: PathLike, compact: bool = False) -> None:
        """Writes the pair file atomically."""
    def to_json(self) -> str: ...
    def __len__(self) -> int: ...

class Quality(TypedDict):
    inlier_ratio: float
    parallax_px: float
    epipolar_px: float
    homography_px: float
    too_few_inliers: bool
    translation_undetermined: bool
    near_planar: bool
    low_inlier_ratio: bool
    collinear: bool
    gyro_noise_runaway: bool

class Estimate:
    """A relative pose (x2 = R x1 + t between the row-0 poses) and its quality report."""

    @property
    def method(self) -> Method: ...
    @property
    def rotation(self) -> npt.NDArray[np.float64]:
        """R = R2 R1^T, 3 x 3."""
    @property
    def translation(self) -> npt.NDArray[np.float64]:
        """Unit t."""
    @property
    def inliers(self) -> npt.NDArray[np.bool_]:
        """One flag per match."""
    @property
    def num_inliers(self) -> int: ...
    @property
    def iterations(self) -> int:
        """RANSAC iterations of the final RANSAC stage."""
    @property
    def ransac_score(self) -> float: ...
    @property
    def refinement_iterations(self) -> int: ...
    @property
    def refinement_cost(self) -> Optional[float]: ...
    @property
    def inlier_ratio(self) -> float: ...
    @property
    def parallax_px(self) -> float: ...
    @property
    def epipolar_px(self) -> float: ...
    @property
    def homography_px(self) -> float: ...
    @property
    def flags(self) -> list[str]:
        """Raised flags among too_few_inliers, translation_undetermined, near_planar,
        low_inlier_ratio, collinear, gyro_noise_runaway."""
    @property
    def quality(self) -> Quality: ...
    @property
    def angular_velocity(self) -> Optional[npt.NDArray[np.float64]]:
        """nrsrp only: 2 x 3 (rad/s, camera axes)."""
    @property
    def linear_velocity(self) -> Optional[npt.NDArray[np.float64]]:
        """nrsrp and rectified+v: 2 x 3 (baselines/s, camera-1 row-0 frame)."""
    @property
    def velocity_fit(self) -> Optional[dict[str, Any]]:
        """rectified+v only: ``outcome`` and its statistics."""
    @property
    def noise_fit(self) -> Optional[dict[str, float]]:
        """With ``fit_gyro_noise``: the fitted ``gyro_noise`` (rad/s) and ``truncation``."""
    @property
    def readout_scale(self) -> Optional[float]:
        """With ``refine_readout=True``: the refined readout time over the nominal one."""
    def to_dict(self) -> dict[str, Any]:
        """The object ``rspose estimate --json`` prints, without ``seconds`` and reference
        errors (``inliers`` is the count there)."""

def estimate_relative_pose(
    x1: ArrayLike,
    x2: ArrayLike,
    camera: Optional[CameraLike] = None,
    gyro1: Optional[ArrayLike] = None,
    gyro2: Optional[ArrayLike] = None,
    method: Method = "grsrp+",
    *,
    cameras: Optional[Sequence[CameraLike]] = None,
    gyro_log: Optional[GyroLog] = None,
    gravity1: Optional[ArrayLike] = None,
    gravity2: Optional[ArrayLike] = None,
    rows: Rows = "integrated",
    preset: Preset = "default",
    **options: Any,
) -> Estimate:
    """Relative pose of two rolling-shutter views from N x 2 pixel matches.

    ``camera``: both images' camera (a ``Camera`` or the pair file's camera dict), or
    ``cameras``: one per image (exactly one of the two).
    ``gyro1``/``gyro2``: each view's gyro reading (rad/s, camera axes); optional with
    ``gyro_log``, whose samples then give the row rotations (``rows="constant"``: each
    frame's mean rate). ``gravity1``/``gravity2``: each view's gravity direction (camera
    axes at row 0, any length), needed by ``grsrp-gravity``. ``preset``: ``"default"``
    (library defaults) or ``"paper"``. ``**options``: the Rust ``EstimateOptions`` fields
    on the preset: the ``RobustOptions`` fields flat or as ``robust={...}`` (``threshold``,
    ``global_shutter_threshold``, ``rolling_shutter_allowance``, ``adaptive``,
    ``success_probability``, ``min_iterations``, ``max_iterations``,
    ``local_optimisation``, ``final_refinement``, ``seed``, ``pixel_noise``, ``gyro_noise``,
    ``fit_gyro_noise``, ``max_points``, ``gravity_noise_deg``), ``refinement``, ``quality`` and ``velocity``
    as dicts, ``essential_solver`` (five_point, eight_point), ``grsrp_solver`` (ten,
    twenty), ``grsrp_model`` (exact, paper: the model grsrp scores and refines with),
    ``gravity_solver`` (six, twelve), ``r0_source`` (gsrp, rectified, gyro or a
    3 x 3 rotation), ``nrsrp_cauchy_px``, ``refine_readout`` (refine a common scale of the
    views' readout times with the pose; gyro-aided methods). Defaults: ``options()``.
    """

def estimate_many(
    pairs: Iterable[Union[Pair, PathLike, Mapping[str, Any], Sequence[Any]]],
    method: Method = "grsrp+",
    *,
    rows: Rows = "integrated",
    preset: Preset = "default",
    threads: Optional[int] = None,
    errors: Literal["raise", "return"] = "raise",
    **options: Any,
) -> list[Any]:
    """Many pairs on all cores (or ``threads``) with the GIL released; equals a loop of
    ``estimate_relative_pose``. Items: ``Pair``, pair-file paths, dicts with the pair
    arguments of ``estimate_relative_pose``, or tuples ``(x1, x2, camera, gyro1, gyro2)``.
    ``errors="return"`` puts each failure's exception in its place."""

def options(method: Method = "grsrp+", *, preset: Preset = "default", **options: Any) -> dict[str, Any]:
    """Every option with its value for ``method`` and ``preset`` (the Rust API's defaults),
    with ``**options`` applied: a nested dict that ``**`` passes back unchanged."""

def load_pair(path: PathLike) -> Pair:
    """Reads and checks a pair file (``OSError`` if unreadable, ``ValueError`` if invalid)."""

def simulate(
    *,
    camera: Optional[CameraLike] = None,
    camera2: Optional[CameraLike] = None,
    points: int = 150,
    min_depth: float = 1.0,
    max_depth: float = 60.0,
    rotation_std_deg: float = 10.0,
    translation_std: float = 2.0,
    angular_velocity: float = 2.5,
    linear_velocity: float = 0.0,
    pixel_noise: float = 1.0,
    gyro_noise: float = 0.1,
    outlier_fraction: float = 0.0,
    gravity_noise_deg: float = 1.0,
    seed: int = 0,
    plane_depth: Optional[float] = None,
) -> Pair:
    """One pair of the paper's synthetic protocol with ground truth (``rspose simulate``);
    unset arguments take the Rust ``SimulationOptions`` defaults shown here (camera:
    ``Camera.paper()``; ``camera2``: view 2's own camera, if it differs)."""

def solve_essential(
    x1: ArrayLike, x2: ArrayLike, camera: CameraLike, solver: Literal["five_point", "eight_point"] = "five_point"
) -> list[npt.NDArray[np.float64]]:
    """Essential matrices from 5 (generated gs5pt) or >= 8 (linear) pixel matches."""

def solve_grsrp(
    x1: ArrayLike,
    x2: ArrayLike,
    camera: CameraLike,
    gyro1: ArrayLike,
    gyro2: ArrayLike,
    r0: ArrayLike,
    solver: Literal["ten", "twenty"] = "ten",
) -> list[Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]]:
    """The generated G-RSRP solver on 5 pixel matches: (R, t) pairs, R = R0 exp([a]x)."""

def solve_gravity(
    x1: ArrayLike,
    x2: ArrayLike,
    camera: CameraLike,
    gyro1: ArrayLike,
    gyro2: ArrayLike,
    gravity1: ArrayLike,
    gravity2: ArrayLike,
    solver: Literal["six", "twelve"] = "six",
) -> list[Tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]]:
    """The generated known-gravity solver on 3 pixel matches: (R, t) pairs, R g1 || g2."""

def rotation_error_deg(reference: ArrayLike, rotation: ArrayLike) -> float:
    """acos((tr(R_ref^T R) - 1) / 2) in degrees."""

def translation_error_deg(reference: ArrayLike, translation: ArrayLike) -> float:
    """acos(t_ref . t) in degrees."""

def methods() -> list[Method]:
    """The method names, in the README's order."""
