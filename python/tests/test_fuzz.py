"""Seeded mutation fuzzing of the package's entry points: every argument of a valid call
replaced, one or two at a time, by a hostile value (wrong types and shapes, extreme and
non-finite numbers, huge integers, complex arrays, booleans, nested containers). Each call
must return or raise ``ValueError``, ``TypeError`` or ``NoSolutionError`` with a one-line
message: never a panic (pyo3's ``PanicException``), an ``OverflowError``, a crash or a hang.
"""

from __future__ import annotations

import math
import random
import time

import numpy as np
import pytest
import rspose

CAMERA = {"fx": 640.0, "fy": 640.0, "cx": 960.0, "cy": 540.0, "width": 1920.0,
          "height": 1080.0, "readout": 6e-5}
SEED = 31
CASES = 300
# Per call: the inputs are small (at most a few thousand numbers), so anything slower is
# a hang in the making.
MAX_SECONDS_PER_CALL = 5.0

ACCEPTED = (ValueError, TypeError, rspose.NoSolutionError)


def hostile_values(rng: random.Random, like):
    """Values to put where `like` was: numbers, strings, containers and arrays that are
    wrong in type, shape or range."""
    scalars = [None, True, False, 0, -1, 10**30, -(10**400), 1e308, -1e308, math.nan,
               math.inf, -math.inf, 5e-324, 1j, "1.0", "", b"x", [], {}, object()]
    try:
        shape = np.shape(like) if isinstance(like, (list, tuple, np.ndarray)) else ()
    except ValueError:  # a ragged list from an earlier mutation
        shape = ()
    arrays = [
        np.zeros(shape),
        np.full(shape, np.nan) if shape else np.nan,
        np.full(shape, 1e300) if shape else 1e300,
        np.ones(shape, dtype=complex) if shape else 1 + 1j,
        np.zeros((0,) + tuple(shape[1:])),
        np.zeros(tuple(s + 1 for s in shape) or (3,)),
        np.zeros((2000, 2)),
        np.full(shape or (1,), "a"),
        [[[1.0]]],
        {"fx": 1.0},
    ]
    if isinstance(like, dict) and like:
        key = rng.choice(sorted(like))
        mutated = dict(like)
        choice = rng.randrange(3)
        if choice == 0:
            del mutated[key]
        elif choice == 1:
            mutated[key] = rng.choice(scalars)
        else:
            mutated[key + "_typo"] = mutated.pop(key)
        return mutated
    return rng.choice(scalars + arrays)


def valid_calls():
    """(name, function, positional arguments, keyword arguments) of valid calls."""
    pair = rspose.simulate(seed=4, points=40, camera=CAMERA)
    x1, x2 = pair.x1, pair.x2
    g1, g2 = pair.gyro1, pair.gyro2
    gravity1, gravity2 = np.array([0.0, 1.0, 0.0]), np.array([0.05, 1.0, 0.0])
    return [
        ("estimate_relative_pose", rspose.estimate_relative_pose,
         [x1, x2, CAMERA, g1, g2, "grsrp+"], {"max_iterations": 50}),
        ("estimate_relative_pose (gsrp)", rspose.estimate_relative_pose,
         [x1, x2, CAMERA, g1, g2, "gsrp"], {"max_iterations": 50}),
        ("Pair", rspose.Pair, [x1, x2, CAMERA, g1, g2], {}),
        ("solve_essential", rspose.solve_essential, [x1[:5], x2[:5], CAMERA], {}),
        ("solve_grsrp", rspose.solve_grsrp, [x1[:5], x2[:5], CAMERA, g1, g2, np.eye(3)], {}),
        ("solve_gravity", rspose.solve_gravity,
         [x1[:3], x2[:3], CAMERA, g1, g2, gravity1, gravity2], {}),
        ("options", rspose.options, ["grsrp+"], {"threshold": ("sampson_pixels", 1.0), "max_iterations": 50}),
        ("simulate", rspose.simulate, [], {"points": 30, "seed": 1, "pixel_noise": 1.0}),
    ]


def test_the_unmutated_calls_are_valid():
    for name, fn, args, kwargs in valid_calls():
        try:
            fn(*args, **kwargs)
        except rspose.NoSolutionError:
            pass  # valid input without a solution
        except Exception as e:  # noqa: BLE001 - name the call that is not valid
            pytest.fail(f"{name}: {type(e).__name__}: {e}")


def test_mutated_calls_return_or_raise_a_one_line_error():
    rng = random.Random(SEED)
    calls = valid_calls()
    outcomes: dict[str, dict[str, int]] = {}
    slowest = (0.0, "")
    for case in range(CASES):
        name, fn, args, kwargs = calls[case % len(calls)]
        args, kwargs = list(args), dict(kwargs)
        slots = [("arg", i) for i in range(len(args))] + [("kw", k) for k in kwargs]
        for _ in range(rng.randint(1, 2)):
            if not slots:
                break
            kind, where = rng.choice(slots)
            if kind == "arg":
                args[where] = hostile_values(rng, args[where])
            else:
                kwargs[where] = hostile_values(rng, kwargs[where])
        start = time.perf_counter()
        try:
            fn(*args, **kwargs)
            outcome = "returned"
        except ACCEPTED as e:
            message = str(e)
            assert message and "\n" not in message and len(message) <= 600, (name, case, message)
            outcome = type(e).__name__
        except BaseException as e:  # noqa: BLE001 - a panic surfaces as a BaseException
            pytest.fail(f"case {case} ({name}): {type(e).__name__}: {e}")
        seconds = time.perf_counter() - start
        slowest = max(slowest, (seconds, f"case {case} ({name})"))
        assert seconds < MAX_SECONDS_PER_CALL, (name, case, seconds)
        outcomes.setdefault(name, {}).setdefault(outcome, 0)
        outcomes[name][outcome] += 1
    # Every entry point was exercised, and the hostile values were refused somewhere.
    assert len(outcomes) == len(calls)
    assert sum(n for o in outcomes.values() for k, n in o.items() if k != "returned") > CASES // 2
    print("\nslowest:", slowest)
    for name, o in sorted(outcomes.items()):
        print(f"{name}: {o}")
