"""Bad input raises ValueError or TypeError, never crashes; where the command line can be
given the same input (a pair file), the message is the one it prints."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import rspose

from conftest import real_pairs

CAMERA = {"fx": 640.0, "fy": 640.0, "cx": 960.0, "cy": 540.0, "width": 1920.0,
          "height": 1080.0, "readout": 6e-5}


@pytest.fixture(scope="module")
def good():
    """A valid simulated pair as a pair-file dict."""
    return json.loads(rspose.simulate(seed=4, points=40).to_json())


def cli_message(cli, tmp_path, pair: dict, *args: str, command: str = "estimate") -> str:
    """The CLI's one-line message for the pair file `pair`, without `rspose: ` and the
    file's path, which Python, given arrays, has no name for."""
    path = tmp_path / "bad.json"
    path.write_text(json.dumps(pair))
    code, _, err = cli(command, path, *args)
    assert code == 2, err
    line = err.strip()
    assert line.startswith("rspose: ")
    return line[len("rspose: "):].replace(f"{path}: ", "")


def estimate(pair: dict, method="grsrp+", **options):
    """`estimate_relative_pose` on the pair-file dict's content."""
    m = np.array(pair["matches"], dtype=float).reshape(-1, 2, 2)
    gyro = pair.get("gyro") or [None, None]
    gravity = pair.get("gravity") or [None, None]
    log = pair.get("gyro_log")
    gyro_log = rspose.GyroLog(**log) if log else None
    return rspose.estimate_relative_pose(
        m[:, 0], m[:, 1], pair["camera"], gyro[0], gyro[1], method,
        gravity1=gravity[0], gravity2=gravity[1], gyro_log=gyro_log, **options,
    )


def same_as_cli(cli, tmp_path, pair, method="grsrp+", error=ValueError):
    with pytest.raises(error) as e:
        estimate(pair, method)
    assert str(e.value) == cli_message(cli, tmp_path, pair, "--method", method)
    return str(e.value)


def test_invalid_camera(good, cli, tmp_path):
    bad = {**good, "camera": {**good["camera"], "fx": -1.0}}
    msg = same_as_cli(cli, tmp_path, bad)
    assert msg.startswith("invalid field `camera.fx`: camera focal length `fx`")
    bad = {**good, "camera": {**good["camera"], "readout": 1.0}}
    assert "camera.readout" in same_as_cli(cli, tmp_path, bad)


def test_implausible_gyro(good, cli, tmp_path):
    bad = {**good, "gyro": [[0.0, 200.0, 0.0], good["gyro"][1]]}
    assert same_as_cli(cli, tmp_path, bad).startswith("invalid field `gyro[0]`")


def test_too_few_and_duplicate_matches(good, cli, tmp_path):
    few = {**good, "matches": good["matches"][:4]}
    few.pop("ground_truth")
    assert same_as_cli(cli, tmp_path, few) == "method grsrp+ needs at least 5 matches, got 4"
    assert "at least 17" in same_as_cli(cli, tmp_path, {**few, "matches": good["matches"][:16]}, "nrsrp")
    dup = {**few, "matches": [good["matches"][0]] * 8}
    assert same_as_cli(cli, tmp_path, dup).startswith("degenerate input: only 1 distinct")


def test_gravity(good, cli, tmp_path):
    no_gravity = {k: v for k, v in good.items() if k != "gravity"}
    msg = same_as_cli(cli, tmp_path, no_gravity, "grsrp-gravity")
    assert msg == "method grsrp-gravity needs the gravity direction of both views; view 1 has none"
    zero = {**good, "gravity": [[0.0, 0.0, 0.0], good["gravity"][1]]}
    assert same_as_cli(cli, tmp_path, zero, "grsrp-gravity").startswith("invalid field `gravity[0]`")
    # One view only: the pair file's field error (the CLI adds where in the file).
    one = {**good, "gravity": [good["gravity"][0], None]}
    with pytest.raises(ValueError) as e:
        estimate(one, "grsrp-gravity")
    assert str(e.value) in cli_message(cli, tmp_path, one)
    assert str(e.value).startswith("field `gravity[1]`: expected three numbers")
    x = np.array(good["matches"])
    with pytest.raises(ValueError, match="gravity1 must be 3 numbers"):
        rspose.estimate_relative_pose(x[:, 0], x[:, 1], CAMERA, [0, 0, 0], [0, 0, 0],
                                      gravity1=[1.0, 2.0], gravity2=[0, 1, 0])


