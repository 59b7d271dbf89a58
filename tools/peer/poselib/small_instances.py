#!/usr/bin/env python3
"""Planted geometric instances of the small classic problems, written twice: once in our
problem file's data-slot order (the `data slot order` line of `mingen inspect`, for
`tools/emitted_solver/run.sh` and `mingen audit --instances-from`) and once as PoseLib's
solver inputs (for small_solvers.cc), with the planted solution in our unknowns' order.

  small_instances.py PROBLEM COUNT SEED OURS PEER SOLUTIONS

PROBLEM (templates/classic/PROBLEM.mp)       PoseLib          peer line (x y z each)
  p3p        lambda x = R X + t               p3p              x[3] (unit), X[3]
  gp3p       p + lambda x = R X + t           gp3p             p[3], x[3] (unit), X[3]
  up2p_elim  lambda x = R X + t, R about y    up2p             x[2] (unit), X[2]
  relpose_upright_3pt_elim                    relpose_upright_3pt  x1[3], x2[3] (unit)
             lambda2 x2 = R lambda1 x1 + t, R about y, |t| = 1
  relpose_upright_3pt_tan  the same, the yaw a as q = tan(a / 2)
  p3ll       l' (R (X + mu V) + t) = 0        p3ll             l[3], X[3], V[3]
  relpose_6pt_focal  x2' F x1 = 0, F = K^-T [t]x R K^-1, K = diag(f, f, 1)
                                              relpose_6pt_shared_focal  x1[6], x2[6]
             (homogeneous image points), then our data: the null-space basis F1, F2, F3
             of the six epipolar constraints (27 numbers, row-major)
  p2p2pl     lambda x = R X + t, 2 points;    p2p2pl           x[2] (unit), X[2],
             lambda y = R (P + mu V) + t, 2 lines              y[2] (unit), P[2], V[2]
  p2p2pl_canonical  the same scene in PoseLib's canonical frames   p2p2pl  as p2p2pl, then
             the frames' rotations rc, r0 (row-major)
  p35pf      lambda (u/f, v/f, 1) = R X + t   p35pf            (u v)[4], X[4]: our line
             (7 of the 8 equations of 4 points)
  p35pf_nullspace  the same scene; our data the null space N of the camera's seven
             linear equations (12 x 5)       p35pf            (u v)[4], X[4], N

Geometry: camera-frame points with x, y uniform in [-1, 1] and depth in [2, 6] (in front
of every camera), rotations uniform (a normalised Gaussian quaternion; about the y axis,
the angle uniform, for the upright problems), translations with entries N(0, 1)
(N(0, 0.5) between the two views of the relative pose). Solutions: p3p depths along
(x, y, 1); gp3p distances along unit rays from the origins p; up2p (cos, sin, t);
relative pose (cos, sin, t / |t|); p3ll the rotation as (b, c, d) = (x, y, z) / w of its
quaternion; relpose_6pt_focal (x, y, w) with
F ∝ x F1 + y F2 + F3 and w = 1 / f^2 (f uniform in [0.5, 2], a rotation near the
identity, t entries N(0, 0.5)). Our solver's data is the null-space basis: its time does
not include computing it, PoseLib's does. p2p2pl and p35pf: (b, c, d) = (x, y, z) / w of
the quaternion (R = Rq / (1 + b^2 + c^2 + d^2)); p2p2pl l = (1 + b^2 + c^2 + d^2) z_0,
the scaled depth of point 0 (our image points are (u, v) of (u, v, 1)); each line is given
by a point P = Q - mu V (mu N(0, 1)) on the world line through the seen point Q, and a
unit direction V uniform on the sphere. p35pf (b, c, d, l, f) with
l = (1 + b^2 + c^2 + d^2) z_0 / f (the ray of point 0 is (u, v, f)) and f uniform in
[0.5, 2]; image points (u, v) = f (x, y) / z. Our equations leave out u of point 3,
PoseLib's v of point 3 (both exact here); PoseLib scales the image points by their mean
norm within its call.
"""
import math
import random
import sys


