"""Fair a fleet of curves on a Dask cluster with the `fairspline` package.

A fleet is many independent curves: every station, waterline and buttock of a set of hull
scans, every section of a wing. Fairing them is a map over curves, which Dask already
distributes well; this example is that map, with each curve's result and report collected
and a failing curve reported on its own line without stopping the others.

    python examples/python/fleet.py CURVES [--workers N | --scheduler ADDRESS]
                                    [--method M] [--set NAME=VALUE ...] [--report OUT.jsonl]

CURVES is a folder of curve files (CSV `x,y` / `x,y,z` with an optional header, or JSON
`{"points": ...}`), a JSON-lines file (one `{"points": [[x, y], ...]}` per line), or a
Parquet file with a `points` column (a list of [x, y] or [x, y, z] per row; needs pyarrow).
Without `--scheduler` a LocalCluster of `--workers` processes runs here; with
`--scheduler tcp://HOST:8786` the same code runs on that cluster (its workers need `fairspline`
installed, nothing else). `--make-fleet N DIR` writes N noisy test curves to DIR.

The report is one JSON line per curve in input order, the command's batch report: the
report of `fair curve` plus `source`, or `{"source", "error", "exit_status"}` for a curve
that failed (exit status 2 for bad input, 1 for a failure of the framework).
"""

from __future__ import annotations

import argparse
import contextlib
import json
import math
import os
import sys
import time
from pathlib import Path
from typing import Any, Iterable

import numpy as np

import fairspline


# --- reading curves -------------------------------------------------------------------------


def read_curve_file(path: str) -> np.ndarray:
    """Points of a CSV (`x,y[,z]`, optional header, `#` comments) or JSON curve file."""
    text = Path(path).read_text()
    if path.lower().endswith(".json") or text.lstrip().startswith(("{", "[")):
        document = json.loads(text)
        points = document["points"] if isinstance(document, dict) else document
        return np.asarray(points, dtype=np.float64)
    rows = []
    for line in text.splitlines():
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        fields = [f.strip() for f in line.split(",")] if "," in line else line.split()
        try:
            rows.append([float(f) for f in fields])
        except ValueError:
            if rows:  # a header is only allowed first
                raise ValueError(f"{path}: not a number in `{line}`") from None
    return np.asarray(rows, dtype=np.float64)


def list_items(source: str) -> list[dict[str, Any]]:
    """The fleet's curves as small picklable items: a path to read on the worker, or points.

    A folder's files are read where they are faired (workers share the file system, as on
    one machine or a cluster with a shared volume); lines and Parquet rows carry their points.
    """
    path = Path(source)
    if path.is_dir():
        return [
            {"source": str(p), "path": str(p)}
            for p in sorted(path.iterdir())
            if p.is_file() and not p.name.startswith(".")
        ]
    if path.suffix.lower() == ".parquet":
        import pyarrow.parquet as pq  # optional dependency

        table = pq.read_table(path)
        names = table.column("source").to_pylist() if "source" in table.column_names else None
        return [
            {"source": names[i] if names else f"{path}:{i + 1}", "points": points}
            for i, points in enumerate(table.column("points").to_pylist())
        ]
    items = []
    with open(path) as stream:
        for number, line in enumerate(stream, start=1):
            if line.strip():
                items.append({"source": f"{path}:{number}", "line": line})
    return items


# --- fairing one curve ----------------------------------------------------------------------


def fair_one(item: dict[str, Any], method: str | None = None, params: dict | None = None) -> dict[str, Any]:
    """Fairs one curve; never raises. Returns {source, points, report} or {source, error,
    exit_status} (2: bad input, the curve's to fix; 1: the framework failed)."""
    source = item["source"]
    try:
        if "path" in item:
            points = read_curve_file(item["path"])
        elif "line" in item:
            document = json.loads(item["line"])
            points = document["points"] if isinstance(document, dict) else document
        else:
            points = item["points"]
        result = fairspline.curve(points, method=method, params=params)
    except (ValueError, TypeError, KeyError, OSError) as error:
        return {"source": source, "error": str(error), "exit_status": 2}
    except Exception as error:  # a failure of the framework: reported, the fleet goes on
        return {"source": source, "error": f"{type(error).__name__}: {error}", "exit_status": 1}
    report = dict(result.report)
    report["source"] = source
    return {"source": source, "points": result.points, "report": report}


def fair_fleet(items: list[dict[str, Any]], method: str | None = None, params: dict | None = None,
               partitions: int | None = None) -> list[dict[str, Any]]:
    """Fairs every item with dask.bag on the active scheduler (a distributed Client when one
    is connected); results come back in input order."""
    import dask.bag as db

    if not items:
        return []
    partitions = partitions or min(len(items), 64)
    bag = db.from_sequence(items, npartitions=partitions)
    return bag.map(fair_one, method=method, params=params).compute()


