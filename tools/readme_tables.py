#!/usr/bin/env python3
"""Print the experiment tables of docs/EXPERIMENTS.md (mean rotation / translation error,
degrees) from the summary CSVs of `rspose experiment`. Usage: python3 tools/readme_tables.py
[RESULTS_DIR] (default `results`; `results` gives the paper preset's tables,
`results/default` the library defaults'); paste the output into docs/EXPERIMENTS.md after
re-running a sweep. `solver/tests/results_fresh.rs` checks docs/EXPERIMENTS.md holds these
rows. `python3 tools/readme_tables.py --gravity` prints docs/EXPERIMENTS.md's
`grsrp-gravity` against `grsrp+` table from `results/default` and `results` (mean errors
and median times of the same runs)."""
import csv
import sys

HEADERS = {
    "angular": "angular velocity (rad/s)",
    "angular-linear": "level (0.5 rad/s + 4 m/s each)",
    "gyro-noise": "gyro noise (rad/s), at 2.5 rad/s + 20 m/s",
    "pixel-noise": "pixel noise (px), at 2.5 rad/s + 20 m/s",
    "gravity-noise": "gravity noise (deg), at 2.5 rad/s, 50 % outliers",
    "readout-error": "nominal / true readout time, at 2.5 rad/s",
}


def table(directory, sweep):
    rows = list(csv.DictReader(open(f"{directory}/{sweep}.csv")))
    # Levels and methods (every method, then variants such as `rectified+k`) in file order.
    levels, methods = [], []
    for r in rows:
        if r["level"] not in levels:
            levels.append(r["level"])
        if r["method"] not in methods:
            methods.append(r["method"])
    out = [f"| {HEADERS[sweep]} | " + " | ".join(methods) + " |", "|---" * (len(methods) + 1) + "|"]
    for level in levels:
        cells = []
        for m in methods:
            r = next(x for x in rows if x["level"] == level and x["method"] == m)
            cells.append(f"{float(r['rot_mean']):.2f} / {float(r['trans_mean']):.2f}")
        out.append(f"| {level} | " + " | ".join(cells) + " |")
    return "\n".join(out)


def gravity_comparison(default="results/default", paper="results"):
    def rows(directory):
        return {(r["level"], r["method"]): r for r in csv.DictReader(open(f"{directory}/gravity-noise.csv"))}

    d, p = rows(default), rows(paper)
    levels = []
    for level, _ in d:
        if level not in levels:
            levels.append(level)

    def cell(r):
        ms = 1000 * float(r["seconds_median"])
        return f"{float(r['rot_mean']):.2f} / {float(r['trans_mean']):.2f}, {ms:.1f} ms"

    def ratio(rs, key):
        return float(rs[(key, "grsrp-gravity")]["seconds_median"]) / float(rs[(key, "grsrp+")]["seconds_median"])

    out = [
        "| gravity noise | `grsrp+` default | `grsrp-gravity` default | time ratio | `grsrp+` paper | `grsrp-gravity` paper | time ratio |",
        "|---|---|---|---|---|---|---|",
    ]
    for level in levels:
        out.append(
            f"| {level}° | {cell(d[(level, 'grsrp+')])} | {cell(d[(level, 'grsrp-gravity')])} | {ratio(d, level):.2f} "
            f"| {cell(p[(level, 'grsrp+')])} | {cell(p[(level, 'grsrp-gravity')])} | {ratio(p, level):.2f} |"
        )
    return "\n".join(out)


if __name__ == "__main__":
    if sys.argv[1:] == ["--gravity"]:
        print(gravity_comparison())
    else:
        directory = sys.argv[1] if len(sys.argv) > 1 else "results"
        print("\n\n".join(table(directory, s) for s in HEADERS))
