"""The generated minimal solvers on numpy input recover planted poses; `options()` gives the
Rust API's names and defaults and round-trips through `**options`; `simulate` is
deterministic and its ground truth consistent."""

from __future__ import annotations

import numpy as np
import pytest
import rspose


def planted(readout: float, angular: float, seed: int = 3, points: int = 5):
    """A noise-free simulated pair: pixels, camera, true rates, gravity and the pose."""
    cam = rspose.Camera.paper()
    cam = rspose.Camera(cam.fx, cam.fy, cam.cx, cam.cy, cam.width, cam.height, readout)
    p = rspose.simulate(camera=cam, points=points, pixel_noise=0.0, gyro_noise=0.0,
                        gravity_noise_deg=0.0, angular_velocity=angular, seed=seed)
    gt = p.ground_truth
    return p, gt


def best(poses, rotation, translation):
    """Smallest rotation + translation-direction error (deg) over the solutions, t up to sign."""
    return min(
        rspose.rotation_error_deg(rotation, r)
        + min(rspose.translation_error_deg(translation, t), rspose.translation_error_deg(translation, -t))
        for r, t in poses
    )


@pytest.mark.parametrize("solver", ["five_point", "eight_point"])
def test_essential_solvers(solver):
    p, gt = planted(readout=0.0, angular=0.0, points=5 if solver == "five_point" else 12)
    es = rspose.solve_essential(p.x1, p.x2, p.camera, solver=solver)
    t = gt.translation
    tx = np.array([[0, -t[2], t[1]], [t[2], 0, -t[0]], [-t[1], t[0], 0]])
    e_true = tx @ gt.rotation
    e_true /= np.linalg.norm(e_true)
    es = [e / np.linalg.norm(e) for e in es]
    assert min(min(np.abs(e - e_true).max(), np.abs(e + e_true).max()) for e in es) < 1e-8
    with pytest.raises(ValueError, match="5 matches"):
        rspose.solve_essential(p.x1[:4], p.x2[:4], p.camera)


@pytest.mark.parametrize("solver", ["ten", "twenty"])
def test_grsrp_solver_is_exact_without_motion_during_readout(solver):
    p, gt = planted(readout=60e-6, angular=0.0, seed=5)
    r0 = gt.rotation @ _rot([0.01, -0.02, 0.01])
    poses = rspose.solve_grsrp(p.x1, p.x2, p.camera, [0, 0, 0], [0, 0, 0], r0, solver=solver)
    assert 1 <= len(poses) <= (10 if solver == "ten" else 20)
    # R0 enters through the solver's linearisation R = R0 exp([a]x): exact at R0 = R.
    exact = rspose.solve_grsrp(p.x1, p.x2, p.camera, [0, 0, 0], [0, 0, 0], gt.rotation, solver=solver)
    assert best(exact, gt.rotation, gt.translation) < 1e-8
    assert best(poses, gt.rotation, gt.translation) < 0.5


def test_grsrp_solver_uses_the_gyro_in_the_api_convention():
    """Rolling-shutter pairs at 0.3 rad/s (the paper's first-order row model is then close):
    with the true gyro readings the solver's best rotation is far closer than with none or
    with the opposite sign."""
    errors = {"true": [], "none": [], "opposite": []}
    for seed in range(10):
        p, gt = planted(readout=60e-6, angular=0.3, seed=seed)
        w = gt.omega
        for name, (w1, w2) in {"true": (w[0], w[1]), "none": ([0, 0, 0], [0, 0, 0]),
                               "opposite": (-w[0], -w[1])}.items():
            poses = rspose.solve_grsrp(p.x1, p.x2, p.camera, w1, w2, gt.rotation)
            errors[name].append(min([rspose.rotation_error_deg(gt.rotation, r) for r, _ in poses] or [180]))
    median = {k: float(np.median(v)) for k, v in errors.items()}
    assert median["true"] < 0.3 and 5 * median["true"] < median["none"] < median["opposite"], median


@pytest.mark.parametrize("solver", ["six", "twelve"])
def test_gravity_solver(solver):
    p, gt = planted(readout=0.0, angular=0.0, seed=8, points=3)
    poses = rspose.solve_gravity(p.x1, p.x2, p.camera, [0, 0, 0], [0, 0, 0],
                                 p.gravity1, p.gravity2, solver=solver)
    assert best(poses, gt.rotation, gt.translation) < 0.2
    for r, _ in poses:
        g1, g2 = p.gravity1 / np.linalg.norm(p.gravity1), p.gravity2 / np.linalg.norm(p.gravity2)
        assert np.abs(np.cross(r @ g1, g2)).max() < 1e-9
    with pytest.raises(ValueError, match=r"invalid view 1: gravity must be a finite vector"):
        rspose.solve_gravity(p.x1, p.x2, p.camera, [0, 0, 0], [0, 0, 0], [0, 0, 0], p.gravity2)
    with pytest.raises(ValueError, match="unknown solver `seven`"):
        rspose.solve_gravity(p.x1, p.x2, p.camera, [0, 0, 0], [0, 0, 0], p.gravity1, p.gravity2, "seven")


