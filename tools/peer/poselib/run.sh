#!/usr/bin/env bash
# Same-data, same-work comparison of rspose with PoseLib, interleaved in rounds.
#
#   tools/peer/poselib/run.sh POSELIB_CHECKOUT [ROUNDS] [PAIRS]
#
# Builds PoseLib from the given checkout (CMake, Release, PoseLib's own flags; needs cmake
# and Eigen 3, e.g. Debian's cmake and libeigen3-dev) into POSELIB_CHECKOUT/_build, the
# driver (driver.cc, our code) against it, and `peer_bench` (solver/examples); writes the
# instances once (PAIRS estimator pairs, default 50; more give steadier accuracy figures),
# then alternates the two programs ROUNDS times (default 9), each pinned to
# one core, and prints every figure per round and the medians of the same-round ratios
# ours/PoseLib with each side's accuracy. Nothing of PoseLib is copied into this repository.
set -euo pipefail
poselib="$(cd "${1:?usage: $0 POSELIB_CHECKOUT [ROUNDS] [PAIRS]}" && pwd)"
rounds="${2:-9}"
pairs="${3:-50}"
here="$(cd "$(dirname "$0")" && pwd)"
repo="$(cd "$here/../../.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT

. "$here/build.sh"
build_against_poselib "$poselib" "$here/driver.cc" "$work/driver"
cargo build --release -q -p rspose --example peer_bench --manifest-path "$repo/Cargo.toml"
ours="$repo/target/release/examples/peer_bench"
"$ours" write "$work/data" "$pairs"

pin=""
command -v taskset >/dev/null && pin="taskset -c 0"
: >"$work/log"
for r in $(seq "$rounds"); do
  $pin "$work/driver" "$work/data" 3 | sed "s/^/$r /" >>"$work/log"
  $pin "$ours" time "$work/data" 3 | sed "s/^/$r /" >>"$work/log"
done
cat "$work/log"
python3 - "$work/log" <<'PY'
import sys, statistics, collections
v = collections.defaultdict(dict)
acc = {}
for line in open(sys.argv[1]):
    f = line.split()
    r, who, key = f[0], f[1], f[2]
    if key.endswith("_us"):
        v[key][(r, who)] = float(f[3])
    else:
        acc[who] = " ".join(f[3:])
print()
print("median of same-round ratios ours / PoseLib:")
for key in v:
    rounds = {r for r, _ in v[key]}
    ratios = [v[key][(r, "ours")] / v[key][(r, "poselib")] for r in sorted(rounds)]
    print(f"  {key:36s} {statistics.median(ratios):.3f}  (ours {statistics.median(v[key][(r, 'ours')] for r in rounds):.2f} us, "
          f"PoseLib {statistics.median(v[key][(r, 'poselib')] for r in rounds):.2f} us)")
for who, a in acc.items():
    print(f"  accuracy {who}: {a}")
PY