def quaternion(rng):
    while True:
        q = [rng.gauss(0, 1) for _ in range(4)]
        n = math.sqrt(sum(x * x for x in q))
        if n > 1e-3 and abs(q[0]) > 0.05 * n:
            return [x / n for x in q]


def rotation(q):
    w, x, y, z = q
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def upright(angle):
    c, s = math.cos(angle), math.sin(angle)
    return [[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]]


def mul(m, v):
    return [sum(m[i][j] * v[j] for j in range(3)) for i in range(3)]


def tmul(m, v):
    return [sum(m[j][i] * v[j] for j in range(3)) for i in range(3)]


def sub(a, b):
    return [x - y for x, y in zip(a, b)]


def add(a, b):
    return [x + y for x, y in zip(a, b)]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def unit(v):
    n = math.sqrt(sum(x * x for x in v))
    return [x / n for x in v]


def dist2(a, b):
    return sum((x - y) ** 2 for x, y in zip(a, b))


def in_front(rng):
    return [rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(2, 6)]


def p3p(rng):
    R, t = rotation(quaternion(rng)), [rng.gauss(0, 1) for _ in range(3)]
    xc = [in_front(rng) for _ in range(3)]
    X = [tmul(R, sub(p, t)) for p in xc]
    ours = [v for p in xc for v in (p[0] / p[2], p[1] / p[2])]
    ours += [dist2(xc[0], xc[1]), dist2(xc[0], xc[2]), dist2(xc[1], xc[2])]
    peer = [v for p in xc for v in unit(p)] + [v for p in X for v in p]
    return ours, peer, [p[2] for p in xc]


def gp3p(rng):
    R, t = rotation(quaternion(rng)), [rng.gauss(0, 1) for _ in range(3)]
    xc = [in_front(rng) for _ in range(3)]
    origins = [[rng.uniform(-1, 1) for _ in range(3)] for _ in range(3)]
    rays = [unit(sub(p, o)) for p, o in zip(xc, origins)]
    X = [tmul(R, sub(p, t)) for p in xc]
    ours = [v for o in origins for v in o] + [v for r in rays for v in r]
    ours += [dist2(xc[0], xc[1]), dist2(xc[0], xc[2]), dist2(xc[1], xc[2])]
    peer = [v for o in origins for v in o] + [v for r in rays for v in r] + [v for p in X for v in p]
    return ours, peer, [math.sqrt(dist2(p, o)) for p, o in zip(xc, origins)]


def up2p_elim(rng):
    angle = rng.uniform(-math.pi, math.pi)
    R, t = upright(angle), [rng.gauss(0, 1) for _ in range(3)]
    xc = [in_front(rng) for _ in range(2)]
    X = [tmul(R, sub(p, t)) for p in xc]
    ours = [v for p in X for v in p] + [v for p in xc for v in (p[0] / p[2], p[1] / p[2])]
    peer = [v for p in xc for v in unit(p)] + [v for p in X for v in p]
    return ours, peer, [math.cos(angle), math.sin(angle)] + t


def relpose_upright_3pt_elim(rng):
    while True:
        angle = rng.uniform(-math.pi, math.pi)
        R, t = upright(angle), [rng.gauss(0, 0.5) for _ in range(3)]
        x1 = [in_front(rng) for _ in range(3)]
        x2 = [add(mul(R, p), t) for p in x1]
        if all(p[2] > 0.5 for p in x2):
            break
    ours = [v for p in x1 + x2 for v in (p[0] / p[2], p[1] / p[2])]
    peer = [v for p in x1 + x2 for v in unit(p)]
    return ours, peer, [math.cos(angle), math.sin(angle)] + unit(t)


def relpose_upright_3pt_tan(rng):
    # The scene of relpose_upright_3pt_elim; the yaw as q = tan(angle / 2).
    ours, peer, (c, s, *t) = relpose_upright_3pt_elim(rng)
    return ours, peer, [s / (1 + c)] + t


