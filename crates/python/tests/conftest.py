"""Shared fixtures: where the repository and the `fair` binary are, and how to read data files.

The comparison binary is `$FAIR_BIN` when set, else the newest of `target/release/fair` and
`target/debug/fair` under `$CARGO_TARGET_DIR` (or the repository's `target/`). Both profiles
compute the same bits (no fast-math anywhere); `.ci/run` points FAIR_BIN at the release build.
"""

from __future__ import annotations

import csv
import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

REPO = Path(__file__).resolve().parents[3]
DATA = REPO / "data"


def fair_binary() -> Path:
    if os.environ.get("FAIR_BIN"):
        return Path(os.environ["FAIR_BIN"])
    target = Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
    found = [p for p in (target / "release" / "fair", target / "debug" / "fair") if p.exists()]
    if not found:
        pytest.exit("no `fair` binary: build it (cargo build --release) or set FAIR_BIN", returncode=1)
    return max(found, key=lambda p: p.stat().st_mtime)


@pytest.fixture(scope="session")
def fair_bin() -> Path:
    return fair_binary()


def run_fair(binary: Path, *args: str) -> subprocess.CompletedProcess:
    return subprocess.run([str(binary), *map(str, args)], capture_output=True, text=True, timeout=600)


def read_points(path: Path) -> np.ndarray:
    """The coordinate columns of a CSV curve file as the command reads them: a header naming
    x,y[,z] picks the columns (others are labels); without a header every column counts."""
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].lstrip().startswith("#")]
    first = [c.strip() for c in rows[0]]
    try:
        [float(c) for c in first]
        header, body = None, rows
    except ValueError:
        header, body = first, rows[1:]
    if header is None:
        columns = list(range(len(first)))
    else:
        columns = [header.index(n) for n in ("x", "y", "z") if n in header]
    return np.array([[float(r[c]) for c in columns] for r in body], dtype=np.float64)


def read_grid(path: Path) -> np.ndarray:
    """An `i,j,x,y,z` CSV as an (m, n, 3) array, indices shifted to start at 0."""
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r]
    if not rows[0][0].strip().lstrip("-").isdigit():
        rows = rows[1:]
    ij = np.array([[int(r[0]), int(r[1])] for r in rows])
    ij -= ij.min(axis=0)
    m, n = ij.max(axis=0) + 1
    grid = np.full((m, n, 3), np.nan)
    for (i, j), r in zip(ij, rows):
        grid[i, j] = [float(r[2]), float(r[3]), float(r[4])]
    assert not np.isnan(grid).any(), f"{path} is not a full grid"
    return grid


def read_report(path: Path) -> dict:
    return json.loads(Path(path).read_text())


def same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    """Equal shapes and equal bits (so -0.0 differs from 0.0 and NaN never matches)."""
    a, b = np.ascontiguousarray(a, dtype=np.float64), np.ascontiguousarray(b, dtype=np.float64)
    return a.shape == b.shape and np.array_equal(a.view(np.uint64), b.view(np.uint64))


def without_timing(value):
    """The report less what measures time (`elapsed_ms`, at the top and in each pipeline
    stage), the one field two runs differ in."""
    if isinstance(value, dict):
        return {k: without_timing(v) for k, v in value.items() if k != "elapsed_ms"}
    if isinstance(value, list):
        return [without_timing(v) for v in value]
    return value
