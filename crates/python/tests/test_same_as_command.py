"""Every method through the package gives the command's output bit for bit.

For each method and each data file it can take, `fairspline.curve(points, ...)` and
`fair curve FILE -o OUT --report REPORT` are run on the same points and options: the faired
points must have the same bits, and the reports the same fields and values (all but
`elapsed_ms`, the time it took). Where the command refuses (exit status 2), the package must
raise ValueError.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import fairspline
from conftest import DATA, read_grid, read_points, read_report, run_fair, same_bits, without_timing

FUNCTION = DATA / "airfoil_naca2412" / "naca2412_upper.csv"
WATERLINE = DATA / "hull_gunnerus" / "waterlines" / "wl_03.csv"
CONTOUR = DATA / "airfoil_naca2412" / "naca2412.csv"
SECTION = DATA / "hull_block_island_boat" / "sections" / "station_01.csv"
CURVE_FILES = [FUNCTION, WATERLINE, CONTOUR, SECTION]
GRID = DATA / "surface_utah_teapot" / "teapot_lid_control_net.csv"

CURVE_METHODS = [m["name"] for m in fairspline.methods() if m["kind"] == "curve"]
SURFACE_METHODS = [m["name"] for m in fairspline.methods() if m["kind"] == "surface"]


def command_curve(fair_bin, tmp_path: Path, source: Path, *options: str):
    """Runs `fair curve` on `source`; returns (points, report) or the failed process."""
    out, report = tmp_path / ("out" + source.suffix), tmp_path / "report.json"
    done = run_fair(fair_bin, "curve", source, "-o", out, "--report", report, "-q", *options)
    if done.returncode != 0:
        return done
    return read_points(out), read_report(report)


def set_options(params: dict) -> list[str]:
    """`--set` options carrying `params` as the package does (str() of ints, repr() of floats)."""
    text = {bool: lambda v: str(v).lower(), int: str, float: repr, str: str}
    return [arg for k, v in params.items() for arg in ("--set", f"{k}={text[type(v)](v)}")]


def assert_same(result: fairspline.FairedCurve, command) -> None:
    points, report = command
    assert same_bits(result.points, points), np.abs(result.points - points).max()
    assert set(result.report) == set(report)
    assert without_timing(result.report) == without_timing(report)
    assert result.points.dtype == np.float64 and result.points.flags.c_contiguous


@pytest.mark.parametrize("method", CURVE_METHODS)
def test_every_curve_method_on_data_files(fair_bin, tmp_path, method):
    succeeded = 0
    for source in CURVE_FILES:
        command = command_curve(fair_bin, tmp_path, source, "--method", method)
        points = read_points(source)
        if not isinstance(command, tuple):
            assert command.returncode == 2, command.stderr
            with pytest.raises(ValueError):
                fairspline.curve(points, method=method)
            continue
        assert_same(fairspline.curve(points, method=method), command)
        succeeded += 1
    assert succeeded > 0, f"{method} ran on none of the files"


def test_default_methods_match(fair_bin, tmp_path):
    for source in (FUNCTION, CONTOUR, SECTION):
        assert_same(fairspline.curve(read_points(source)), command_curve(fair_bin, tmp_path, source))


CASES = [
    # (method, file, params, keyword arguments)
    ("smoothing-spline", CONTOUR, {"p": 0.9999}, {"fixed": [0, 17]}),
    ("smoothing-spline", FUNCTION, {"p": "auto", "rule": "trace"}, {"tolerance": 0.001}),
    ("strain-energy", CONTOUR, {"energy-tolerance": 1e-8, "pairs": "on"}, {"clamp_ends": "g0"}),
    ("strain-energy", CONTOUR, {}, {"points_to_fix": [5, 9]}),
    ("kjellander", WATERLINE, {"max-iterations": 50}, {"tolerance": 0.01, "kind": "parametric"}),
    ("nurbs-weights", FUNCTION, {"criterion": "ek"}, {}),
    ("two-phase", WATERLINE, {}, {"fixed": [3, 40]}),
    ("sapidis-farin", CONTOUR, {"jump-reduction": 0.001}, {}),
    ("batten", SECTION, {"update": "jacobi"}, {}),
]


@pytest.mark.parametrize("method,source,params,options", CASES)
def test_parameters_and_constraints(fair_bin, tmp_path, method, source, params, options):
    if method not in CURVE_METHODS:
        pytest.skip(f"{method} is not in this build's catalogue")
    flags = ["--method", method, *set_options(params)]
    for name, flag in [("fixed", "--fixed"), ("points_to_fix", "--points")]:
        if name in options:
            flags += [flag, ",".join(map(str, options[name]))]
    for name, flag in [("tolerance", "--tolerance"), ("clamp_ends", "--clamp-ends"), ("kind", "--kind")]:
        if name in options:
            flags += [flag, repr(options[name]) if isinstance(options[name], float) else options[name]]
    command = command_curve(fair_bin, tmp_path, source, *flags)
    assert isinstance(command, tuple), command.stderr
    assert_same(fairspline.curve(read_points(source), method=method, params=params, **options), command)


def test_corners_are_the_commands(fair_bin, tmp_path):
    """corners= is `--corners`: detected by default (R140's trailing edge, kept bit for bit),
    "none", and a list give the command's result."""
    source = DATA / "airfoil_r140" / "r140.csv"
    points = read_points(source)
    default = fairspline.curve(points)
    assert default.report["corners"] == [0]
    assert same_bits(default.points[0], points[0])
    assert_same(default, command_curve(fair_bin, tmp_path, source))
    for given, flag in [("none", "none"), ([0, 46], "0,46")]:
        command = command_curve(fair_bin, tmp_path, source, "--corners", flag)
        assert isinstance(command, tuple), command.stderr
        assert_same(fairspline.curve(points, corners=given), command)
    with pytest.raises(ValueError, match="corners"):
        fairspline.curve(points, corners="sometimes")


def test_closed_two_phase_is_the_closed_parameter(fair_bin, tmp_path):
    command = command_curve(fair_bin, tmp_path, CONTOUR, "--method", "two-phase", "--set", "closed=true")
    assert isinstance(command, tuple), command.stderr
    assert_same(fairspline.curve(read_points(CONTOUR), method="two-phase", closed=True), command)


def test_closed_loop_is_given_with_its_first_point_repeated(fair_bin, tmp_path):
    """closed=True for a method without a closed mode: the command's closed form (first point
    repeated at the end); the result drops the repeat."""
    t = np.linspace(0.0, 2.0 * np.pi, 24, endpoint=False)
    loop = np.column_stack([np.cos(t), 0.6 * np.sin(t) + 0.01 * np.cos(7 * t)])
    repeated = tmp_path / "loop.csv"
    repeated.write_text("x,y\n" + "".join(f"{float(x)!r},{float(y)!r}\n" for x, y in np.vstack([loop, loop[:1]])))
    points, report = command_curve(fair_bin, tmp_path, repeated, "--method", "strain-energy")
    result = fairspline.curve(loop, method="strain-energy", closed=True)
    assert same_bits(result.points, points[:-1])
    assert same_bits(points[0], points[-1])
    assert without_timing(result.report) == without_timing(report)


@pytest.mark.parametrize("method", SURFACE_METHODS)
def test_every_surface_method(fair_bin, tmp_path, method):
    out, report = tmp_path / "out.csv", tmp_path / "report.json"
    done = run_fair(fair_bin, "surface", GRID, "--method", method, "-o", out, "--report", report, "-q")
    assert done.returncode == 0, done.stderr
    result = fairspline.surface(read_grid(GRID), method=method)
    assert same_bits(result.grid, read_grid(out))
    assert without_timing(result.report) == without_timing(read_report(report))


def test_surface_constraints(fair_bin, tmp_path):
    grid = read_grid(GRID)
    columns = grid.shape[1]
    out, report = tmp_path / "out.csv", tmp_path / "report.json"
    done = run_fair(fair_bin, "surface", GRID, "-o", out, "--report", report, "-q", "--method", "zhang-cheng",
                    "--fixed", f"{columns + 1},{2 * columns + 2}", "--tolerance", "0.05", "--set", "max-steps=200")
    assert done.returncode == 0, done.stderr
    result = fairspline.surface(grid, method="zhang-cheng", fixed=[(1, 1), 2 * columns + 2], tolerance=0.05,
                                params={"max-steps": 200})
    assert same_bits(result.grid, read_grid(out))
    assert without_timing(result.report) == without_timing(read_report(report))


def test_inspect_matches(fair_bin, tmp_path):
    for source, kind in [(FUNCTION, None), (CONTOUR, None), (SECTION, None), (FUNCTION, "parametric")]:
        report = tmp_path / "inspect.json"
        flags = ["--kind", kind] if kind else []
        done = run_fair(fair_bin, "inspect", source, "--report", report, "-q", *flags)
        assert done.returncode == 0, done.stderr
        assert fairspline.inspect(read_points(source), kind=kind) == read_report(report)
    done = run_fair(fair_bin, "inspect", GRID, "--report", report, "-q")
    assert done.returncode == 0, done.stderr
    assert fairspline.inspect(read_grid(GRID)) == read_report(report)


PIPELINE = """
[constraints]
fixed = [0, 17]
tolerance = 0.002

[[stage]]
method = "smoothing-spline"
p = 0.9999

[[stage]]
method = "strain-energy"
energy-tolerance = 1e-7
"""


def test_pipeline_from_toml_dict_and_path(fair_bin, tmp_path):
    config = tmp_path / "pipeline.toml"
    config.write_text(PIPELINE)
    command = command_curve(fair_bin, tmp_path, CONTOUR, "--config", config)
    assert isinstance(command, tuple), command.stderr
    points = read_points(CONTOUR)
    as_dict = {
        "constraints": {"fixed": [0, 17], "tolerance": 0.002},
        "stage": [
            {"method": "smoothing-spline", "p": 0.9999},
            {"method": "strain-energy", "energy-tolerance": 1e-7},
        ],
    }
    for pipeline in (fairspline.pipeline(config), fairspline.pipeline(PIPELINE), fairspline.pipeline(as_dict)):
        assert_same(pipeline.curve(points), command)
        assert_same(pipeline(points), command)


def test_pipeline_arguments_win_over_the_config(fair_bin, tmp_path):
    config = tmp_path / "pipeline.toml"
    config.write_text(PIPELINE)
    command = command_curve(fair_bin, tmp_path, CONTOUR, "--config", config, "--fixed", "3", "--tolerance", "0.001")
    assert isinstance(command, tuple), command.stderr
    assert_same(fairspline.pipeline(config).curve(read_points(CONTOUR), fixed=[3], tolerance=0.001), command)


def test_methods_is_the_command_catalogue(fair_bin):
    listed = run_fair(fair_bin, "methods")
    assert listed.returncode == 0
    catalogue = fairspline.methods()
    assert {m["kind"] for m in catalogue} == {"curve", "surface"}
    for method in catalogue:
        assert method["name"] in listed.stdout
        for parameter in method["parameters"]:
            assert f"{parameter['name']}={parameter['default']}" in listed.stdout
    defaults = fairspline.default_methods()
    assert set(defaults) == {"function", "parametric", "surface"}
    assert all(any(m["name"] == d for m in catalogue) for d in defaults.values())


def test_inputs_that_are_not_float64_c_arrays(fair_bin, tmp_path):
    """A Fortran-ordered or strided array, a list, and integer points give the same result as
    the float64 C array of the same values."""
    points = read_points(CONTOUR)
    reference = fairspline.curve(points, method="smoothing-spline")
    for variant in (np.asfortranarray(points), np.repeat(points, 2, axis=0)[::2], points.tolist()):
        result = fairspline.curve(variant, method="smoothing-spline")
        assert same_bits(result.points, reference.points)
    integers = np.array([[0, 0], [1, 2], [2, 3], [3, 3], [4, 2], [5, 0]])
    assert same_bits(fairspline.curve(integers).points, fairspline.curve(integers.astype(np.float64)).points)
