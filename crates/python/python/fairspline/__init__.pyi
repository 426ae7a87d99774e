"""Typed interface of the `fairspline` package (the native module `fairspline._native`)."""

import os
from typing import Any, Literal, Mapping, Sequence, TypedDict, Union

import numpy as np
import numpy.typing as npt

__version__: str

ArrayLike = npt.ArrayLike
Kind = Literal["auto", "function", "parametric"]
Clamp = Literal["g0", "g1", "g2"]
Corners = Union[Literal["auto", "none"], Sequence[int]]
ParamValue = Union[bool, int, float, str]
GridIndex = Union[int, tuple[int, int]]

class Parameter(TypedDict):
    name: str
    default: str
    meaning: str

class Method(TypedDict):
    name: str
    kind: Literal["curve", "surface"]
    paper: str
    summary: str
    parameters: list[Parameter]

class FairedCurve:
    """A faired curve: `.points` and `.report`."""

    @property
    def points(self) -> npt.NDArray[np.float64]:
        """The faired points, an (n, d) float64 array, same count and order as given."""
    @property
    def report(self) -> dict[str, Any]:
        """The report: exactly the fields of `fair curve --report` (method, kind, n,
        iterations, before, after, s_d, m_d, moved, elapsed_ms, curve, params, and the
        method's extras such as termination)."""

class FairedSurface:
    """A faired surface: `.grid` and `.report`."""

    @property
    def grid(self) -> npt.NDArray[np.float64]:
        """The faired grid, an (m, n, 3) float64 array."""
    @property
    def report(self) -> dict[str, Any]:
        """The report: exactly the fields of `fair surface --report`."""

class Pipeline:
    """A config as `fair curve --config` takes it; build with `fairspline.pipeline(config)`."""

    def curve(
        self,
        points: ArrayLike,
        kind: Kind | None = None,
        fixed: Sequence[int] | None = None,
        points_to_fix: Sequence[int] | None = None,
        tolerance: float | None = None,
        clamp_ends: Clamp | None = None,
        closed: bool = False,
    ) -> FairedCurve:
        """Fair a curve with this config (arguments win over its `[constraints]`)."""
    def __call__(
        self,
        points: ArrayLike,
        kind: Kind | None = None,
        fixed: Sequence[int] | None = None,
        points_to_fix: Sequence[int] | None = None,
        tolerance: float | None = None,
        clamp_ends: Clamp | None = None,
        closed: bool = False,
    ) -> FairedCurve:
        """Same as `.curve(...)`."""
    def surface(
        self,
        grid: ArrayLike,
        fixed: Sequence[GridIndex] | None = None,
        points_to_fix: Sequence[GridIndex] | None = None,
        tolerance: float | None = None,
        clamp_ends: Clamp | None = None,
    ) -> FairedSurface:
        """Fair a surface grid with this config (one method; stages are for curves)."""

def curve(
    points: ArrayLike,
    method: str | None = None,
    kind: Kind | None = None,
    params: Mapping[str, ParamValue] | None = None,
    fixed: Sequence[int] | None = None,
    points_to_fix: Sequence[int] | None = None,
    tolerance: float | None = None,
    clamp_ends: Clamp | None = None,
    closed: bool = False,
    corners: Corners | None = None,
) -> FairedCurve:
    """Fair a curve, as `fair curve` does.

    points: (n, 2) or (n, 3) array (float64; integer and float32 arrays are converted).
    method: a curve method of `methods()`; default jump-lsq.
    kind: "function", "parametric" or "auto"/None (function when x increases strictly).
    params: the method's parameters, {name: value}, as `--set name=value`.
    fixed: indices of points that must not move (`--fixed`).
    points_to_fix: the bad points for the interactive methods (`--points`).
    tolerance: no point moves farther than this (`--tolerance`).
    clamp_ends: "g0", "g1" or "g2" (`--clamp-ends`).
    closed: the points are a closed loop (last joins first).
    corners: "auto"/None (detected), "none", or indices kept as corners (`--corners`).

    Raises ValueError for bad input, with the framework's message.
    """

def surface(
    grid: ArrayLike,
    method: str | None = None,
    params: Mapping[str, ParamValue] | None = None,
    fixed: Sequence[GridIndex] | None = None,
    points_to_fix: Sequence[GridIndex] | None = None,
    tolerance: float | None = None,
    clamp_ends: Clamp | None = None,
) -> FairedSurface:
    """Fair an (m, n, 3) grid, as `fair surface` does; indices k = i * n + j or (i, j)."""

def inspect(points: ArrayLike, kind: Kind | None = None) -> dict[str, Any]:
    """Measure a curve ((n, 2)/(n, 3)) or a grid ((m, n, 3)), as `fair inspect` does."""

def lines(
    path: Union[str, os.PathLike[str]],
    step: float | None = None,
    tolerance: float | None = None,
    knuckles: Sequence[str] | None = None,
) -> tuple[dict[str, Any], npt.NDArray[np.float64]]:
    """Fair a table of offsets as one hull, as `fair lines` does: (report, (n, 3) offsets)."""

def methods() -> list[Method]:
    """The catalogue of methods, as `fair methods` lists them."""

def default_methods() -> dict[str, str]:
    """The default method for "function", "parametric" and "surface" input."""

