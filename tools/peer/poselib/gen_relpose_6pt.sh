#!/usr/bin/env bash
# Generalised relative pose from 6 rays: our emitted solver of
# templates/large/gen_relpose_6pt.mp against PoseLib's gen_relpose_6pt on the same
# instances, interleaved in rounds.
#
#   tools/peer/poselib/gen_relpose_6pt.sh POSELIB_CHECKOUT [ROUNDS] [INSTANCES] [-- GENERATE_ARGS...]
#
# Builds PoseLib as run.sh does, the driver gen_relpose_6pt.cc (our code) against it, and
# our solver in a crate of its own (tools/emitted_solver/run.sh; arguments after `--` go
# to `mingen generate`, e.g. --newton 5); writes INSTANCES planted instances (default 500,
# tools/gen_relpose_6pt_instances.py), alternates the two programs ROUNDS times (default
# 5), each pinned to one core, and prints both sides' lines per round and the median of
# the same-round ratios of the per-call times. Work per call: PoseLib returns the poses
# that pass its cheirality check, refined by up to 5 Newton steps; ours every real
# solution, polished by the file's `option newton` steps.
set -euo pipefail
poselib="$(cd "${1:?usage: $0 POSELIB_CHECKOUT [ROUNDS] [INSTANCES] [-- GENERATE_ARGS...]}" && pwd)"
shift
rounds=5
count=500
[[ $# -gt 0 && $1 != -- ]] && { rounds=$1; shift; }
[[ $# -gt 0 && $1 != -- ]] && { count=$1; shift; }
[[ ${1:-} == -- ]] && shift
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../../.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

. "$here/build.sh"
build_against_poselib "$poselib" "$here/gen_relpose_6pt.cc" "$work/poselib"
python3 "$repo/tools/gen_relpose_6pt_instances.py" "$count" 3 --solutions "$work/solutions" \
  >"$work/instances"
"$repo/tools/emitted_solver/run.sh" "$repo/templates/large/gen_relpose_6pt.mp" \
  "$work/instances" "$work/solutions" -- "$@" >/dev/null
ours="${CARGO_TARGET_DIR:-$repo/target/emitted-solver/target}/release/emitted-solver-gen_relpose_6pt"

pin=""
command -v taskset >/dev/null && pin="taskset -c 0"
: >"$work/log"
for r in $(seq "$rounds"); do
  $pin "$work/poselib" "$work/instances" "$work/solutions" | sed "s/^/$r poselib /" >>"$work/log"
  $pin "$ours" "$work/instances" "$work/solutions" | sed "s/^/$r ours /" >>"$work/log"
done
cat "$work/log"
python3 - "$work/log" <<'PY'
import sys, statistics, collections
t = collections.defaultdict(dict)
for line in open(sys.argv[1]):
    f = line.split()
    if "per" in f and "call" in f:
        t[f[0]][f[1]] = float(f[f.index("us") - 1])
ratios = [v["ours"] / v["poselib"] for v in t.values() if len(v) == 2]
print(f"\nmedian of same-round ratios ours / PoseLib, per call: {statistics.median(ratios):.3f} "
      f"(ours {statistics.median(v['ours'] for v in t.values()):.0f} us, "
      f"PoseLib {statistics.median(v['poselib'] for v in t.values()):.0f} us)")
PY
