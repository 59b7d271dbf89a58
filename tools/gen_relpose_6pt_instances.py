# Planted instances of templates/large/gen_relpose_6pt.mp, one per line in the data-slot
# order of `mingen inspect` (p1[0..6], d1[0..6], p2[0..6], d2[0..6], x y z each), for
# `mingen audit --instances-from`, `tools/emitted_solver/run.sh` and the PoseLib peer
# driver (tools/peer/poselib/gen_relpose_6pt.sh).
#
# Geometry: a generalised camera of six ray origins p1 in [-1, 1]^3, 3D points X1 in front
# (x, y in [-2, 2], z in [4, 8]); a random rotation R (uniform) and translation t (each
# entry N(0, 1)); X2 = R X1 + t; the second camera's origins p2 in [-1, 1]^3. The
# directions are unit vectors d = (X - p) / |X - p|, so every point lies ahead along both
# rays (cheirality holds).
#
# Usage: python3 tools/gen_relpose_6pt_instances.py COUNT [SEED] [--solutions FILE] > DATA
# --solutions FILE writes the planted solution of each instance (q1 q2 q3 t1 t2 t3, q the
# Cayley vector of R: R is the rotation of the quaternion (1, q) / |(1, q)|).
import math, random, sys

args = sys.argv[1:]
solutions = None
if '--solutions' in args:
    i = args.index('--solutions')
    solutions = open(args[i + 1], 'w')
    del args[i:i + 2]
if not args:
    sys.exit(__doc__ or 'usage: gen_relpose_6pt_instances.py COUNT [SEED] [--solutions FILE]')
rng = random.Random(int(args[1]) if len(args) > 1 else 1)


def quaternion():
    while True:
        q = [rng.gauss(0, 1) for _ in range(4)]
        n = math.sqrt(sum(x * x for x in q))
        w, x, y, z = [c / n for c in q]
        if abs(w) > 0.05:  # the Cayley vector q = (x, y, z) / w stays finite
            return w, x, y, z


def rotation(w, x, y, z):
    return [[1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)],
            [2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)],
            [2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)]]


def unit(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v]


for _ in range(int(args[0])):
    w, x, y, z = quaternion()
    R = rotation(w, x, y, z)
    t = [rng.gauss(0, 1) for _ in range(3)]
    p1, d1, p2, d2 = [], [], [], []
    for _ in range(6):
        a = [rng.uniform(-1, 1) for _ in range(3)]
        X1 = [rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(4, 8)]
        X2 = [sum(R[i][k] * X1[k] for k in range(3)) + t[i] for i in range(3)]
        b = [rng.uniform(-1, 1) for _ in range(3)]
        p1.append(a)
        d1.append(unit([X1[i] - a[i] for i in range(3)]))
        p2.append(b)
        d2.append(unit([X2[i] - b[i] for i in range(3)]))
    print(' '.join(repr(c) for v in p1 + d1 + p2 + d2 for c in v))
    if solutions:
        solutions.write(' '.join(repr(c) for c in [x / w, y / w, z / w] + t) + '\n')
