# %% [markdown]
# # Prototype a fairing method in NumPy, judge it against the built-ins
#
# A notebook in plain Python (`# %%` cells: VS Code, Jupytext and Spyder run them one by one;
# `python examples/python/prototype_method.py` runs them all). It needs the package
# (`pip install ./crates/python`) and NumPy, nothing else.
#
# 1. A test set: noisy curves with their clean twins (fixed seeds).
# 2. A method prototyped in NumPy: Laplacian smoothing, one step at a time.
# 3. The method and a criterion registered in a `fairspline.Catalog`: the framework holds the
#    constraints (ends fixed, a tolerance band), runs the steps and writes the report.
# 4. The judgement: every method on every case, RMS distance to the clean twin, inflections
#    against the clean twin's, and the Python criterion from the report.

# %%
import numpy as np

import fairspline

N = 61
SIGMA = 2e-3  # the noise's standard deviation
TOLERANCE = 3 * SIGMA  # the band every method is held to
SEEDS = (101, 102, 103)


def shapes():
    """Clean curves: three functions y(x) and a parametric arc (x not monotone)."""
    x = np.linspace(0.0, 1.0, N)
    yield "sine", "function", np.column_stack([x, 0.2 * np.sin(3 * np.pi * x)])
    yield "bump", "function", np.column_stack([x, 0.3 * np.exp(-30 * (x - 0.5) ** 2)])
    u = np.linspace(-1.0, 1.0, N)
    yield "cubic", "function", np.column_stack([u, 0.3 * (u**3 - 0.6 * u)])
    t = np.linspace(0.0, np.pi, N)
    yield "arc", "parametric", np.column_stack([0.5 * np.cos(t), 0.3 * np.sin(t)])


def test_set():
    """Each shape with Gaussian noise on y (functions) or on both coordinates (the arc)."""
    cases = []
    for name, kind, clean in shapes():
        for seed in SEEDS:
            rng = np.random.default_rng(seed)
            noise = SIGMA * rng.standard_normal(clean.shape)
            if kind == "function":
                noise[:, 0] = 0.0
            cases.append((f"{name}/{seed}", kind, clean, clean + noise))
    return cases


CASES = test_set()
print(f"{len(CASES)} cases, n = {N}, sigma = {SIGMA}, tolerance = {TOLERANCE}")

# %% [markdown]
# ## The prototype, in NumPy
#
# One step of Laplacian smoothing moves every interior point a fraction of the way to its
# neighbours' midpoint. The function gets the current points and a context (the fixed points,
# the band, its settings, the step) and proposes new points; it does not enforce anything.


def laplacian(points, context):
    """Laplacian smoothing: every point a fraction of the way to its neighbours' midpoint."""
    if context.step >= context.settings["passes"]:
        return None  # done
    proposed = points.copy()
    midpoints = 0.5 * (points[:-2] + points[2:])
    proposed[1:-1] += context.settings["factor"] * (midpoints - points[1:-1])
    return proposed


def curvature_variation(curve):
    """Total variation of the signed curvature along the curve (sampled)."""
    d1, d2 = curve.d1, curve.d2
    kappa = (d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0]) / np.linalg.norm(d1, axis=1) ** 3
    return float(np.abs(np.diff(kappa)).sum())


# %% [markdown]
# ## Registered: the framework runs it
#
# `settings` declares the parameters and their defaults (chosen before looking at the test
# set, not tuned on it); `params=` and config stages set them, typed and checked as a built-in
# method's are. The criterion is then in every report's `criteria`, built-ins' included.

# %%
catalog = fairspline.Catalog()
catalog.add_strategy(
    "laplacian",
    laplacian,
    settings={"factor": 0.5, "passes": 10},
    docs={"factor": "how far towards the neighbours' midpoint per pass", "passes": "passes at most"},
)
catalog.add_criterion("curvature-variation", curvature_variation)
(entry,) = [m for m in catalog.methods() if m["name"] == "laplacian"]
for p in entry["parameters"]:
    print(f"laplacian {p['name']}={p['default']}  {p['meaning']}")

# %% [markdown]
# ## Judged against the built-ins
#
# Every method under the same constraints: both ends fixed, no point farther than the band.
# RMS is the distance of the faired points to the clean twin's (the input's RMS for scale);
# "infl" counts the curvature's sign changes after fairing, against the clean twin's count.

# %%
METHODS = [
    ("jump-lsq", lambda pts, kind, constraints: catalog.curve(pts, method="jump-lsq", kind=kind, **constraints)),
    ("smoothing-spline", lambda pts, kind, c: catalog.curve(pts, method="smoothing-spline", kind=kind, **c)),
    ("two-phase", lambda pts, kind, c: catalog.curve(pts, method="two-phase", kind=kind, **c)),
    ("laplacian", lambda pts, kind, c: catalog.curve(pts, method="laplacian", kind=kind, **c)),
    (
        "smoothing-spline+laplacian",
        lambda pts, kind, c: catalog.pipeline(
            {"stage": [{"method": "smoothing-spline"}, {"method": "laplacian", "passes": 3}]}
        ).curve(pts, kind=kind, **c),
    ),
]


def rms(a, b):
    return float(np.sqrt(np.mean(np.sum((a - b) ** 2, axis=1))))


rows = {name: {"rms": [], "infl_off": [], "cv": [], "refused": 0} for name, _ in METHODS}
rows["clean twin"] = {"rms": [], "infl_off": [], "cv": [], "refused": 0}
input_rms = []
for case, kind, clean, noisy in CASES:
    constraints = {"fixed": [0, N - 1], "tolerance": TOLERANCE}
    clean_report = catalog.inspect(clean, kind=kind)["before"]
    clean_inflections = clean_report["inflections"]
    rows["clean twin"]["cv"].append(clean_report["criteria"]["curvature-variation"])
    input_rms.append(rms(noisy, clean))
    for name, run in METHODS:
        try:
            result = run(noisy, kind, constraints)
        except ValueError as refused:
            rows[name]["refused"] += 1
            print(f"{case}: {name} refused: {refused}")
            continue
        moves = np.linalg.norm(result.points - noisy, axis=1)
        assert moves.max() <= TOLERANCE and result.points[[0, -1]].tobytes() == noisy[[0, -1]].tobytes()
        after = result.report["after"]
        rows[name]["rms"].append(rms(result.points, clean))
        rows[name]["infl_off"].append(abs(after["inflections"] - clean_inflections))
        rows[name]["cv"].append(after["criteria"]["curvature-variation"])

print(f"input: mean RMS to clean {np.mean(input_rms):.3e}")
print(f"{'method':28} {'mean RMS':>10} {'worst RMS':>10} {'|infl - clean|':>15} {'curv. variation':>16}")
for name, row in rows.items():
    if not row["rms"]:
        print(f"{name:28} {'':10} {'':10} {'':15} {np.median(row['cv']):16.3e}")
        continue
    print(
        f"{name:28} {np.mean(row['rms']):10.3e} {np.max(row['rms']):10.3e} "
        f"{np.mean(row['infl_off']):15.2f} {np.median(row['cv']):16.3e}"
        + (f"  ({row['refused']} refused)" if row["refused"] else "")
    )
