#!/usr/bin/env bash
# Rebuilds the real-data pair files of solver/tests/data/cc9pro from the recording:
# SIFT matches (tools/match_frames.py, OpenCV) then `rspose make-pair` (gyro log, frame
# times, rig calibration). Usage:
#   tools/make_cc9pro_pairs.sh RECORDING_DIR [OUT_DIR] [PAIRS_FILE]
# RECORDING_DIR holds frames/, gyro.txt and framestamp.txt (e.g. shared/realdata/cc9pro).
# Needs python3 with the packages in tools/requirements.txt.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
rec="${1:?usage: $0 RECORDING_DIR [OUT_DIR] [PAIRS_FILE]}"
out="${2:-$here/solver/tests/data/cc9pro}"
pairs="${3:-$here/solver/tests/data/cc9pro/pairs.txt}"
calibration="$here/solver/tests/data/cc9pro/calibration.json"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
python3 "$here/tools/match_frames.py" --frames-dir "$rec/frames" --pairs-file "$pairs" --out-dir "$work"
cargo build --release -q -p rspose --manifest-path "$here/Cargo.toml"
mkdir -p "$out"
for m in "$work"/matches-*.json; do
  name="$(basename "$m" .json)"
  "$here/target/release/rspose" make-pair --calibration "$calibration" \
    --gyro "$rec/gyro.txt" --frame-times "$rec/framestamp.txt" \
    --matches "$m" -o "$out/pair-${name#matches-}.json"
done
