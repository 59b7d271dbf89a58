#!/usr/bin/env bash
# Emits one problem's solver with `mingen generate --out`, compiles it in a crate of its own
# that depends on mingen-runtime alone (as a user's crate would), and runs it on instances
# from a file: compile time, per-call time, solutions per instance and, given planted
# solutions, their recovery.
#
#   tools/emitted_solver/run.sh PROBLEM.mp INSTANCES [SOLUTIONS [SIGN_FREE]] [-- GENERATE_ARGS...]
#
# INSTANCES / SOLUTIONS: one instance (data slots) / planted solution (every unknown) per
# line, as `mingen audit --instances-from/--solutions-from` read them; INSTANCES may be
# `random:N` (N instances with every slot uniform in [-1, 1]). SIGN_FREE: comma-
# separated unknown indices whose joint sign is free (an eliminated unit translation).
# Arguments after `--` go to `mingen generate` (e.g. --code-form inline).
# PROFILE=dev builds the solver's crate in the dev (debug) profile instead of release, as
# a user's `cargo build` does: emitted code must build in any profile. EDITION (default
# 2024) is the crate's edition: it must build in any. BUILD_ONLY=1 stops
# after the build (INSTANCES is then not read). MINGEN=PATH uses that mingen binary instead
# of building the workspace's (CI passes the one its test build made). The crates share one
# target directory, target/emitted-solver/target (or CARGO_TARGET_DIR), so mingen-runtime
# and its dependencies are built once per profile, not once per problem; the driver is
# TARGET_DIR/{release,debug}/emitted-solver-NAME.
# Example (G-RSRP with unknown readout, 100 solutions):
#   python3 tools/grsrp_readout_instances.py 200 2 --solutions /tmp/s.txt > /tmp/i.txt
#   tools/emitted_solver/run.sh templates/large/grsrp_readout.mp /tmp/i.txt /tmp/s.txt 3,4,5
set -euo pipefail
root=$(cd "$(dirname "$0")/../.." && pwd)
args=()
while [[ $# -gt 0 && $1 != -- ]]; do args+=("$1"); shift; done
[[ ${1:-} == -- ]] && shift
if [[ ${#args[@]} -lt 2 ]]; then
    sed -n 2,24p "$0" >&2
    exit 2
fi
profile=${PROFILE:-release}
case $profile in
    release) flag=(--release); dir=release ;;
    dev) flag=(); dir=debug ;;
    *) echo "PROFILE must be release or dev, not '$profile'" >&2; exit 2 ;;
esac
problem=${args[0]}
name=$(basename "$problem" .mp)
work="$root/target/emitted-solver/$name"
crates_target="${CARGO_TARGET_DIR:-$root/target/emitted-solver/target}"
mkdir -p "$work/src"
mingen=${MINGEN:-}
if [[ -z $mingen ]]; then
    cargo build --release -q -p mingen --manifest-path "$root/Cargo.toml"
    mingen="${CARGO_TARGET_DIR:-$root/target}/release/mingen"
fi
"$mingen" generate "$problem" --out "$work/src/solver.rs" "$@"
cp "$root/tools/emitted_solver/main.rs" "$work/src/main.rs"
cat > "$work/Cargo.toml" <<TOML
[package]
name = "emitted-solver-$name"
version = "0.0.0"
edition = "${EDITION:-2024}"
publish = false

[dependencies]
mingen-runtime = { path = "$root/generator/runtime" }

[workspace]
TOML
# The workspace's lock file: the same dependency versions as the workspace, so that a
# shared CARGO_TARGET_DIR reuses their builds (cargo drops the entries it does not need).
[[ -f "$root/Cargo.lock" ]] && cp "$root/Cargo.lock" "$work/Cargo.lock"
# Dependencies first, so that the figure below is the solver's own compile time.
cargo build "${flag[@]}" -q --manifest-path "$work/Cargo.toml" --target-dir "$crates_target" -p mingen-runtime
touch "$work/src/main.rs"
start=$(date +%s%N)
if ! log=$(cargo build "${flag[@]}" -q --manifest-path "$work/Cargo.toml" --target-dir "$crates_target" 2>&1); then
    echo "$log" >&2
    exit 1
fi
end=$(date +%s%N)
lines=$(wc -l < "$work/src/solver.rs")
ms=$(( (end - start) / 1000000 ))
printf '%s: %d lines emitted, compiled in %d.%d s (%s)\n' "$name" "$lines" $((ms / 1000)) $((ms % 1000 / 100)) "$profile"
[[ ${BUILD_ONLY:-0} == 1 ]] && exit 0
"$crates_target/$dir/emitted-solver-$name" "${args[@]:1}"
