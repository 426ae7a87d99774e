"""The Dask example fairs 200 curves on a LocalCluster of 2 workers and matches the
sequential result; a failing curve is reported on its own without stopping the others."""

from __future__ import annotations

import importlib.util
import json
import sys

import numpy as np
import pytest

from conftest import REPO, run_fair, same_bits, without_timing

pytest.importorskip("dask.distributed")

FLEET = REPO / "examples" / "python" / "fleet.py"
# The test is of the distribution, not of a method: the smoothing spline is one linear solve
# per curve, so 200 curves take seconds even with a debug build of the package.
METHOD = "smoothing-spline"


@pytest.fixture(scope="module")
def fleet():
    spec = importlib.util.spec_from_file_location("fleet", FLEET)
    module = importlib.util.module_from_spec(spec)
    sys.modules["fleet"] = module
    spec.loader.exec_module(module)
    return module


@pytest.fixture(scope="module")
def folder(tmp_path_factory, fleet):
    folder = tmp_path_factory.mktemp("fleet")
    fleet.make_fleet(198, str(folder), points=60)
    (folder / "zz_bad_nan.csv").write_text("x,y\n0,0\n1,nan\n2,1\n3,0\n")
    (folder / "zz_bad_short.csv").write_text("x,y\n0,0\n1,1\n")
    return folder


def test_fleet_on_two_workers_matches_sequential(fleet, folder):
    items = fleet.list_items(str(folder))
    assert len(items) == 200
    with fleet.connect(workers=2) as client:
        assert len(client.scheduler_info()["workers"]) == 2
        distributed = fleet.fair_fleet(items, METHOD)
    sequential = fleet.fair_sequential(items, METHOD)
    assert [r["source"] for r in distributed] == [item["source"] for item in items]
    failed = [r for r in distributed if "error" in r]
    assert [r["source"] for r in failed] == [str(folder / "zz_bad_nan.csv"), str(folder / "zz_bad_short.csv")]
    assert all(r["exit_status"] == 2 for r in failed)
    for d, s in zip(distributed, sequential):
        assert d.keys() == s.keys()
        if "error" in d:
            assert d == s
        else:
            assert same_bits(d["points"], s["points"])
            assert without_timing(d["report"]) == without_timing(s["report"])


def test_fleet_report_is_the_command_batch_report(fleet, folder, fair_bin, tmp_path):
    """The example's JSON lines are the lines of `fair curve DIR` (but the time)."""
    items = fleet.list_items(str(folder))[-12:]
    subset = tmp_path / "subset"
    subset.mkdir()
    for item in items:
        (subset / item["source"].rsplit("/", 1)[-1]).write_text(open(item["path"]).read())
    done = run_fair(fair_bin, "curve", subset, "-q")
    assert done.returncode == 2  # the two bad curves
    command = [json.loads(line) for line in done.stdout.splitlines()]
    ours = [json.loads(line) for line in fleet.report_lines(fleet.fair_sequential(fleet.list_items(str(subset))))]
    assert len(command) == len(ours) == 12
    for c, o in zip(command, ours):
        assert c["source"].rsplit("/", 1)[-1] == o["source"].rsplit("/", 1)[-1]
        if "error" in c:
            assert o["exit_status"] == c["exit_status"] == 2
        else:
            c.pop("source"), o.pop("source")
            assert without_timing(c) == without_timing(o)


def test_fleet_from_json_lines(fleet, folder, tmp_path):
    lines = tmp_path / "fleet.jsonl"
    items = fleet.list_items(str(folder))[:5]
    lines.write_text("".join(json.dumps({"points": fleet.read_curve_file(i["path"]).tolist()}) + "\n" for i in items))
    from_lines = fleet.fair_sequential(fleet.list_items(str(lines)))
    from_files = fleet.fair_sequential(items)
    for a, b in zip(from_lines, from_files):
        assert same_bits(a["points"], b["points"])
