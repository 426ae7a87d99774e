"""`fairspline.export_cad` and `fairspline.read_cad`: the file holds the same curve as `fair curve -o
FILE.igs` writes (bit for bit), and the faired points lie on it to 1e-9 of their size,
evaluated here by de Boor's algorithm independently of the framework."""

from __future__ import annotations

import numpy as np
import pytest

import fairspline
from conftest import DATA, read_points, read_report, run_fair


def evaluate(curve: dict, t: float) -> np.ndarray:
    """The (rational) B-spline curve at t, by de Boor's algorithm in homogeneous coordinates."""
    p = curve["degree"]
    knots = np.array(curve["knots"])
    points = np.array(curve["control_points"])
    weights = np.array(curve["weights"])
    n = len(points) - 1
    k = min(max(int(np.searchsorted(knots, t, side="right")) - 1, p), n)
    homogeneous = np.hstack([points * weights[:, None], weights[:, None]])
    d = [homogeneous[j + k - p].copy() for j in range(p + 1)]
    for r in range(1, p + 1):
        for j in range(p, r - 1, -1):
            left, right = knots[j + k - p], knots[j + 1 + k - r]
            alpha = 0.0 if right == left else (t - left) / (right - left)
            d[j] = (1.0 - alpha) * d[j - 1] + alpha * d[j]
    return d[p][:3] / d[p][3]


def lifted(points: np.ndarray) -> np.ndarray:
    return np.hstack([points, np.zeros((len(points), 3 - points.shape[1]))])


def size(points: np.ndarray) -> float:
    return float(np.linalg.norm(points.max(axis=0) - points.min(axis=0)))


def test_a_function_result_is_the_command_s_file(tmp_path, fair_bin):
    path = DATA / "airfoil_r140" / "r140_upper.csv"
    result = fairspline.curve(read_points(path), method="two-phase")
    summary = fairspline.export_cad(result, tmp_path / "py.igs")
    assert summary["representation"] == "spline-function" and summary["exact"]
    ours = fairspline.read_cad(tmp_path / "py.igs")
    command = run_fair(fair_bin, "curve", path, "-m", "two-phase", "-q", "-o", tmp_path / "cmd.igs",
                       "--report", tmp_path / "cmd.json")
    assert command.returncode == 0, command.stderr
    theirs = fairspline.read_cad(tmp_path / "cmd.igs")
    for field in ("degree", "knots", "control_points", "weights"):
        assert ours["curves"][0][field] == theirs["curves"][0][field], field
    report = read_report(tmp_path / "cmd.json")["cad"]
    assert {k: v for k, v in summary.items() if k != "file"} == {k: v for k, v in report.items() if k != "file"}
    # A function's curve has x(t) = t: the faired point above x_i is the curve at t = x_i.
    faired = lifted(result.points)
    on_curve = np.array([evaluate(ours["curves"][0], x) for x in faired[:, 0]])
    assert np.abs(on_curve - faired).max() <= 1e-9 * size(faired)


@pytest.mark.parametrize("method, fmt", [("strain-energy", "step"), ("nurbs-weights", "dxf")])
def test_a_parametric_result_passes_through_its_points(tmp_path, method, fmt):
    points = read_points(DATA / "airfoil_naca2412" / "naca2412_upper.csv")
    params = {"max-iterations": 60} if method == "nurbs-weights" else None
    result = fairspline.curve(points, method=method, kind="parametric", params=params)
    summary = fairspline.export_cad(result, tmp_path / "c.out", format=fmt)
    assert summary["format"] == fmt and summary["exact"]
    model = fairspline.read_cad(tmp_path / "c.out", format=fmt)
    record = result.report["curve"]
    parameters = record["knots"] if record["type"] == "hermite" else record["params"]
    faired = lifted(result.points)
    on_curve = np.array([evaluate(model["curves"][0], t) for t in parameters[: len(faired)]])
    assert np.abs(on_curve - faired).max() <= 1e-9 * size(faired)


def test_points_as_they_are_with_a_rebuild(tmp_path):
    points = read_points(DATA / "airfoil_r140" / "r140_upper.csv")
    summary = fairspline.export_cad(points, tmp_path / "r.step", control_points=10)
    assert not summary["exact"] and summary["control_points"] == 10
    assert summary["wiggles_back"] == (
        summary["written"]["vibrations"] > summary["faired"]["vibrations"]
        or summary["written"]["inflections"] > summary["faired"]["inflections"]
    )
    curve = fairspline.read_cad(tmp_path / "r.step")["curves"][0]
    assert len(curve["control_points"]) == 10
    deviation = max(abs(evaluate(curve, x)[1] - y) for x, y in points)
    assert deviation == pytest.approx(summary["max_deviation"], rel=1e-9, abs=1e-15)


def test_a_surface_and_the_refusals(tmp_path):
    x, y = np.meshgrid(np.arange(7.0) * 10, np.arange(6.0) * 8, indexing="ij")
    grid = np.stack([x, y, 0.002 * x * x + 0.1 * y], axis=-1)
    grid[3, 2, 2] += 1.5
    result = fairspline.surface(grid)
    summary = fairspline.export_cad(result, tmp_path / "s.stp")
    assert summary["representation"] == "bicubic"
    model = fairspline.read_cad(tmp_path / "s.stp")
    assert len(model["surfaces"]) == 1 and not model["curves"]
    for call, argument in [
        (lambda: fairspline.export_cad(result, tmp_path / "s.dxf"), "path"),
        (lambda: fairspline.export_cad(result, tmp_path / "s.igs", control_points=6), "control_points"),
        (lambda: fairspline.export_cad(grid[0], tmp_path / "c.csv"), "path"),
        (lambda: fairspline.export_cad(grid[0], tmp_path / "c.igs", format="obj"), "format"),
        (lambda: fairspline.export_cad(grid[0], tmp_path / "c.igs", control_points=5, fit_tolerance=0.1), "control_points"),
    ]:
        with pytest.raises(ValueError, match=f"^{argument}:"):
            call()
    assert not (tmp_path / "s.dxf").exists()