def test_gyro_log_errors(cli, tmp_path):
    pair = json.loads(real_pairs()[0].read_text())
    unsorted = json.loads(json.dumps(pair))
    s = unsorted["gyro_log"]["samples"]
    s[10], s[11] = s[11], s[10]
    assert same_as_cli(cli, tmp_path, unsorted).startswith("invalid field `gyro_log.samples[11]`")
    short = json.loads(json.dumps(pair))
    short["gyro_log"]["samples"] = short["gyro_log"]["samples"][:20]
    assert "do not cover image 1's readout" in same_as_cli(cli, tmp_path, short)
    neither = {k: v for k, v in pair.items() if k not in ("gyro", "gyro_log")}
    assert same_as_cli(cli, tmp_path, neither) == "invalid field `gyro`: missing (give `gyro` or `gyro_log`)"


def test_unknown_method_is_the_cli_message(good, cli, tmp_path):
    with pytest.raises(ValueError) as e:
        estimate(good, "five-point")
    assert str(e.value) == cli_message(cli, tmp_path, good, "--method", "five-point")


def test_simulation_options_are_the_cli_messages(cli, tmp_path):
    for kwargs, args in [({"points": 0}, ["--points", "0"]),
                         ({"outlier_fraction": 1.0}, ["--outliers", "1"]),
                         ({"angular_velocity": -1.0}, ["--angular=-1"])]:
        with pytest.raises(ValueError) as e:
            rspose.simulate(**kwargs)
        code, _, err = cli("simulate", *args, "-o", tmp_path / "s.json")
        assert code == 2 and err.strip() == f"rspose: {e.value}"


def test_non_finite_pixels_name_the_match(good):
    x = np.array(good["matches"], dtype=float)
    x1, x2 = x[:, 0].copy(), x[:, 1].copy()
    x2[3, 1] = math.nan
    with pytest.raises(ValueError, match=r"^invalid field `matches\[3\]`: non-finite pixel coordinate$"):
        rspose.estimate_relative_pose(x1, x2, CAMERA, good["gyro"][0], good["gyro"][1])


def test_shapes_and_types(good):
    x = np.array(good["matches"], dtype=float)
    x1, x2, g = x[:, 0], x[:, 1], good["gyro"]
    with pytest.raises(ValueError, match=r"x1 must have shape \(N, 2\).*got shape \(40, 3\)"):
        rspose.estimate_relative_pose(np.ones((40, 3)), x2, CAMERA, *g)
    with pytest.raises(ValueError, match="same number of rows"):
        rspose.estimate_relative_pose(x1[:10], x2, CAMERA, *g)
    with pytest.raises(TypeError, match="x1: expected an array of numbers"):
        rspose.estimate_relative_pose([["a", "b"]], x2, CAMERA, *g)
    with pytest.raises(TypeError, match="camera: expected rspose.Camera or a dict"):
        rspose.estimate_relative_pose(x1, x2, [640, 640], *g)
    with pytest.raises(ValueError, match="camera: missing field `readout`"):
        rspose.estimate_relative_pose(x1, x2, {k: v for k, v in CAMERA.items() if k != "readout"}, *g)
    with pytest.raises(ValueError, match="gyro2 must be 3 numbers"):
        rspose.estimate_relative_pose(x1, x2, CAMERA, g[0], [1.0, 2.0])
    with pytest.raises(ValueError, match="gyro1 and gyro2"):
        rspose.estimate_relative_pose(x1, x2, CAMERA, g[0])
    with pytest.raises(TypeError, match="gyro_log: expected rspose.GyroLog"):
        rspose.estimate_relative_pose(x1, x2, CAMERA, *g, gyro_log={"samples": []})
    # Integer arrays and lists are accepted as numbers.
    assert rspose.estimate_relative_pose(x1.tolist(), x2.round().astype(int), CAMERA, *g).rotation.shape == (3, 3)