def p3ll(rng):
    q = quaternion(rng)
    if q[0] < 0:
        q = [-x for x in q]
    R, t = rotation(q), [rng.gauss(0, 1) for _ in range(3)]
    X = [tmul(R, sub(in_front(rng), t)) for _ in range(3)]
    V = [unit([rng.gauss(0, 1) for _ in range(3)]) for _ in range(3)]
    lines = [unit(cross(add(mul(R, x), t), mul(R, v))) for x, v in zip(X, V)]
    b, c, d = q[1] / q[0], q[2] / q[0], q[3] / q[0]
    ours = [v for l in lines for v in l] + [v for w in V for v in w]
    peer = [v for l in lines for v in l] + [v for x in X for v in x] + [v for w in V for v in w]
    return ours, peer, [b, c, d]


def solve_linear(a, b):
    """x with a x = b (square, Gaussian elimination with partial pivoting)."""
    n = len(a)
    m = [row[:] + [bi] for row, bi in zip(a, b)]
    for k in range(n):
        p = max(range(k, n), key=lambda i: abs(m[i][k]))
        m[k], m[p] = m[p], m[k]
        for i in range(k + 1, n):
            f = m[i][k] / m[k][k]
            m[i] = [x - f * y for x, y in zip(m[i], m[k])]
    x = [0.0] * n
    for k in reversed(range(n)):
        x[k] = (m[k][n] - sum(m[k][j] * x[j] for j in range(k + 1, n))) / m[k][k]
    return x


def null_space(rows, n):
    """A basis of the null space of `rows` (each of length n): reduced row echelon form
    with partial pivoting, one vector per free column (that entry 1, the other free 0)."""
    m = [r[:] for r in rows]
    pivots, r = [], 0
    for c in range(n):
        if r == len(m):
            break
        p = max(range(r, len(m)), key=lambda i: abs(m[i][c]))
        if abs(m[p][c]) < 1e-12:
            continue
        m[r], m[p] = m[p], m[r]
        m[r] = [x / m[r][c] for x in m[r]]
        for i in range(len(m)):
            if i != r:
                f = m[i][c]
                m[i] = [x - f * y for x, y in zip(m[i], m[r])]
        pivots.append(c)
        r += 1
    basis = []
    for free in (c for c in range(n) if c not in pivots):
        v = [0.0] * n
        v[free] = 1.0
        for i, c in enumerate(pivots):
            v[c] = -m[i][free]
        basis.append(v)
    return basis


def orthonormal_mix(rng, vectors):
    """An orthonormal basis of the span of `vectors` in a random orientation (as an SVD
    gives one; an echelon basis has exact zeros and can be far from orthogonal)."""
    k, basis = len(vectors), []
    for _ in range(k):
        mix = [rng.gauss(0, 1) for _ in range(k)]
        v = [sum(m * u[e] for m, u in zip(mix, vectors)) for e in range(len(vectors[0]))]
        for u in basis:
            dot = sum(x * y for x, y in zip(u, v))
            v = [x - dot * y for x, y in zip(v, u)]
        basis.append(unit(v))
    return basis


def relpose_6pt_focal(rng):
    # Both cameras K = diag(f, f, 1); the second at R, t with R near the first.
    while True:
        f = rng.uniform(0.5, 2.0)
        q = unit([1.0] + [rng.gauss(0, 0.2) for _ in range(3)])
        R, t = rotation(q), [rng.gauss(0, 0.5) for _ in range(3)]
        pts = [in_front(rng) for _ in range(6)]
        cam2 = [add(mul(R, p), t) for p in pts]
        if all(p[2] > 0.5 for p in cam2):
            break
    x1 = [[f * p[0] / p[2], f * p[1] / p[2], 1.0] for p in pts]
    x2 = [[f * p[0] / p[2], f * p[1] / p[2], 1.0] for p in cam2]
    # F1, F2, F3 span the null space of the epipolar constraints x2' F x1 = 0 (F row-major).
    rows = [[b[i] * a[j] for i in range(3) for j in range(3)] for a, b in zip(x1, x2)]
    basis = orthonormal_mix(rng, null_space(rows, 9))
    # The truth F = K^-T [t]x R K^-1 in that basis: lambda F - x F1 - y F2 = F3.
    tx = [[0.0, -t[2], t[1]], [t[2], 0.0, -t[0]], [-t[1], t[0], 0.0]]
    E = [[sum(tx[i][k] * R[k][j] for k in range(3)) for j in range(3)] for i in range(3)]
    kinv = [1 / f, 1 / f, 1.0]
    F = [E[i][j] * kinv[i] * kinv[j] for i in range(3) for j in range(3)]
    cols = [F, [-v for v in basis[0]], [-v for v in basis[1]]]
    ata = [[sum(a * b for a, b in zip(ci, cj)) for cj in cols] for ci in cols]
    atb = [sum(a * b for a, b in zip(ci, basis[2])) for ci in cols]
    _, x, y = solve_linear(ata, atb)
    ours = basis[0] + basis[1] + basis[2]
    peer = [v for p in x1 + x2 for v in p] + ours
    return ours, peer, [x, y, 1 / (f * f)]


