#!/usr/bin/env python3
"""Records the template benchmark: runs `mingen report` on every file of
templates/benchmark (--jobs at a time), writes each file's `# recorded: RxC` header line
(`RxC + NxM reduction` when the solver row-reduces its equations first: the elimination
area the regression test generator/tests/benchmark_sizes.rs holds the search to; a file
without a template gets no line) and the Markdown table of docs/BENCHMARK.md between its
markers.

    python3 tools/benchmark_record.py [--instances N] [--jobs J] [--check] [--only NAME ...]

--check writes nothing and exits 1 if a recorded line would change (every problem is
planned, also those the test skips for their planning time). Each problem's report row is
kept in target/benchmark_rows/NAME.json; --only NAME ... plans just those problems (e.g.
one whose wall-clock budget ran out on a busy machine) and takes the others' rows from
there, so the table stays whole; --table-only plans nothing and writes the table from those
rows. Run from anywhere; builds mingen in release first.

--redundant-basis plans every problem with `--redundant-basis yes` instead (templates whose
basis may have more monomials than solutions, Martyushev et al.'s redundant solving bases;
off by default in mingen): it writes `# recorded redundant: RxC` lines, the table between
docs/BENCHMARK.md's redundant-table markers, and keeps its rows in
target/benchmark_rows_redundant/.
"""
import argparse
import concurrent.futures
import json
import pathlib
import re
import subprocess
import sys

ROOT = pathlib.Path(__file__).resolve().parent.parent
BENCH = ROOT / "templates" / "benchmark"
DOC = ROOT / "docs" / "BENCHMARK.md"
ROWS = ROOT / "target" / "benchmark_rows"
BEGIN, END = "<!-- benchmark table: begin -->", "<!-- benchmark table: end -->"
# The same for `--redundant-basis`.
REDUNDANT_ROWS = ROOT / "target" / "benchmark_rows_redundant"
REDUNDANT_BEGIN = "<!-- redundant benchmark table: begin -->"
REDUNDANT_END = "<!-- redundant benchmark table: end -->"


def mingen(*args):
    exe = ROOT / "target" / "release" / "mingen"
    out = subprocess.run([str(exe), *args], capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"mingen {' '.join(args)} failed:\n{out.stderr}")
    return out.stdout


def size_text(r):
    """The recorded size of a report row: `RxC`, `RxC + NxM reduction`, or None."""
    t = r["template"]
    if not t:
        return None
    red = r.get("equation_reduction")
    extra = f" + {red['rows']}x{red['cols']} reduction" if red else ""
    return f"{t['rows']}x{t['cols']}{extra}"


def markdown(rows):
    """The table of `mingen report --markdown` (the same columns), from its JSON rows."""
    def ratio(x):
        return "—" if x is None else f"{x:.2f}"
    head = ["problem", "unknowns", "solutions", "template", "published", "area / std",
            "whole / std whole",
            "area / best", "audit: median / p99 log10 residual / failures",
            "other polishing", "seconds"]
    out = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    def audit(a, figures):
        if a is None or figures is None:
            return "—"
        text = (f"{figures['median_log10_residual']:.2f} / {figures['p99_log10_residual']:.2f}"
                f" / {figures['failures']} of {a['instances']}")
        if "newton_steps" in figures:
            steps = figures["newton_steps"]
            text += " (unpolished)" if steps == 0 else f" (newton {steps})"
        return text
    for r in rows:
        a = r["audit"]
        unknowns = ", ".join(r["unknowns"])
        if r["eliminated"]:
            unknowns += f" ({', '.join(r['eliminated'])} eliminated)"
        cells = [
            f"`{r['problem']}`", unknowns or "—",
            "—" if r["solutions"] is None else str(r["solutions"]),
            (size_text(r) or "none")
            + (f" ({r['folded_rows']} rows folded)" if r.get("folded_rows") else ""),
            r["published"] or "—", ratio(r["area_over_std"]),
            ratio(r["whole_area_over_std_whole"]), ratio(r["area_over_best"]),
            audit(a, a), audit(a, a and a.get("other_polishing")),
            f"{r['seconds']:.2f}",
        ]
        out.append("| " + " | ".join(c.replace("|", "\\|") for c in cells) + " |")
    out.append("")
    for r in rows:
        if r["error"]:
            # Paths relative to the repository, so that the table is the same on every machine.
            error = re.sub(r"\S*/(templates/benchmark/)", r"\1", r["error"])
            out.append(f"`{r['problem']}`: {error}")
            out.append("")
    return "\n".join(out) + "\n"


