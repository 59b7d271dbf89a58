#!/usr/bin/env python3
"""Check the claim of docs/EXPERIMENTS.md and docs/LIBRARY.md that the library defaults
are at least as accurate as the paper preset: for every level of the four paper sweeps
and the methods `rectified`, `grsrp`, `grsrp+`, the mean of the paired differences (same trial, default minus paper) of
the rotation and translation errors, with its 95 % confidence interval. A row is marked
WORSE when the whole interval is above zero (the default is worse beyond noise) and
BETTER when it is below.
Usage: python3 tools/compare_presets.py [DEFAULT_DIR] [PAPER_DIR]
(default `results/default` and `results`). Exit code 1 if any row is WORSE."""
import csv
import math
import statistics
import sys

SWEEPS = ["angular", "angular-linear", "gyro-noise", "pixel-noise"]
METHODS = ["rectified", "grsrp", "grsrp+"]


def trials(directory, sweep):
    out = {}
    for r in csv.DictReader(open(f"{directory}/{sweep}-trials.csv")):
        if r["rot_err"] and r["trans_err"]:
            out[(r["level"], r["trial"], r["method"])] = (float(r["rot_err"]), float(r["trans_err"]))
    return out


def main():
    default = sys.argv[1] if len(sys.argv) > 1 else "results/default"
    paper = sys.argv[2] if len(sys.argv) > 2 else "results"
    worse = better = cells_total = 0
    print("| sweep | level | method | rotation: default − paper (95 % CI) | translation: default − paper (95 % CI) |")
    print("|---|---|---|---|---|")
    for sweep in SWEEPS:
        d, p = trials(default, sweep), trials(paper, sweep)
        levels = []
        for level, _, _ in d:
            if level not in levels:
                levels.append(level)
        for level in levels:
            for m in METHODS:
                keys = [k for k in d if k[0] == level and k[2] == m and k in p]
                cells = []
                for axis in (0, 1):
                    diff = [d[k][axis] - p[k][axis] for k in keys]
                    mean = statistics.mean(diff)
                    half = 1.96 * statistics.stdev(diff) / math.sqrt(len(diff))
                    flag = " WORSE" if mean - half > 0 else " BETTER" if mean + half < 0 else ""
                    worse += flag == " WORSE"
                    better += flag == " BETTER"
                    cells_total += 1
                    cells.append(f"{mean:+.3f} ({mean - half:+.3f}, {mean + half:+.3f}){flag}")
                print(f"| {sweep} | {level} | {m} | {cells[0]} | {cells[1]} |")
    print(f"\nof {cells_total} cells, the default is worse beyond the interval in {worse}, better in {better}")
    return 1 if worse else 0


if __name__ == "__main__":
    sys.exit(main())
