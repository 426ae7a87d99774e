"""Fair measured curves and surfaces from Python: the `fair` command's methods on NumPy arrays,
and a place to compose methods of your own.

    >>> import numpy as np, fairspline
    >>> x = np.linspace(0.0, 1.0, 41)
    >>> noisy = np.column_stack([x, np.sin(3 * x) + 1e-3 * np.cos(97 * x)])
    >>> result = fairspline.curve(noisy, method="smoothing-spline")
    >>> result.points.shape, result.report["method"]
    ((41, 2), 'smoothing-spline')

Every function does what the command does, bit for bit: `curve` is `fair curve`, `surface`
is `fair surface`, `inspect` is `fair inspect`, `methods` is `fair methods`, and `pipeline`
takes the config files `--config` takes; `export_cad` writes a result as an exact
B-spline into IGES, STEP or DXF (`fair curve -o FILE.igs`) and `read_cad` reads such files. Reports are dicts with exactly the fields of the
command's JSON report. Bad input raises ValueError with the framework's message; the GIL is
released while a curve is faired, so threads fair curves in parallel.

`Catalog()` holds the same methods and criteria; `add_strategy` adds a strategy written in
Python (a function that proposes moved points; the framework applies the constraints, runs the
pipeline and writes the report) and `add_criterion` a criterion written in Python, both then
run as the built-ins run (`catalog.curve`, `catalog.pipeline`).
"""

from ._native import (
    Catalog,
    FairedCurve,
    FairedSurface,
    Pipeline,
    __version__,
    curve,
    default_methods,
    export_cad,
    inspect,
    lines,
    methods,
    pipeline,
    read_cad,
    surface,
)

__all__ = [
    "Catalog",
    "FairedCurve",
    "FairedSurface",
    "Pipeline",
    "__version__",
    "curve",
    "default_methods",
    "export_cad",
    "inspect",
    "lines",
    "methods",
    "pipeline",
    "read_cad",
    "surface",
]