def with_recorded(text, size, seconds, key="recorded"):
    """`text` with its `# KEY: ...` line for `size` (none when `size` is None), after the
    `# published:` line and the `# recorded:` line."""
    lines = [l for l in text.splitlines() if not l.startswith(f"# {key}:")]
    if size is not None:
        at = next((i + 1 for i, l in enumerate(lines) if l.startswith("# published:")), 0)
        if key != "recorded":
            at = next((i + 1 for i, l in enumerate(lines) if l.startswith("# recorded:")), at)
        # The seconds are rounded up to a coarse step so that re-recording on a machine
        # of another speed rarely changes the line.
        step = next(s for s in (1, 5, 20, 60, 300, 10**9) if seconds <= s)
        tool = "tools/benchmark_record.py" + (" --redundant-basis" if key != "recorded" else "")
        lines.insert(at, f"# {key}: {size}, planned within {step} s (mingen; {tool})")
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--instances", type=int, default=1000)
    ap.add_argument("--check", action="store_true")
    ap.add_argument("--max-seconds", type=float, default=None,
                    help="planning budget per problem (default: mingen's)")
    ap.add_argument("--jobs", type=int, default=2, help="problems planned at a time")
    ap.add_argument("--table-only", action="store_true",
                    help="plan nothing: the table from the last run's rows, recorded lines as they are")
    ap.add_argument("--only", nargs="+", metavar="NAME",
                    help="plan only these problems (file stems); the other rows come from "
                         "the last run's target/benchmark_rows/")
    ap.add_argument("--redundant-basis", action="store_true",
                    help="plan with --redundant-basis yes: `# recorded redundant:` lines and "
                         "the redundant table")
    a = ap.parse_args()
    rows_dir, begin, end, key = (
        (REDUNDANT_ROWS, REDUNDANT_BEGIN, REDUNDANT_END, "recorded redundant")
        if a.redundant_basis else (ROWS, BEGIN, END, "recorded"))
    subprocess.run(["cargo", "build", "--release", "-q", "-p", "mingen"], cwd=ROOT, check=True)
    extra = ["--max-seconds", str(a.max_seconds)] if a.max_seconds else []
    if a.redundant_basis:
        extra += ["--redundant-basis", "yes"]
    files = sorted(BENCH.glob("*.mp"))

    if a.only:
        unknown = sorted(set(a.only) - {f.stem for f in files})
        if unknown:
            sys.exit("no such benchmark problem: " + ", ".join(unknown))
    rows_dir.mkdir(parents=True, exist_ok=True)

    def one(f):
        cached = rows_dir / f"{f.stem}.json"
        if a.table_only or (a.only and f.stem not in a.only):
            if not cached.exists():
                sys.exit(f"{cached} missing: run without --only first")
            return json.loads(cached.read_text())
        rs = json.loads(mingen("report", str(f), "--json", "--instances", str(a.instances), *extra))
        cached.write_text(json.dumps(rs))
        return rs

    with concurrent.futures.ThreadPoolExecutor(max_workers=max(1, a.jobs)) as pool:
        rows = [row for rs in pool.map(one, files) for row in rs]
    table = markdown(rows)
    stale = []
    for r in rows:
        # Rows cached by a run in another checkout name their files there.
        f = BENCH / pathlib.Path(r["file"]).name
        size = size_text(r)
        old = f.read_text()
        new = with_recorded(old, size, r["seconds"], key)
        if new != old:
            stale.append(f.name)
            if not a.check:
                f.write_text(new)
    doc = DOC.read_text()
    m = re.search(re.escape(begin) + r"\n(.*?)" + re.escape(end), doc, re.S)
    if m is None:
        sys.exit(f"{DOC}: markers {begin} / {end} missing")
    new_doc = doc[: m.start(1)] + table + doc[m.end(1) :]
    if a.check:
        if stale:
            sys.exit("recorded sizes differ: " + ", ".join(stale))
        return
    DOC.write_text(new_doc)
    print(f"{len(rows)} problems; recorded sizes updated in {len(stale)} files; {DOC} written")


if __name__ == "__main__":
    main()
