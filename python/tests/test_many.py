"""`estimate_many` returns what a loop of single estimates returns, in order, for every
kind of input it takes, and releases the GIL while it works."""

from __future__ import annotations

import threading
import time

import numpy as np
import pytest
import rspose

from conftest import real_pairs


def same(a: rspose.Estimate, b: rspose.Estimate) -> None:
    assert a.to_dict() == b.to_dict()
    np.testing.assert_array_equal(a.inliers, b.inliers)


@pytest.mark.parametrize("method", ["grsrp+", "rectified"])
def test_pair_files_equal_a_loop(method):
    paths = real_pairs()
    many = rspose.estimate_many(paths, method, seed=2)
    loop = [rspose.load_pair(p).estimate(method, seed=2) for p in paths]
    assert len(many) == len(loop) == 12
    for a, b in zip(many, loop):
        same(a, b)
    # str paths, Pair objects and one thread: the same again.
    for a, b in zip(rspose.estimate_many([str(p) for p in paths], method, seed=2, threads=1), loop):
        same(a, b)


def test_every_kind_of_input_equals_a_loop():
    sims = [rspose.simulate(seed=s, points=100, outlier_fraction=0.3) for s in range(6)]
    inputs = []
    for k, p in enumerate(sims):
        if k % 3 == 0:
            inputs.append(p)
        elif k % 3 == 1:
            inputs.append((p.x1, p.x2, p.camera, p.gyro1, p.gyro2))
        else:
            inputs.append({"x1": p.x1, "x2": p.x2, "camera": p.camera.to_dict(), "gyro1": p.gyro1,
                           "gyro2": p.gyro2, "gravity1": p.gravity1, "gravity2": p.gravity2})
    for method in ["gsrp", "nrsrp", "grsrp"]:
        many = rspose.estimate_many(inputs, method, preset="paper", seed=9)
        for a, p in zip(many, sims):
            same(a, rspose.estimate_relative_pose(p.x1, p.x2, p.camera, p.gyro1, p.gyro2, method,
                                                  preset="paper", seed=9))
    # A generator works as well as a list.
    many = rspose.estimate_many((p for p in sims), "rectified")
    assert [e.to_dict() for e in many] == [p.estimate("rectified").to_dict() for p in sims]


def test_errors_raise_or_return_in_place(tmp_path):
    good = rspose.simulate(seed=1, points=50)
    few = (good.x1[:4], good.x2[:4], good.camera, good.gyro1, good.gyro2)
    missing = tmp_path / "missing.json"
    with pytest.raises(ValueError, match="needs at least 5 matches, got 4"):
        rspose.estimate_many([good, few, good])
    out = rspose.estimate_many([good, few, missing, good], errors="return")
    assert isinstance(out[0], rspose.Estimate) and isinstance(out[3], rspose.Estimate)
    assert isinstance(out[1], ValueError) and "needs at least 5 matches" in str(out[1])
    assert isinstance(out[2], OSError) and str(missing) in str(out[2])
    # Pairs that cannot even be read as arguments name their index.
    with pytest.raises(ValueError, match=r"^pairs\[1\]: x1 must have shape"):
        rspose.estimate_many([good, (np.ones(3), good.x2, good.camera, good.gyro1, good.gyro2)])
    with pytest.raises(TypeError, match=r"^pairs\[0\]: expected a Pair"):
        rspose.estimate_many([42])
    with pytest.raises(TypeError, match=r"pairs\[0\]: missing key `camera`"):
        rspose.estimate_many([{"x1": good.x1, "x2": good.x2}])
    with pytest.raises(TypeError, match="single one"):
        rspose.estimate_many(good)
    with pytest.raises(ValueError, match="threads must be at least 1"):
        rspose.estimate_many([good], threads=0)
    with pytest.raises(ValueError, match="unknown errors"):
        rspose.estimate_many([good], errors="ignore")
    assert rspose.estimate_many([]) == []


def test_pair_file_errors_name_the_file_as_the_cli_does(tmp_path, cli):
    path = tmp_path / "few.json"
    p = rspose.simulate(seed=2, points=10)
    p.save(path)
    code, _, err = cli("estimate", path, "--method", "nrsrp")
    assert code == 2
    (out,) = rspose.estimate_many([path], "nrsrp", errors="return")
    assert err.strip() == f"rspose: {out}"


def test_the_gil_is_released():
    """A Python thread keeps running while estimate_many works."""
    pairs = [rspose.simulate(seed=s, points=300, outlier_fraction=0.5) for s in range(8)] * 3
    ticks = []
    done = threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    t = threading.Thread(target=tick)
    start = time.perf_counter()
    t.start()
    try:
        rspose.estimate_many(pairs, "nrsrp", threads=1)
    finally:
        done.set()
        t.join()
    elapsed = time.perf_counter() - start
    during = [x for x in ticks if x < start + elapsed * 0.9]
    # Held GIL: the ticker would stall for the whole call.
    assert elapsed > 0.05 and len(during) > 10, (elapsed, len(during))
