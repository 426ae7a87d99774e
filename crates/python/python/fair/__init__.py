"""Fair measured curves and surfaces from Python: the `fair` command's methods on NumPy arrays.

    >>> import numpy as np, fair
    >>> x = np.linspace(0.0, 1.0, 41)
    >>> noisy = np.column_stack([x, np.sin(3 * x) + 1e-3 * np.cos(97 * x)])
    >>> result = fair.curve(noisy, method="smoothing-spline")
    >>> result.points.shape, result.report["method"]
    ((41, 2), 'smoothing-spline')

Every function does what the command does, bit for bit: `curve` is `fair curve`, `surface`
is `fair surface`, `inspect` is `fair inspect`, `methods` is `fair methods`, and `pipeline`
takes the config files `--config` takes; `export_cad` writes a result as an exact
B-spline into IGES, STEP or DXF (`fair curve -o FILE.igs`) and `read_cad` reads such files. Reports are dicts with exactly the fields of the
command's JSON report. Bad input raises ValueError with the framework's message; the GIL is
released while a curve is faired, so threads fair curves in parallel.
"""

from ._native import (
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