def fair_sequential(items: list[dict[str, Any]], method: str | None = None,
                    params: dict | None = None) -> list[dict[str, Any]]:
    """The same, one curve after the other in this process (the reference for checks)."""
    return [fair_one(item, method, params) for item in items]


def report_lines(results: Iterable[dict[str, Any]]) -> list[str]:
    """One JSON line per curve: the report with `source`, or the error line."""
    lines = []
    for r in results:
        if "error" in r:
            lines.append(json.dumps({"source": r["source"], "error": r["error"], "exit_status": r["exit_status"]}))
        else:
            lines.append(json.dumps(r["report"]))
    return lines


@contextlib.contextmanager
def connect(workers: int = 2, scheduler: str | None = None):
    """A distributed Client, closed on exit: to `scheduler` if given, else to a new
    LocalCluster of `workers` single-threaded processes (closed too).

    Run as a script, this module's functions travel to the workers by value; imported (as
    the tests do), the module file is uploaded to them. Either way the workers need only
    `fairspline` (and numpy) installed.
    """
    from dask.distributed import Client, LocalCluster

    def ready(client):
        if __name__ != "__main__":
            client.upload_file(__file__)
        return client

    if scheduler:
        with Client(scheduler) as client:
            yield ready(client)
        return
    with LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                      dashboard_address=None) as cluster, Client(cluster) as client:
        yield ready(client)


# --- a test fleet ---------------------------------------------------------------------------


def make_fleet(count: int, folder: str, points: int = 200, seed: int = 7) -> list[str]:
    """Writes `count` noisy curves (sines, arcs, airfoil-like contours, clothoid-like spirals)
    as CSV files to `folder`; returns their paths."""
    rng = np.random.default_rng(seed)
    Path(folder).mkdir(parents=True, exist_ok=True)
    paths = []
    for k in range(count):
        t = np.linspace(0.0, 1.0, points)
        shape = k % 4
        if shape == 0:  # a function y(x)
            xy = np.column_stack([t * 10.0, np.sin(2.0 * math.pi * t * (1 + k % 3))])
        elif shape == 1:  # an arc
            a = t * math.pi * (0.5 + (k % 5) / 5.0)
            xy = np.column_stack([np.cos(a), np.sin(a)])
        elif shape == 2:  # an airfoil-like upper surface
            x = t**2
            xy = np.column_stack([x, 0.6 * (0.2969 * np.sqrt(x) - 0.126 * x - 0.3516 * x**2 + 0.2843 * x**3 - 0.1036 * x**4)])
        else:  # a spiral
            a = 4.0 * math.pi * t
            xy = np.column_stack([(1 + t) * np.cos(a), (1 + t) * np.sin(a)])
        xy[1:-1] += rng.normal(scale=2e-3, size=(points - 2, 2))
        path = os.path.join(folder, f"curve_{k:05d}.csv")
        with open(path, "w") as out:
            out.write("x,y\n")
            for x, y in xy:
                out.write(f"{float(x)!r},{float(y)!r}\n")
        paths.append(path)
    return paths


# --- command line ---------------------------------------------------------------------------


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("curves", nargs="?", help="folder, .jsonl or .parquet file of curves")
    parser.add_argument("--workers", type=int, default=2, help="LocalCluster worker processes (default 2)")
    parser.add_argument("--scheduler", help="address of a running Dask scheduler, e.g. tcp://host:8786")
    parser.add_argument("--method", help="fairing method (default: the command's for the curve's kind)")
    parser.add_argument("--set", dest="settings", action="append", default=[], metavar="NAME=VALUE",
                        help="a method parameter (repeatable)")
    parser.add_argument("--report", help="write the JSON-lines report here (default: standard output)")
    parser.add_argument("--make-fleet", nargs=2, metavar=("N", "DIR"), help="write N test curves to DIR and stop")
    args = parser.parse_args(argv)

    if args.make_fleet:
        make_fleet(int(args.make_fleet[0]), args.make_fleet[1])
        return 0
    if not args.curves:
        parser.error("CURVES is required")
    params = dict(s.split("=", 1) for s in args.settings) or None

    items = list_items(args.curves)
    with connect(args.workers, args.scheduler) as client:
        client.run(lambda: None)  # the workers are up before the clock starts
        start = time.perf_counter()
        results = fair_fleet(items, args.method, params)
        seconds = time.perf_counter() - start
    text = "\n".join(report_lines(results)) + ("\n" if results else "")
    if args.report:
        Path(args.report).write_text(text)
    else:
        sys.stdout.write(text)
    failed = sum("error" in r for r in results)
    where = args.scheduler or f"LocalCluster, {args.workers} workers"
    print(f"{len(results)} curves ({failed} failed) in {seconds:.2f} s on {where}: "
          f"{len(results) / seconds:.3g} curves/s", file=sys.stderr)
    if failed:
        return max(r.get("exit_status", 0) for r in results if "error" in r)
    return 0


if __name__ == "__main__":
    sys.exit(main())
