"""Bad input raises ValueError naming the problem, never a crash of the interpreter."""

from __future__ import annotations

import numpy as np
import pytest

import fairspline

T = np.linspace(0.0, 1.0, 12)
GOOD = np.column_stack([T, np.sin(3.0 * T)])
I, J = np.meshgrid(np.arange(4.0), np.arange(5.0), indexing="ij")
GRID = np.stack([I, J, 0.1 * I * J], axis=-1)


@pytest.mark.parametrize(
    "points,words",
    [
        (np.arange(10.0), ["(n, 2) or (n, 3)", "(10,)"]),
        (np.zeros((6, 4)), ["(n, 2) or (n, 3)", "(6, 4)"]),
        (np.zeros((2, 3, 3)), ["(n, 2) or (n, 3)", "(2, 3, 3)"]),
        (np.zeros((0, 2)), ["0 points"]),
        (GOOD[:2], ["2 points", "at least 3"]),
    ],
)
def test_wrong_shape(points, words):
    with pytest.raises(ValueError) as raised:
        fairspline.curve(points)
    for word in words:
        assert word in str(raised.value)


@pytest.mark.parametrize("bad", [np.nan, np.inf, -np.inf])
def test_not_finite(bad):
    points = GOOD.copy()
    points[4, 1] = bad
    with pytest.raises(ValueError, match="point 4 .*not finite"):
        fairspline.curve(points)
    with pytest.raises(ValueError, match="not finite"):
        fairspline.inspect(points)
    grid = GRID.copy()
    grid[2, 3, 2] = bad
    with pytest.raises(ValueError, match=r"\(2, 3\).*not finite"):
        fairspline.surface(grid)


@pytest.mark.parametrize(
    "points,dtype",
    [
        (GOOD.astype(np.complex128), "complex128"),
        (GOOD > 0.5, "bool"),
        (GOOD.astype(str), "U"),
        (np.array([[0.0, 1.0], [1.0]], dtype=object), "object"),
    ],
)
def test_wrong_dtype(points, dtype):
    with pytest.raises(ValueError, match=f"dtype.*{dtype}"):
        fairspline.curve(points)


def test_ragged_list():
    with pytest.raises(ValueError, match="points"):
        fairspline.curve([[0.0, 1.0], [1.0], [2.0, 3.0]])


def test_unknown_method():
    with pytest.raises(ValueError, match=r"unknown curve method `wobble`.*strain-energy"):
        fairspline.curve(GOOD, method="wobble")
    with pytest.raises(ValueError, match=r"method: `strain-energy` is a curve method and the input is a surface"):
        fairspline.surface(GRID, method="strain-energy")


def test_unknown_parameter():
    with pytest.raises(ValueError, match=r"params.*`wobble`"):
        fairspline.curve(GOOD, method="smoothing-spline", params={"wobble": 1})


def test_bad_parameter_value():
    with pytest.raises(ValueError, match=r"params: `smoothing-spline`: p = 7(\.0)? is out of range: a number in \[0, 1\]"):
        fairspline.curve(GOOD, method="smoothing-spline", params={"p": 7.0})
    with pytest.raises(ValueError, match="must be a number, a boolean or a string"):
        fairspline.curve(GOOD, method="smoothing-spline", params={"p": [0.5]})


def test_fixed_index_out_of_range():
    with pytest.raises(ValueError, match=r"fixed: index 12 is past the last point \(12 points"):
        fairspline.curve(GOOD, fixed=[0, 12])
    with pytest.raises(ValueError, match=r"fixed: index -1 is negative"):
        fairspline.curve(GOOD, fixed=[-1])
    with pytest.raises(ValueError, match=r"fixed: index 3 appears twice"):
        fairspline.curve(GOOD, fixed=[3, 3])
    with pytest.raises(ValueError, match=r"points_to_fix: index 40 is past the last point"):
        fairspline.curve(GOOD, method="strain-energy", points_to_fix=[40])
    with pytest.raises(ValueError, match=r"fixed: column j = 9 of \(1, 9\)"):
        fairspline.surface(GRID, fixed=[(1, 9)])
    with pytest.raises(ValueError, match=r"fixed: index 20 is past the last point \(20 points"):
        fairspline.surface(GRID, fixed=[20])


def test_options_the_method_cannot_use():
    with pytest.raises(ValueError, match="points_to_fix"):
        fairspline.curve(GOOD, method="smoothing-spline", points_to_fix=[3])
    with pytest.raises(ValueError, match="clamp_ends"):
        fairspline.curve(GOOD, method="two-phase", clamp_ends="g2")
    with pytest.raises(ValueError, match="clamp_ends: `g4`"):
        fairspline.curve(GOOD, clamp_ends="g4")
    with pytest.raises(ValueError, match="kind: `spline`"):
        fairspline.curve(GOOD, kind="spline")
    with pytest.raises(ValueError, match="tolerance"):
        fairspline.curve(GOOD, tolerance=-1.0)
    with pytest.raises(ValueError, match="kind"):
        fairspline.curve(GOOD[::-1], kind="function")


def test_bad_config():
    with pytest.raises(ValueError, match="unknown curve method `wobble`"):
        fairspline.pipeline("[[stage]]\nmethod = 'wobble'\n").curve(GOOD)
    with pytest.raises(ValueError, match=r"config:2"):
        fairspline.pipeline("[constraints]\nfixed = [0,\n")
    with pytest.raises(TypeError, match="config"):
        fairspline.pipeline(42)


def test_a_failure_leaves_the_interpreter_usable():
    for _ in range(3):
        with pytest.raises(ValueError):
            fairspline.curve(np.full((5, 2), np.nan))
    assert fairspline.curve(GOOD).points.shape == GOOD.shape
