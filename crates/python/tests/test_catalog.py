"""`fairspline.Catalog`: strategies and criteria written in Python, run by the framework as the
built-ins run. The constraints are the library's (fixed points bit for bit, moves clipped to the
tolerance band), whatever the Python function proposes."""

from __future__ import annotations

import numpy as np
import pytest

import fairspline

TOLERANCE = 0.004
FIXED = [0, 7, 20, 40]


def noisy_arc(n: int = 41, seed: int = 5) -> np.ndarray:
    """A parametric quarter circle with noise (x not monotone in places: a parametric curve)."""
    rng = np.random.default_rng(seed)
    t = np.linspace(0.0, np.pi / 2, n)
    points = np.column_stack([np.cos(t), np.sin(t)])
    return points + 3e-3 * rng.standard_normal(points.shape)


def laplace(points, context):
    """Laplacian smoothing: every point a fraction of the way to its neighbours' midpoint."""
    if context.step >= context.settings["passes"]:
        return None
    proposed = points.copy()
    proposed[1:-1] += context.settings["factor"] * (0.5 * (points[:-2] + points[2:]) - points[1:-1])
    return proposed


def catalog_with_laplace() -> fairspline.Catalog:
    catalog = fairspline.Catalog()
    catalog.add_strategy(
        "laplace",
        laplace,
        settings={"factor": 0.5, "passes": 25},
        docs={"factor": "how far towards the midpoint per pass", "passes": "passes at most"},
    )
    return catalog


def test_catalog_lists_the_builtins_as_the_module_does():
    catalog = fairspline.Catalog()
    assert catalog.methods() == fairspline.methods()
    names = [c["name"] for c in catalog.criteria()]
    assert {"e1", "e2", "e3", "ek", "ek-prime"} <= set(names)
    assert "two-phase" in catalog and "laplace" not in catalog


def test_a_python_strategy_is_listed_with_its_settings_and_not_added_to_the_module():
    catalog = catalog_with_laplace()
    (entry,) = [m for m in catalog.methods() if m["name"] == "laplace"]
    assert entry["kind"] == "curve"
    assert entry["summary"] == "Laplacian smoothing: every point a fraction of the way to its neighbours' midpoint."
    parameters = {p["name"]: p for p in entry["parameters"]}
    assert parameters["factor"]["value"] == 0.5 and parameters["factor"]["schema"]["type"] == "number"
    assert parameters["factor"]["meaning"] == "how far towards the midpoint per pass"
    assert parameters["passes"]["value"] == 25 and parameters["passes"]["schema"]["type"] == "integer"
    assert "laplace" not in [m["name"] for m in fairspline.methods()]
    assert "laplace" not in fairspline.Catalog()


def test_pipeline_builtin_then_python_strategy_keeps_constraints_and_reports_python_criterion():
    catalog = catalog_with_laplace()
    seen = []

    def chord_turning(curve):
        """Total turning of the sampled tangent, in radians."""
        d1 = curve.d1
        cross = d1[:-1, 0] * d1[1:, 1] - d1[:-1, 1] * d1[1:, 0]
        dot = np.einsum("ij,ij->i", d1[:-1], d1[1:])
        value = float(np.abs(np.arctan2(cross, dot)).sum())
        seen.append((curve, value))
        return value

    catalog.add_criterion("turning", chord_turning)
    points = noisy_arc()
    config = {
        "constraints": {"fixed": FIXED, "tolerance": TOLERANCE},
        "stage": [{"method": "smoothing-spline"}, {"method": "laplace", "factor": 0.3}],
    }
    result = catalog.pipeline(config).curve(points, kind="parametric")
    report = result.report

    assert [s["method"] for s in report["stages"]] == ["smoothing-spline", "laplace"]
    assert report["stages"][1]["params"] == {"factor": 0.3, "passes": 25}
    assert report["stages"][1]["moved"] > 0
    # Fixed points bit for bit, every move within the band.
    assert result.points[FIXED].tobytes() == points[FIXED].tobytes()
    moves = np.linalg.norm(result.points - points, axis=1)
    assert moves.max() <= TOLERANCE
    # The Python criterion's values are the report's, before and after.
    values = [v for _, v in seen]
    assert report["before"]["criteria"]["turning"] in values
    assert report["after"]["criteria"]["turning"] in values
    assert report["after"]["criteria"]["turning"] < report["before"]["criteria"]["turning"]
    # It saw the measured curve: at its breaks, the interpolating spline passes through the
    # points it measures (the input for `before`).
    curve = next(c for c, v in seen if v == report["before"]["criteria"]["turning"])
    at_breaks = curve.points[np.isin(curve.t, curve.breaks)]
    np.testing.assert_allclose(at_breaks, points, rtol=0, atol=1e-12)


