#!/usr/bin/env bash
# The small classic problems: our emitted solvers (templates/classic/PROBLEM.mp) against
# PoseLib's hand-written ones on the same planted geometric instances, interleaved in
# rounds.
#
#   tools/peer/poselib/small_solvers.sh POSELIB_CHECKOUT [ROUNDS] [INSTANCES] [PROBLEM...]
#
# Builds PoseLib as run.sh does and the driver small_solvers.cc (our code) against it; per
# problem (default: p3p gp3p up2p_elim relpose_upright_3pt_elim relpose_upright_3pt_tan p3ll relpose_6pt_focal
# p2p2pl p2p2pl_canonical p35pf p35pf_nullspace) writes INSTANCES instances (default 1000; small_instances.py, seed 7) in
# both forms, builds our solver in a crate of its own (tools/emitted_solver/run.sh, the
# plan's defaults; p2p2pl and p35pf plan for a minute or more and compile for minutes),
# alternates the two programs ROUNDS times (default 9), each pinned to one core, and
# prints a markdown table:
# per-call medians, the median of the same-round ratios ours / PoseLib, solutions returned
# per instance and planted solutions recovered (to 1e-6 relative) on each side. Work per
# call: PoseLib returns poses; ours what its problem file solves for (p3p and gp3p: the
# three depths; p3ll: the rotation; the upright problems: rotation and translation;
# relpose_6pt_focal: the fundamental matrix in the null-space basis of its six epipolar
# constraints, given as data, and the focal length; PoseLib computes that basis within
# its call, our time does not include it; p2p2pl: the rotation and the scaled depth of
# the first point, which fixes the translation, PoseLib the pose; p35pf: the rotation,
# the scaled depth of the first point and the focal length, PoseLib the pose and the
# focal length, after scaling the image points by their mean norm, which ours does not
# do; both return the positive focal length only, ours by its file's `positive f`;
# p35pf_nullspace: the camera's coordinates in the null-space basis of its seven linear
# equations, given as data, which PoseLib computes within its call and our time does not
# include; p2p2pl_canonical: the rotation's (b, c) in PoseLib's canonical frames from the
# data moved to them, which PoseLib does within its call and our time does not include).
set -euo pipefail
poselib="$(cd "${1:?usage: $0 POSELIB_CHECKOUT [ROUNDS] [INSTANCES] [PROBLEM...]}" && pwd)"
shift
rounds=${1:-9}
[[ $# -gt 0 ]] && shift
count=${1:-1000}
[[ $# -gt 0 ]] && shift
problems=("$@")
[[ ${#problems[@]} -eq 0 ]] && problems=(p3p gp3p up2p_elim relpose_upright_3pt_elim relpose_upright_3pt_tan p3ll relpose_6pt_focal
  p2p2pl p2p2pl_canonical p35pf p35pf_nullspace)
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../../.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

. "$here/build.sh"
build_against_poselib "$poselib" "$here/small_solvers.cc" "$work/poselib"
pin=""
command -v taskset >/dev/null && pin="taskset -c 0"
: >"$work/log"
for p in "${problems[@]}"; do
  python3 "$here/small_instances.py" "$p" "$count" 7 "$work/$p.ours" "$work/$p.peer" "$work/$p.sol"
  sign_free=()
  [[ $p == relpose_upright_3pt_elim ]] && sign_free=(2,3,4)
  [[ $p == relpose_upright_3pt_tan ]] && sign_free=(1,2,3)
  "$repo/tools/emitted_solver/run.sh" "$repo/templates/classic/$p.mp" "$work/$p.ours" \
    "$work/$p.sol" "${sign_free[@]}" >/dev/null
  ours="${CARGO_TARGET_DIR:-$repo/target/emitted-solver/target}/release/emitted-solver-$p"
  for r in $(seq "$rounds"); do
    $pin "$work/poselib" "$p" "$work/$p.peer" "$work/$p.sol" | sed "s/^/$p $r poselib /" >>"$work/log"
    $pin "$ours" "$work/$p.ours" "$work/$p.sol" "${sign_free[@]}" | sed "s/^/$p $r ours /" >>"$work/log"
  done
done
python3 - "$work/log" <<'PY'
import collections, re, statistics, sys
time = collections.defaultdict(dict)
sols, recovered, instances = {}, {}, "?"
for line in open(sys.argv[1]):
    f = line.split()
    p, r, who = f[0], f[1], f[2]
    if "per" in f and "call" in f:
        time[p][(r, who)] = float(f[f.index("us") - 1])
        sols[(p, who)] = float(f[f.index("real") - 1])
    elif line.split(None, 3)[3].startswith("planted"):
        m = re.search(r"(\d+) of (\d+)", line)
        recovered[(p, who)] = m.group(1)
        instances = m.group(2)
print("| problem | PoseLib µs | ours µs | ratio ours / PoseLib | solutions returned, PoseLib / ours | planted recovered (of instances), PoseLib / ours |")
print("|---|---|---|---|---|---|")
for p, t in time.items():
    rounds = sorted({r for r, _ in t})
    ratios = [t[(r, "ours")] / t[(r, "poselib")] for r in rounds if (r, "ours") in t and (r, "poselib") in t]
    med = lambda who: statistics.median(t[(r, who)] for r in rounds if (r, who) in t)
    print(f"| `{p}` | {med('poselib'):.3f} | {med('ours'):.3f} | {statistics.median(ratios):.2f} | "
          f"{sols[(p, 'poselib')]:.2f} / {sols[(p, 'ours')]:.2f} | "
          f"{recovered.get((p, 'poselib'), '?')} / {recovered.get((p, 'ours'), '?')} (of {instances}) |")
PY