def pipeline(config: Union[Mapping[str, Any], str, os.PathLike[str]]) -> Pipeline:
    """A pipeline from a config dict, TOML text, or a path to a .toml/.json file."""

Units = Literal["mm", "cm", "m", "um", "in", "ft"]
CadFormat = Literal["iges", "step", "dxf"]

class CurvatureCounts(TypedDict):
    inflections: int | None
    vibrations: int

class CadSummary(TypedDict, total=False):
    """The report's `cad` object: what was written and how close it is to the faired points."""

    format: CadFormat
    file: str
    units: Units
    tolerance: float
    representation: str
    exact: bool
    degree: int
    control_points: int
    max_deviation: float
    fit_tolerance: float | None
    exact_fallback: bool
    faired: CurvatureCounts
    written: CurvatureCounts
    wiggles_back: bool
    net: list[int]

def export_cad(
    result: Union[FairedCurve, FairedSurface, ArrayLike],
    path: Union[str, os.PathLike[str]],
    format: CadFormat | None = None,
    control_points: int | None = None,
    fit_tolerance: float | None = None,
    kind: Kind | None = None,
) -> CadSummary:
    """Write a faired result as an exact B-spline into a CAD file, as `fair curve -o FILE.igs`.

    result: a FairedCurve or FairedSurface (the method's own curve or surface is written),
        or an (n, 2)/(n, 3) curve or (m, n, 3) grid taken as already faired (written as the
        interpolating spline the report measures).
    path: the file; its extension (.igs/.iges, .step/.stp, .dxf) chooses the format.
    format: "iges", "step" or "dxf" (`--cad`; DXF holds curves only).
    control_points: rebuild a curve with this many control points (`--control-points`).
    fit_tolerance: rebuild with the fewest control points within this distance of every
        faired point (`--fit-tolerance`); the exact curve when no fit with at most half as
        many control points as points meets it.
    kind: for points only, "function", "parametric" or "auto".

    Returns the report's `cad` dict. Raises ValueError for a bad combination, naming the
    argument (a DXF surface, a rebuild of a surface, both rebuild options, ...).
    """

class CadCurve(TypedDict):
    name: str
    degree: int
    knots: list[float]
    control_points: list[list[float]]
    weights: list[float]

class CadSurface(TypedDict):
    name: str
    degrees: list[int]
    u_knots: list[float]
    v_knots: list[float]
    control_points: list[list[list[float]]]
    weights: list[list[float]]

class CadModel(TypedDict):
    units: Units
    tolerance: float
    curves: list[CadCurve]
    surfaces: list[CadSurface]

def read_cad(path: Union[str, os.PathLike[str]], format: CadFormat | None = None) -> CadModel:
    """Read an IGES, STEP or DXF file (ours, OpenCASCADE's, ezdxf's): its B-spline curves and
    surfaces, every number as written (the round trip is exact)."""

class StrategyContext:
    """What a Python strategy's function is given beside the points (a SimpleNamespace)."""

    original: npt.NDArray[np.float64]
    fixed: npt.NDArray[np.uint64]
    tolerance: float | None
    settings: dict[str, ParamValue]
    step: int
    kind: Literal["function", "parametric"]
    name: str

class CurveSamples:
    """What a Python criterion's function is given (a SimpleNamespace): the measured curve
    at every break and 15 more parameters inside each piece."""

    t: npt.NDArray[np.float64]
    points: npt.NDArray[np.float64]
    d1: npt.NDArray[np.float64]
    d2: npt.NDArray[np.float64]
    d3: npt.NDArray[np.float64]
    breaks: npt.NDArray[np.float64]

class Catalog:
    """The module's methods and criteria, to which methods and criteria written in Python are
    added; `curve` and `pipeline` run them all as the built-ins run."""

    def __init__(self) -> None: ...
    def methods(self) -> list[Method]: ...
    def criteria(self) -> list[dict[str, str]]: ...
    def add_strategy(
        self,
        name: str,
        function: Any,
        summary: str | None = None,
        settings: Mapping[str, ParamValue] | None = None,
        docs: Mapping[str, str] | None = None,
        max_steps: int | None = None,
        paper: str | None = None,
    ) -> None:
        """Add a strategy: function(points, context: StrategyContext) -> proposed (n, d)
        points, or None when done. The framework clips every move to the constraints."""
    def add_criterion(self, name: str, function: Any, summary: str | None = None) -> None:
        """Add a criterion: function(curve: CurveSamples) -> float; it is in every report's
        criteria."""
    def curve(
        self,
        points: ArrayLike,
        method: str | None = None,
        kind: Kind | None = None,
        params: Mapping[str, ParamValue] | None = None,
        fixed: Sequence[int] | None = None,
        points_to_fix: Sequence[int] | None = None,
        tolerance: float | None = None,
        clamp_ends: Clamp | None = None,
        closed: bool = False,
        corners: Corners | None = None,
    ) -> FairedCurve:
        """Fair a curve with this catalogue's methods (the arguments of `fairspline.curve`)."""
    def inspect(self, points: ArrayLike, kind: Kind | None = None) -> dict[str, Any]:
        """Measure a curve, as `fairspline.inspect`, with this catalogue's criteria."""
    def pipeline(self, config: Union[Mapping[str, Any], str, os.PathLike[str]]) -> Pipeline:
        """A config pipeline over this catalogue: its stages may name Python methods."""
    def __contains__(self, name: str) -> bool: ...