def test_moves_past_the_band_are_clipped_and_fixed_points_refused():
    catalog = fairspline.Catalog()
    calls = []

    def push_out(points, context):
        """Proposes every point, fixed ones included, 1.0 further out (far past the band)."""
        calls.append(context)
        if context.step > 0:
            return None
        return points * 2.0

    catalog.add_strategy("push-out", push_out)
    points = noisy_arc()
    result = catalog.curve(points, method="push-out", kind="parametric", fixed=FIXED, tolerance=TOLERANCE)
    moves = np.linalg.norm(result.points - points, axis=1)
    free = np.setdiff1d(np.arange(len(points)), FIXED)
    assert result.points[FIXED].tobytes() == points[FIXED].tobytes()
    assert moves.max() <= TOLERANCE
    # Projected onto the band's sphere, not left where they were.
    assert moves[free].min() > 0.999 * TOLERANCE
    # The context names the frozen points; the band is in the frame the points are in.
    assert list(calls[0].fixed) == FIXED
    assert calls[0].tolerance is not None and calls[0].kind == "parametric"


def test_a_function_keeps_its_x_whatever_the_strategy_proposes():
    catalog = fairspline.Catalog()
    catalog.add_strategy("shift", lambda p, c: None if c.step else p + 0.01)
    x = np.linspace(0.0, 1.0, 21)
    points = np.column_stack([x, np.sin(3 * x)])
    result = catalog.curve(points, method="shift", kind="function")
    assert result.points[:, 0].tobytes() == points[:, 0].tobytes()
    assert np.all(result.points[:, 1] != points[:, 1])


def test_an_exception_in_the_strategy_is_a_python_exception_naming_it():
    catalog = fairspline.Catalog()

    def broken(points, context):
        raise ZeroDivisionError("no step today")

    catalog.add_strategy("broken", broken)
    with pytest.raises(RuntimeError, match=r"strategy `broken`.*ZeroDivisionError: no step today") as raised:
        catalog.curve(noisy_arc(), method="broken")
    assert isinstance(raised.value.__cause__, ZeroDivisionError)
    # In a pipeline after a built-in, too; and the catalogue still works afterwards.
    with pytest.raises(RuntimeError, match=r"strategy `broken`"):
        catalog.pipeline({"stage": [{"method": "smoothing-spline"}, {"method": "broken"}]}).curve(noisy_arc())
    assert catalog.curve(noisy_arc(), method="smoothing-spline").points.shape == (41, 2)


def test_an_exception_in_a_criterion_is_a_python_exception_naming_it():
    catalog = fairspline.Catalog()
    catalog.add_criterion("fails", lambda curve: 1.0 / 0.0)
    with pytest.raises(RuntimeError, match=r"criterion `fails`.*ZeroDivisionError") as raised:
        catalog.curve(noisy_arc(), method="smoothing-spline")
    assert isinstance(raised.value.__cause__, ZeroDivisionError)
    catalog = fairspline.Catalog()
    catalog.add_criterion("nan", lambda curve: float("nan"))
    with pytest.raises(RuntimeError, match=r"criterion `nan`.*not a finite number"):
        catalog.curve(noisy_arc(), method="smoothing-spline")