def test_options(good):
    x = np.array(good["matches"], dtype=float)
    args = (x[:, 0], x[:, 1], CAMERA, *good["gyro"])
    with pytest.raises(TypeError, match="unexpected keyword argument 'iterations'"):
        rspose.estimate_relative_pose(*args, iterations=5)
    with pytest.raises(TypeError, match="unknown option `refinement.seed`"):
        rspose.estimate_relative_pose(*args, refinement={"seed": 1})
    with pytest.raises(TypeError, match="option `robust.seed`: expected a non-negative integer"):
        rspose.estimate_relative_pose(*args, seed=-1)
    with pytest.raises(TypeError, match="option `robust.adaptive`: expected a bool"):
        rspose.estimate_relative_pose(*args, adaptive="yes")
    with pytest.raises(TypeError, match="option `robust.threshold`: expected a tuple"):
        rspose.estimate_relative_pose(*args, threshold=2.0)
    with pytest.raises(ValueError, match="unknown threshold kind `pixels`"):
        rspose.estimate_relative_pose(*args, threshold=("pixels", 2.0))
    # Values are checked by the library, with its messages.
    with pytest.raises(ValueError, match=r"^invalid option `robust.max_iterations`: must be at least 1$"):
        rspose.estimate_relative_pose(*args, max_iterations=0)
    with pytest.raises(ValueError, match=r"^invalid option `robust.threshold`: must be finite and positive$"):
        rspose.estimate_relative_pose(*args, threshold=("sampson_pixels", -1.0))
    with pytest.raises(ValueError, match=r"^invalid option `velocity.rounds`"):
        rspose.estimate_relative_pose(*args, velocity={"rounds": 0})
    with pytest.raises(ValueError, match="r0_source.*not a rotation"):
        rspose.estimate_relative_pose(*args, r0_source=2 * np.eye(3))
    with pytest.raises(ValueError, match="r0_source `gyro` needs a gyro_log"):
        rspose.estimate_relative_pose(*args, r0_source="gyro")
    with pytest.raises(ValueError, match="unknown preset `fast`"):
        rspose.estimate_relative_pose(*args, preset="fast")
    with pytest.raises(ValueError, match="unknown rows `exact`"):
        rspose.estimate_relative_pose(*args, rows="exact")
    with pytest.raises(ValueError, match="unknown solver `nine`"):
        rspose.estimate_relative_pose(*args, grsrp_solver="nine")
    with pytest.raises(ValueError, match="grsrp_model.*`linear`"):
        rspose.estimate_relative_pose(*args, grsrp_model="linear")


def test_garbage_never_crashes(good):
    """Extreme but well-typed inputs end in an estimate or a ValueError/NoSolutionError,
    never a panic (which would surface as pyo3's PanicException, a BaseException)."""
    rng = np.random.default_rng(0)
    x = np.array(good["matches"], dtype=float)
    cases = [
        (x[:, 0] * 1e300, x[:, 1], good["gyro"]),
        (x[:, 0], x[:, 1] * -1e12, good["gyro"]),
        (rng.normal(size=(40, 2)), rng.normal(size=(40, 2)), good["gyro"]),
        (np.zeros((40, 2)) + np.arange(40)[:, None], np.zeros((40, 2)), good["gyro"]),
        (x[:, 0], x[:, 1], [[1e-300, 0, 0], [0, 0, 99.9]]),
    ]
    for x1, x2, g in cases:
        for method in rspose.methods():
            try:
                e = rspose.estimate_relative_pose(x1, x2, CAMERA, *g, method,
                                                  gravity1=[0, 1, 0], gravity2=[0, 1, 1e-300])
                assert np.all(np.isfinite(e.rotation)) and abs(np.linalg.norm(e.translation) - 1) < 1e-6
            except (ValueError, rspose.NoSolutionError):
                pass


def test_complex_arrays_and_bad_refinement_options_are_refused(good):
    x = np.array(good["matches"], dtype=float)
    x1, x2, g = x[:, 0], x[:, 1], good["gyro"]
    with pytest.raises(TypeError, match="x1: expected an array of real numbers, got complex values"):
        rspose.estimate_relative_pose(x1 + 1j, x2, CAMERA, *g)
    with pytest.raises(ValueError, match=r"^invalid option `refinement.initial_damping`: must be finite and positive$"):
        rspose.estimate_relative_pose(x1, x2, CAMERA, *g, refinement={"initial_damping": -1.0})


def test_solve_grsrp_refuses_an_r0_that_is_not_a_rotation(good):
    x = np.array(good["matches"], dtype=float)[:5]
    with pytest.raises(ValueError, match="r0 must be a rotation matrix"):
        rspose.solve_grsrp(x[:, 0], x[:, 1], CAMERA, good["gyro"][0], good["gyro"][1], 2 * np.eye(3))


def test_out_of_range_integers_are_value_errors():
    with pytest.raises(ValueError, match="points must be an integer from 0 to"):
        rspose.simulate(points=2**70)
    with pytest.raises(ValueError, match=f"seed must be an integer from 0 to {2**64 - 1}, got -1"):
        rspose.simulate(seed=-1)
    with pytest.raises(TypeError, match="points: expected an integer, got bool"):
        rspose.simulate(points=True)
    with pytest.raises(ValueError, match="threads must be an integer from 0 to"):
        rspose.estimate_many([], threads=2**70)


def test_a_bool_camera_parameter_is_a_type_error():
    with pytest.raises(TypeError, match="Camera: `fx` must be a number, got bool"):
        rspose.Camera(fx=True, fy=640.0, cx=960.0, cy=540.0, width=1920.0, height=1080.0, readout=6e-5)
    assert rspose.Camera(640, 640, 960, 540, 1920, 1080, 0).fx == 640.0
