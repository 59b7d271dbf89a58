#!/usr/bin/env python3
"""Print the README's experiment tables (mean rotation / translation error, degrees) from
the summary CSVs of `rspose experiment`. Usage: python3 tools/readme_tables.py [RESULTS_DIR]
(default `results`). `solver/tests/results_fresh.rs` checks the README holds these rows."""
import csv
import sys

METHODS = ["gsrp", "nrsrp", "grsrp", "grsrp+", "rectified", "rectified+v", "grsrp-gravity"]
HEADERS = {
    "angular": "angular velocity (rad/s)",
    "angular-linear": "level (0.5 rad/s + 4 m/s each)",
    "gyro-noise": "gyro noise (rad/s), at 2.5 rad/s + 20 m/s",
    "pixel-noise": "pixel noise (px), at 2.5 rad/s + 20 m/s",
    "gravity-noise": "gravity noise (deg), at 2.5 rad/s, 50 % outliers",
}


def table(directory, sweep):
    rows = list(csv.DictReader(open(f"{directory}/{sweep}.csv")))
    levels = []
    for r in rows:
        if r["level"] not in levels:
            levels.append(r["level"])
    out = [f"| {HEADERS[sweep]} | " + " | ".join(METHODS) + " |", "|---" * (len(METHODS) + 1) + "|"]
    for level in levels:
        cells = []
        for m in METHODS:
            r = next(x for x in rows if x["level"] == level and x["method"] == m)
            cells.append(f"{float(r['rot_mean']):.2f} / {float(r['trans_mean']):.2f}")
        out.append(f"| {level} | " + " | ".join(cells) + " |")
    return "\n".join(out)


if __name__ == "__main__":
    directory = sys.argv[1] if len(sys.argv) > 1 else "results"
    print("\n\n".join(table(directory, s) for s in HEADERS))