def _rot(v):
    v = np.asarray(v, dtype=float)
    a = np.linalg.norm(v)
    k = np.array([[0, -v[2], v[1]], [v[2], 0, -v[0]], [-v[1], v[0], 0]]) / a
    return np.eye(3) + np.sin(a) * k + (1 - np.cos(a)) * k @ k


def test_options_are_the_rust_defaults_and_presets():
    d = rspose.options()
    assert d["method"] == "grsrp+"
    r = d["robust"]
    assert r["threshold"] == ("sampson_pixels", 2.5)
    assert r["global_shutter_threshold"] == ("sampson_pixels", 2.0)
    assert (r["adaptive"], r["min_iterations"], r["max_iterations"], r["seed"]) == (True, 50, 1000, 0)
    assert (r["pixel_noise"], r["gyro_noise"], r["max_points"]) == (1.0, 0.1, 20000)
    assert r["fit_gyro_noise"] is True
    assert d["r0_source"] == "rectified" and d["essential_solver"] == "five_point"
    assert d["grsrp_model"] == "exact"
    assert d["refinement"]["max_iterations"] == 50 and d["quality"]["min_inliers"] == 15
    assert d["velocity"]["min_inliers"] == 30
    paper = rspose.options("grsrp", preset="paper")
    assert paper["robust"]["threshold"] == ("algebraic", 0.01)
    assert (paper["robust"]["adaptive"], paper["robust"]["max_iterations"]) == (False, 200)
    assert paper["r0_source"] == "gsrp" and paper["grsrp_model"] == "paper"


def test_options_round_trip_through_keywords():
    custom = rspose.options(
        "rectified+v", seed=4, threshold=("algebraic", 0.02), refinement={"fd_step": 1e-7},
        quality={"min_inliers": 9}, velocity={"prior_std": float("inf")}, grsrp_solver="twenty",
        gravity_solver="twelve", essential_solver="eight_point", r0_source=np.eye(3),
        grsrp_model="paper",
        nrsrp_cauchy_px=3.0,
    )
    again = rspose.options(**custom)
    np.testing.assert_array_equal(again.pop("r0_source"), custom.pop("r0_source"))
    assert again == custom
    assert custom["robust"]["seed"] == 4 and custom["velocity"]["prior_std"] == float("inf")
    # The options change the estimate as the Rust API's do.
    p = rspose.simulate(seed=2, points=60, outlier_fraction=0.3)
    a = p.estimate("gsrp", preset="paper", seed=1)
    b = p.estimate("gsrp", preset="paper", seed=2)
    assert a.to_dict() != b.to_dict() or a.iterations == 200


def test_simulate_and_its_ground_truth():
    a = rspose.simulate(seed=11, points=70, outlier_fraction=0.2, linear_velocity=1.0)
    b = rspose.simulate(seed=11, points=70, outlier_fraction=0.2, linear_velocity=1.0)
    assert a.to_json() == b.to_json() and len(a) == 70
    gt = a.ground_truth
    r = gt.rotation
    np.testing.assert_allclose(r @ r.T, np.eye(3), atol=1e-12)
    assert abs(np.linalg.norm(gt.translation) - 1) < 1e-12
    assert gt.inliers.dtype == bool and (~gt.inliers).sum() == 14
    assert np.allclose(np.linalg.norm(gt.velocity, axis=1), 1.0)
    assert a.x1.shape == a.x2.shape == (70, 2) and a.gyro1.shape == (3,)
    e = a.estimate("rectified")
    assert rspose.rotation_error_deg(gt.rotation, e.rotation) < 2.0
    assert e.inliers[gt.inliers].mean() > 0.9


def test_refine_readout_recovers_a_wrong_nominal_readout():
    p = rspose.simulate(angular_velocity=2.5, seed=4)
    cam = p.camera
    wrong = rspose.Camera(cam.fx, cam.fy, cam.cx, cam.cy, cam.width, cam.height, 0.7 * cam.readout)
    plain = rspose.estimate_relative_pose(p.x1, p.x2, wrong, p.gyro1, p.gyro2, "rectified")
    fitted = rspose.estimate_relative_pose(p.x1, p.x2, wrong, p.gyro1, p.gyro2, "rectified",
                                           refine_readout=True)
    assert plain.readout_scale is None and rspose.options()["refine_readout"] is False
    assert abs(fitted.readout_scale * 0.7 - 1.0) < 0.1
    assert fitted.to_dict()["readout_scale"] == fitted.readout_scale
    gt = p.ground_truth
    assert rspose.rotation_error_deg(gt.rotation, fitted.rotation) < rspose.rotation_error_deg(
        gt.rotation, plain.rotation)
    with pytest.raises(ValueError, match="readout"):
        rspose.estimate_relative_pose(p.x1, p.x2, wrong, p.gyro1, p.gyro2, "gsrp", refine_readout=True)