def p2p2pl_scene(rng):
    # Two points seen at x_i; two lines, each through a point seen at y_j, given by another
    # point P_j on it (mu_j along V_j away from the seen one) and its unit direction V_j.
    q = quaternion(rng)
    R, t = rotation(q), [rng.gauss(0, 1) for _ in range(3)]
    xc = [in_front(rng) for _ in range(2)]
    yc = [in_front(rng) for _ in range(2)]
    X = [tmul(R, sub(p, t)) for p in xc]
    V = [unit([rng.gauss(0, 1) for _ in range(3)]) for _ in range(2)]
    mu = [rng.gauss(0, 1) for _ in range(2)]
    P = [sub(tmul(R, sub(p, t)), [m * x for x in v]) for p, v, m in zip(yc, V, mu)]
    peer = [v for p in xc for v in unit(p)] + [v for p in X for v in p]
    peer += [v for p in yc for v in unit(p)] + [v for p in P for v in p] + [v for w in V for v in w]
    return q, R, xc, yc, X, V, P, peer


def p2p2pl(rng):
    q, _, xc, yc, X, V, P, peer = p2p2pl_scene(rng)
    b, c, d = q[1] / q[0], q[2] / q[0], q[3] / q[0]
    s = 1 + b * b + c * c + d * d
    ours = [v for p in xc for v in (p[0] / p[2], p[1] / p[2])] + [v for p in X for v in p]
    ours += [v for p in yc for v in (p[0] / p[2], p[1] / p[2])] + [v for p in P for v in p]
    ours += [v for w in V for v in w]
    return ours, peer, [b, c, d, s * xc[0][2]]


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def transpose(a):
    return [[a[j][i] for j in range(3)] for i in range(3)]


def rotation_between(a, b):
    """The rotation about a x b taking the unit vector a to the unit vector b."""
    v, c = cross(a, b), sum(x * y for x, y in zip(a, b))
    k = [[0.0, -v[2], v[1]], [v[2], 0.0, -v[0]], [-v[1], v[0], 0.0]]
    k2 = matmul(k, k)
    return [[(i == j) + k[i][j] + k2[i][j] / (1 + c) for j in range(3)] for i in range(3)]


def quaternion_of(r):
    """(w, x, y, z) of the rotation matrix r (w >= 0 branch; r is far from a half-turn)."""
    w = math.sqrt(max(0.0, 1 + r[0][0] + r[1][1] + r[2][2])) / 2
    return [w, (r[2][1] - r[1][2]) / (4 * w), (r[0][2] - r[2][0]) / (4 * w), (r[1][0] - r[0][1]) / (4 * w)]


