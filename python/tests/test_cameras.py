"""Camera models, readout directions and a camera per view, as the pair file has them."""

from __future__ import annotations

import numpy as np
import pytest

import rspose

OPENCV = {
    "model": "OPENCV",
    "width": 1920,
    "height": 1080,
    "params": [700.0, 690.0, 955.0, 545.0, -0.28, 0.08, 0.0008, -0.0005],
    "readout": 6e-5,
}
FISHEYE = {
    "model": "OPENCV_FISHEYE",
    "width": 1920,
    "height": 1080,
    "params": [600.0, 600.0, 960.0, 540.0, 0.05, -0.01, 0.002, -0.0005],
    "readout": 3.4e-5,
    "readout_direction": "right_to_left",
}


def rotation_error(e, gt) -> float:
    return rspose.rotation_error_deg(gt.rotation, e.rotation)


def test_camera_objects_and_their_dicts():
    cam = rspose.Camera.from_params("OPENCV", 1920, 1080, OPENCV["params"], 6e-5)
    assert cam.model == "OPENCV" and cam.params == OPENCV["params"]
    assert (cam.fx, cam.fy, cam.cx, cam.cy) == (700.0, 690.0, 955.0, 545.0)
    assert cam.readout_direction == "top_to_bottom" and cam.lines == 1080
    d = cam.to_dict()
    assert d["model"] == "OPENCV" and d["params"] == OPENCV["params"]
    # The pinhole keeps its short form.
    assert set(rspose.Camera.paper().to_dict()) == {"fx", "fy", "cx", "cy", "width", "height", "readout"}
    fish = rspose.Camera.from_params(**{**FISHEYE, "readout_direction": "left_to_right"})
    assert fish.readout_line(100.0, 7.0) == 100.0 and fish.lines == 1920
    # Round trip through the bearing; a pixel beyond the fisheye's horizon has none.
    b = fish.undistort_bearing(1500.0, 900.0)
    assert b[2] == 1.0
    np.testing.assert_allclose(fish.project(b * 4.0), [1500.0, 900.0], atol=1e-6)
    with pytest.raises(ValueError, match="not invertible"):
        fish.undistort_bearing(1919.0, 1079.0)
    with pytest.raises(ValueError, match=r"OPENCV takes 8 params \[fx, fy, cx, cy, k1, k2, p1, p2\], got 4"):
        rspose.Camera.from_params("OPENCV", 1920, 1080, [1.0, 2.0, 3.0, 4.0], 0.0)
    with pytest.raises(ValueError, match="unknown camera model `KB`"):
        rspose.Camera.from_params("KB", 1920, 1080, [1.0], 0.0)
    with pytest.raises(ValueError, match="readout_direction"):
        rspose.Camera(1, 1, 1, 1, 10, 10, 0.0, readout_direction="sideways")


def test_simulated_distorted_pairs_are_estimated_exactly():
    for camera in (OPENCV, FISHEYE):
        p = rspose.simulate(camera=camera, pixel_noise=0.0, gyro_noise=0.0, seed=2)
        assert p.camera.model == camera["model"]
        for method in ("rectified", "grsrp+"):
            e = p.estimate(method)
            assert rotation_error(e, p.ground_truth) < 1e-4, (camera["model"], method)
        # The same through the pair's arrays and the camera dict.
        e = rspose.estimate_relative_pose(p.x1, p.x2, camera, p.gyro1, p.gyro2, "rectified")
        assert rotation_error(e, p.ground_truth) < 1e-4


def test_a_camera_per_view_and_its_errors():
    p = rspose.simulate(camera=OPENCV, pixel_noise=0.0, gyro_noise=0.0, seed=4)
    cam = p.camera
    pair = rspose.Pair(p.x1, p.x2, cameras=[cam, OPENCV], gyro1=p.gyro1, gyro2=p.gyro2)
    assert pair.cameras == (cam, cam)
    e = rspose.estimate_relative_pose(p.x1, p.x2, None, p.gyro1, p.gyro2, "rectified", cameras=(cam, cam))
    assert rotation_error(e, p.ground_truth) < 1e-4
    other = rspose.Pair(p.x1, p.x2, cameras=[cam, rspose.Camera.paper()], gyro1=p.gyro1, gyro2=p.gyro2)
    assert other.cameras[1] == rspose.Camera.paper()
    with pytest.raises(ValueError, match="different cameras"):
        other.camera
    assert '"cameras"' in other.to_json()
    with pytest.raises(ValueError, match="not both"):
        rspose.Pair(p.x1, p.x2, cam, p.gyro1, p.gyro2, cameras=[cam, cam])
    with pytest.raises(TypeError, match="missing `camera`"):
        rspose.Pair(p.x1, p.x2, gyro1=p.gyro1, gyro2=p.gyro2)
    with pytest.raises(ValueError, match="one camera for each of the two images, got 1"):
        rspose.Pair(p.x1, p.x2, cameras=[cam], gyro1=p.gyro1, gyro2=p.gyro2)
    with pytest.raises(ValueError, match=r"cameras\[1\]: camera: unknown field `focal`"):
        rspose.Pair(p.x1, p.x2, cameras=[cam, {**OPENCV, "focal": 3}], gyro1=p.gyro1, gyro2=p.gyro2)
    bad = {**OPENCV, "params": OPENCV["params"][:4] + [float("nan")] + OPENCV["params"][5:]}
    with pytest.raises(ValueError, match=r"invalid field `camera.params\[4\]`: .*`k1`"):
        rspose.Pair(p.x1, p.x2, bad, p.gyro1, p.gyro2)
    # A pixel without a bearing is named by its match.
    fish = rspose.simulate(camera=FISHEYE, pixel_noise=0.0, gyro_noise=0.0, seed=1)
    x2 = fish.x2.copy()
    x2[5] = [1919.0, 1079.0]
    with pytest.raises(ValueError, match="match 5: image 2's pixel has no bearing"):
        rspose.estimate_relative_pose(fish.x1, x2, FISHEYE, fish.gyro1, fish.gyro2, "rectified")


def test_simulate_with_a_camera_per_view():
    p = rspose.simulate(camera=OPENCV, camera2=FISHEYE, pixel_noise=0.0, gyro_noise=0.0, seed=3)
    assert [c.model for c in p.cameras] == ["OPENCV", "OPENCV_FISHEYE"]
    assert p.cameras[1].readout_direction == "right_to_left"
    e = p.estimate("rectified")
    assert rotation_error(e, p.ground_truth) < 1e-4
    again = rspose.Pair(p.x1, p.x2, cameras=[OPENCV, FISHEYE], gyro1=p.gyro1, gyro2=p.gyro2)
    assert again.cameras == p.cameras