def test_bad_proposals_and_settings_are_refused_by_name():
    catalog = catalog_with_laplace()
    catalog.add_strategy("short", lambda p, c: p[:-1])
    with pytest.raises(RuntimeError, match=r"strategy `short`.*shape \(40, 2\) where the points are \(41, 2\)"):
        catalog.curve(noisy_arc(), method="short")
    catalog.add_strategy("nan", lambda p, c: p * np.nan)
    with pytest.raises(RuntimeError, match=r"strategy `nan`.*not finite"):
        catalog.curve(noisy_arc(), method="nan")
    with pytest.raises(ValueError, match=r"`factor`.*not a number"):
        catalog.curve(noisy_arc(), method="laplace", params={"factor": "lots"})
    with pytest.raises(ValueError, match=r"`speed`.*factor, passes"):
        catalog.curve(noisy_arc(), method="laplace", params={"speed": 2})
    with pytest.raises(ValueError, match=r"docs: `speed` is not one of the settings"):
        catalog.add_strategy("x", laplace, settings={"factor": 0.5}, docs={"speed": "?"})
    with pytest.raises(TypeError, match=r"strategy `x` needs a callable"):
        catalog.add_strategy("x", 3)
    with pytest.raises(ValueError, match=r"name: `a b`"):
        catalog.add_strategy("a b", laplace)


def test_a_builtin_method_searches_with_a_python_criterion():
    """nurbs-weights takes `criterion=NAME`: it minimises the Python criterion, which sees the
    curve's second derivative (its trapezoid rule over the samples is within 2 % of the
    built-in e2 = ∫|C''|² dt of the same curve)."""
    catalog = fairspline.Catalog()
    calls = []

    def sampled_e2(curve):
        """∫|C''|² dt by the trapezoid rule over the samples."""
        calls.append(1)
        squared = np.sum(curve.d2**2, axis=1)
        return float(np.sum(0.5 * (squared[:-1] + squared[1:]) * np.diff(curve.t)))

    catalog.add_criterion("sampled-e2", sampled_e2)
    points = noisy_arc(21)
    result = catalog.curve(
        points, method="nurbs-weights", kind="parametric", params={"criterion": "sampled-e2", "max-iterations": 5}
    )
    report = result.report
    assert report["params"]["criterion"] == "sampled-e2"
    assert len(calls) > 2  # during the search, not only for the report's before and after
    for side in ("before", "after"):
        criteria = report[side]["criteria"]
        assert abs(criteria["sampled-e2"] - criteria["e2"]) < 2e-2 * criteria["e2"]
    assert report["after"]["criteria"]["sampled-e2"] < report["before"]["criteria"]["sampled-e2"]


def test_threads_share_a_catalog_with_python_methods():
    """Calls from several threads (each releasing the GIL, the strategy taking it back at every
    step) neither deadlock nor mix their results or exceptions: each is the sequential one."""
    from concurrent.futures import ThreadPoolExecutor

    catalog = catalog_with_laplace()
    catalog.add_strategy("broken", lambda p, c: 1 / 0)
    cases = [noisy_arc(41, seed) for seed in range(6)]
    expected = [catalog.curve(p, method="laplace", fixed=FIXED, tolerance=TOLERANCE).points for p in cases]

    def run(k):
        if k % 3 == 2:
            with pytest.raises(RuntimeError, match="strategy `broken`"):
                catalog.curve(cases[k], method="broken")
            return None
        return catalog.curve(cases[k], method="laplace", fixed=FIXED, tolerance=TOLERANCE).points

    with ThreadPoolExecutor(3) as pool:
        results = list(pool.map(run, range(len(cases))))
    for k, points in enumerate(results):
        if points is not None:
            assert points.tobytes() == expected[k].tobytes()


def test_the_docs_example_runs():
    """docs/python.md's "Composing methods in Python" block, on a noisy arc of 41 points."""
    from test_readme import python_blocks

    (block,) = python_blocks("docs/python.md", "Composing methods in Python")
    namespace = {"points": noisy_arc()}
    exec(compile(block, "docs/python.md (composing methods)", "exec"), namespace)
    report = namespace["result"].report
    assert [s["method"] for s in report["stages"]] == ["smoothing-spline", "laplacian"]
    assert report["after"]["criteria"]["turning"] < report["before"]["criteria"]["turning"]
    moves = np.linalg.norm(namespace["result"].points - namespace["points"], axis=1)
    assert moves.max() <= 0.005
