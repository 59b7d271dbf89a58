"""Shared fixtures: the repository, the committed real pairs and the command line.

The command-line binary and the library example are built from this checkout by
`cargo test --workspace --release --no-run` (the build of the README's test command: a
no-op when it has run, as in `.ci/run`), into the target directory named by
CARGO_TARGET_DIR or the repository's `target/`.
"""

from __future__ import annotations

import json
import os
import subprocess
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
CC9PRO = REPO / "solver" / "tests" / "data" / "cc9pro"


def target_dir() -> Path:
    return Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))


@pytest.fixture(scope="session")
def binaries() -> dict[str, Path]:
    """Paths of the `rspose` command line and the `library` example (release builds)."""
    build = subprocess.run(
        ["cargo", "test", "--workspace", "--release", "--no-run", "-q"],
        cwd=REPO,
        capture_output=True,
        text=True,
    )
    assert build.returncode == 0, build.stderr
    release = target_dir() / "release"
    return {"rspose": release / "rspose", "library": release / "examples" / "library"}


@pytest.fixture(scope="session")
def cli(binaries):
    """Runs `rspose ARGS...`; returns (exit code, stdout, stderr)."""

    def run(*args: str) -> tuple[int, str, str]:
        p = subprocess.run([str(binaries["rspose"]), *map(str, args)], capture_output=True, text=True)
        return p.returncode, p.stdout, p.stderr

    return run


@pytest.fixture(scope="session")
def cli_json(cli):
    """`rspose estimate PAIR --json ARGS...` as a dict (the command must succeed)."""

    def run(path, *args: str) -> dict:
        code, out, err = cli("estimate", path, "--json", *args)
        assert code == 0, err
        return json.loads(out)

    return run


def real_pairs() -> list[Path]:
    return sorted(CC9PRO.glob("pair-*.json"))