def p2p2pl_canonical(rng):
    # The scene of p2p2pl in PoseLib's canonical frames (templates/classic/p2p2pl_canonical.mp):
    # world point 0 at the origin and point 1 at (1, 0, 0) (translation, scale s0, rotation
    # r0); bearing 0 along z and bearing 1 in the x-z plane (rotation rc). The truth: (b, c)
    # of the rotation rc R r0' between the frames, quaternion (1, b, c, -b c). A peer line
    # also holds rc and r0 (row-major) to express PoseLib's poses in our unknowns.
    _, R, xc, yc, X, V, P, peer = p2p2pl_scene(rng)
    d1 = sub(X[1], X[0])
    s0 = math.sqrt(sum(x * x for x in d1))
    r0 = rotation_between(unit(d1), [1.0, 0.0, 0.0])
    r1 = rotation_between(unit(xc[0]), [0.0, 0.0, 1.0])
    y1 = mul(r1, unit(xc[1]))
    a = unit([y1[0], y1[1]])
    rc = matmul([[a[0], a[1], 0.0], [-a[1], a[0], 0.0], [0.0, 0.0, 1.0]], r1)
    y1 = mul(rc, xc[1])
    ours = [y1[2] / y1[0]] + [v for p in yc for v in mul(rc, p)]
    ours += [v for p in P for v in mul(r0, [x / s0 for x in sub(p, X[0])])]
    ours += [v for w in V for v in mul(r0, w)]
    q = quaternion_of(matmul(matmul(rc, R), transpose(r0)))
    peer += [v for row in rc for v in row] + [v for row in r0 for v in row]
    return ours, peer, [q[1] / q[0], q[2] / q[0]]


def p35pf_scene(rng):
    f = rng.uniform(0.5, 2.0)
    q = quaternion(rng)
    R, t = rotation(q), [rng.gauss(0, 1) for _ in range(3)]
    xc = [in_front(rng) for _ in range(4)]
    X = [tmul(R, sub(p, t)) for p in xc]
    return f, q, R, t, xc, X


def p35pf(rng):
    f, q, R, t, xc, X = p35pf_scene(rng)
    b, c, d = q[1] / q[0], q[2] / q[0], q[3] / q[0]
    s = 1 + b * b + c * c + d * d
    ours = [v for p in xc for v in (f * p[0] / p[2], f * p[1] / p[2])] + [v for p in X for v in p]
    return ours, ours, [b, c, d, s * xc[0][2] / f, f]


def p35pf_nullspace(rng):
    # The scene of p35pf; our data the null space of the camera P's seven linear equations
    # (u_i P_3 X_i = P_1 X_i and v_i P_3 X_i = P_2 X_i, all but v_3) with P's entries column
    # by column, as an orthonormal basis N (12 x 5, row-major); the truth x = v[0..4] / v[4]
    # for the coordinates v of P = diag(f, f, 1) [R | t] in it.
    f, _, R, t, xc, X = p35pf_scene(rng)
    uv = [(f * p[0] / p[2], f * p[1] / p[2]) for p in xc]
    rows = []
    for i in range(4):
        h = X[i] + [1.0]
        for axis in (0, 1):
            if (i, axis) == (3, 1):
                continue
            row = [0.0] * 12
            for c in range(4):
                row[3 * c + axis] = -h[c]
                row[3 * c + 2] = uv[i][axis] * h[c]
            rows.append(row)
    basis = orthonormal_mix(rng, null_space(rows, 12))
    k = [f, f, 1.0]
    P = [k[e % 3] * (R[e % 3][e // 3] if e < 9 else t[e % 3]) for e in range(12)]
    v = [sum(x * y for x, y in zip(b, P)) for b in basis]
    ours = [basis[j][e] for e in range(12) for j in range(5)]
    peer = [c for p in uv for c in p] + [c for p in X for c in p] + ours
    return ours, peer, [v[j] / v[4] for j in range(4)]


PROBLEMS = {f.__name__: f for f in (p3p, gp3p, up2p_elim, relpose_upright_3pt_elim,
                                    relpose_upright_3pt_tan, p3ll,
                                    relpose_6pt_focal, p2p2pl, p2p2pl_canonical, p35pf,
                                    p35pf_nullspace)}


def main():
    if len(sys.argv) != 7 or sys.argv[1] not in PROBLEMS:
        sys.exit(__doc__)
    make = PROBLEMS[sys.argv[1]]
    count, rng = int(sys.argv[2]), random.Random(int(sys.argv[3]))
    with open(sys.argv[4], "w") as ours, open(sys.argv[5], "w") as peer, \
            open(sys.argv[6], "w") as solutions:
        for _ in range(count):
            o, p, s = make(rng)
            for f, row in ((ours, o), (peer, p), (solutions, s)):
                f.write(" ".join(repr(x) for x in row) + "\n")


if __name__ == "__main__":
    main()
