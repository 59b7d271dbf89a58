"""Python and the command line give the same answers on the same pair files: the committed
real pairs (`solver/tests/data/cc9pro`, gyro logs) and simulated ones, for every method,
both presets, other seeds, `rows="constant"` and `r0_source="gyro"`. Python reads each pair
twice: as the pair file (`rspose.load_pair`) and as numpy arrays built here from the JSON
(`estimate_relative_pose` with a `GyroLog`), the way an application passes its matches."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import rspose

from conftest import real_pairs

TOL = 1e-12
CLI_ONLY = {"seconds", "gyro_rotation_difference_deg", "rotation_error_deg", "translation_error_deg"}


def differences(a, b, path="") -> list[tuple[str, float]]:
    """(path, |a - b|) for every number of two JSON-like values of the same shape; raises
    AssertionError where shapes or non-numbers differ."""
    if isinstance(a, dict):
        assert isinstance(b, dict) and set(a) == set(b), f"{path}: keys {sorted(a)} vs {sorted(b)}"
        return [d for k in a for d in differences(a[k], b[k], f"{path}.{k}")]
    if isinstance(a, list):
        assert isinstance(b, list) and len(a) == len(b), f"{path}: lengths differ"
        return [d for i, (x, y) in enumerate(zip(a, b)) for d in differences(x, y, f"{path}[{i}]")]
    if isinstance(a, bool) or isinstance(a, str) or a is None:
        assert a == b, f"{path}: {a!r} vs {b!r}"
        return []
    assert isinstance(a, (int, float)) and isinstance(b, (int, float)), f"{path}: {a!r} vs {b!r}"
    if isinstance(a, int) and isinstance(b, int):
        assert a == b, f"{path}: {a} vs {b}"
    return [(path, abs(float(a) - float(b)))]


def assert_same(estimate: rspose.Estimate, cli: dict) -> float:
    """The estimate agrees with the CLI's JSON to TOL everywhere; returns the largest
    difference."""
    ours = estimate.to_dict()
    theirs = {k: v for k, v in cli.items() if k not in CLI_ONLY}
    diffs = differences(ours, theirs)
    worst = max(diffs, key=lambda d: d[1])
    assert worst[1] <= TOL, f"{worst[0]} differs by {worst[1]}"
    # The attributes are the same numbers as the dict.
    np.testing.assert_array_equal(estimate.rotation, np.array(ours["rotation"]))
    np.testing.assert_array_equal(estimate.translation, np.array(ours["translation"]))
    assert estimate.num_inliers == int(estimate.inliers.sum()) == cli["inliers"]
    assert estimate.iterations == cli["iterations"]
    assert estimate.flags == cli["flags"]
    assert estimate.inlier_ratio == pytest.approx(cli["inlier_ratio"], abs=TOL)
    return worst[1]


def pair_from_json(path) -> rspose.Pair:
    """The pair file's content as numpy arrays and a GyroLog, through the public API."""
    d = json.loads(path.read_text())
    m = np.array(d["matches"], dtype=float)
    log = d.get("gyro_log")
    gyro_log = None
    if log is not None:
        gyro_log = rspose.GyroLog(
            np.array(log["samples"]),
            log["frame_times"],
            camera_from_gyro=np.array(log.get("camera_from_gyro", np.eye(3))),
            time_offset=log.get("time_offset", 0.0),
        )
    gyro = d.get("gyro") or [None, None]
    gravity = d.get("gravity") or [None, None]
    return rspose.Pair(
        m[:, 0], m[:, 1], d["camera"], gyro[0], gyro[1],
        gyro_log=gyro_log, gravity1=gravity[0], gravity2=gravity[1],
    )


NO_GRAVITY = [m for m in rspose.methods() if m != "grsrp-gravity"]


@pytest.mark.parametrize("path", real_pairs(), ids=lambda p: p.stem)
def test_real_pairs_every_method_default_preset(path, cli_json):
    loaded = rspose.load_pair(path)
    arrays = pair_from_json(path)
    reference = loaded.gyro_relative_rotation()
    assert reference is not None
    for method in NO_GRAVITY:
        cli = cli_json(path, "--method", method)
        a = loaded.estimate(method)
        b = rspose.estimate_relative_pose(
            arrays.x1, arrays.x2, arrays.camera, method=method, gyro_log=arrays.gyro_log
        )
        assert_same(a, cli)
        assert_same(b, cli)
        assert rspose.rotation_error_deg(reference, a.rotation) == pytest.approx(
            cli["gyro_rotation_difference_deg"], abs=TOL
        )


def test_real_pairs_grsrp_gravity_without_gravity_fails_as_on_the_cli(cli):
    path = real_pairs()[0]
    code, _, err = cli("estimate", path, "--method", "grsrp-gravity")
    assert code == 2
    with pytest.raises(ValueError) as e:
        rspose.load_pair(path).estimate("grsrp-gravity")
    assert err.strip() == f"rspose: {e.value}"
    assert str(e.value).startswith(f"{path}: ")


