"""Writes surface_smoothing_csaps.json: csaps's NdGridCubicSmoothingSpline on a 9 x 12 grid.

Run once (the test reads the JSON; CI has no Python):
    /work/peers/.venv/bin/python data/reference/surface_smoothing_csaps.py
"""
import json
import pathlib

import csaps
import numpy as np

rng = np.random.default_rng(19)
u = np.cumsum(np.concatenate([[0.0], rng.uniform(0.5, 1.5, 8)]))
v = np.cumsum(np.concatenate([[0.0], rng.uniform(0.3, 1.2, 11)]))
U, V = np.meshgrid(u, v, indexing="ij")
data = np.sin(0.6 * U) * np.cos(0.4 * V) + 0.05 * rng.standard_normal(U.shape)

cases = []
for smooth in ([0.6, 0.85], [0.95, 0.3], None):
    s = csaps.NdGridCubicSmoothingSpline([u, v], data, smooth=smooth)
    values = s([u, v])
    cases.append({
        "smooth": smooth,
        "p": [float(p) for p in s.smooth],
        "values": values.tolist(),
    })

out = {
    "source": f"csaps {csaps.__version__} NdGridCubicSmoothingSpline([u, v], data, smooth), "
              "evaluated at its own grid; smooth null = csaps's automatic rule per axis",
    "u": u.tolist(),
    "v": v.tolist(),
    "data": data.tolist(),
    "cases": cases,
}
path = pathlib.Path(__file__).with_suffix(".json")
path.write_text(json.dumps(out, indent=1))
print("wrote", path)