@pytest.mark.parametrize(
    "cli_args, kwargs",
    [
        (["--preset", "paper"], {"preset": "paper"}),
        (["--seed", "7"], {"seed": 7}),
        (["--rows", "constant"], {"rows": "constant"}),
        (["--r0", "gyro"], {"r0_source": "gyro"}),
        (["--r0", "gsrp", "--seed", "3"], {"r0_source": "gsrp", "robust": {"seed": 3}}),
        (["--preset", "paper", "--seed", "11", "--rows", "constant"],
         {"preset": "paper", "seed": 11, "rows": "constant"}),
    ],
    ids=lambda v: " ".join(v) if isinstance(v, list) else None,
)
def test_real_pairs_presets_seeds_rows_r0(cli_args, kwargs, cli_json):
    for path in real_pairs()[::3]:
        pair = pair_from_json(path)
        for method in ["gsrp", "grsrp+", "rectified", "rectified+v"]:
            cli = cli_json(path, "--method", method, *cli_args)
            est = rspose.estimate_relative_pose(
                pair.x1, pair.x2, pair.camera, method=method, gyro_log=pair.gyro_log, **kwargs
            )
            assert_same(est, cli)


@pytest.mark.parametrize("seed", [1, 2])
def test_simulated_pairs_every_method(seed, tmp_path, cli, cli_json):
    # Simulated in Python and by the CLI with the same options: the same pair file.
    path = tmp_path / "sim.json"
    code, _, err = cli("simulate", "--seed", seed, "--points", 120, "--outliers", 0.25,
                       "--linear", 0.5, "-o", path)
    assert code == 0, err
    simulated = rspose.simulate(seed=seed, points=120, outlier_fraction=0.25, linear_velocity=0.5)
    assert json.loads(simulated.to_json()) == json.loads(path.read_text())
    # The estimates start from the file as the CLI reads it (serde_json's float parsing may
    # differ from the simulator's numbers in the last bit).
    ours = rspose.load_pair(path)
    gt = ours.ground_truth
    for method in rspose.methods():
        c = cli_json(path, "--method", method)
        est = rspose.estimate_relative_pose(
            ours.x1, ours.x2, ours.camera, ours.gyro1, ours.gyro2, method,
            gravity1=ours.gravity1, gravity2=ours.gravity2,
        )
        assert_same(est, c)
        assert rspose.rotation_error_deg(gt.rotation, est.rotation) == pytest.approx(
            c["rotation_error_deg"], abs=TOL
        )
        assert rspose.translation_error_deg(gt.translation, est.translation) == pytest.approx(
            c["translation_error_deg"], abs=TOL
        )


def test_a_pair_saved_from_python_is_read_by_the_cli(tmp_path, cli_json):
    pair = rspose.simulate(seed=5, points=80)
    path = tmp_path / "p.json"
    pair.save(path)
    assert json.loads(path.read_text()) == json.loads(pair.to_json())
    loaded = rspose.load_pair(path)
    assert loaded.path == path and len(loaded) == 80 and loaded.ground_truth is not None
    assert_same(loaded.estimate("rectified"), cli_json(path, "--method", "rectified"))


def test_same_answer_as_the_rust_library_example(binaries):
    """`solver/examples/library.rs` (the README's ten lines) against the same call in
    Python: the default simulated pair, `grsrp+` with the library defaults."""
    import subprocess

    out = subprocess.run([str(binaries["library"])], capture_output=True, text=True, check=True).stdout
    numbers = [float(x) for x in __import__("re").findall(r"-?\d+\.\d+(?:e-?\d+)?", out)]
    rotation, translation = np.array(numbers[:9]).reshape(3, 3), np.array(numbers[9:12])
    inliers = int(__import__("re").search(r"(\d+) inliers", out).group(1))
    pair = rspose.simulate()
    camera = rspose.Camera(fx=640.0, fy=640.0, cx=960.0, cy=540.0, width=1920.0, height=1080.0,
                           readout=60e-6)
    est = rspose.estimate_relative_pose(pair.x1, pair.x2, camera, pair.gyro1, pair.gyro2, "grsrp+")
    assert np.abs(est.rotation - rotation).max() <= TOL
    assert np.abs(est.translation - translation).max() <= TOL
    assert est.num_inliers == inliers


RECORDING = Path(__file__).resolve().parents[3] / "shared" / "realdata" / "cc9pro"


@pytest.mark.skipif(not (RECORDING / "gyro.txt").exists(), reason=f"recording not at {RECORDING}")
def test_gyro_log_excerpt_is_make_pairs(cli_json):
    """`GyroLog.excerpt` on the recording's whole gyro log (what examples/python/cc9pro.py
    does) gives each committed pair the samples `rspose make-pair` gave it, and so the same
    estimates."""
    calibration = json.loads((real_pairs()[0].parent / "calibration.json").read_text())
    log = np.loadtxt(RECORDING / "gyro.txt", delimiter=",")
    samples = np.column_stack([log[:, 3], log[:, :3]])
    frame_times = np.loadtxt(RECORDING / "framestamp.txt")
    camera = rspose.Camera(**calibration["camera"])
    for path in real_pairs()[::4]:
        committed = rspose.load_pair(path)
        n1, n2 = (int(n) for n in path.stem.split("-")[1:])
        excerpt = rspose.GyroLog.excerpt(
            samples, [frame_times[n1 - 1], frame_times[n2 - 1]], camera.height * camera.readout,
            camera_from_gyro=calibration["camera_from_gyro"], time_offset=calibration["time_offset"],
        )
        np.testing.assert_array_equal(excerpt.samples, committed.gyro_log.samples)
        pair = rspose.Pair(committed.x1, committed.x2, camera, gyro_log=excerpt)
        assert_same(pair.estimate("rectified"), cli_json(path, "--method", "rectified"))
