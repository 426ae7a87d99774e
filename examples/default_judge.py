#!/usr/bin/env python3
"""Noisy curves with clean twins, a fixed tuning/test split, and the judge over them.

The generator (`cases`, `make`) draws every family of issue 44: a sine segment (even and
uneven spacing), NACA 0012 and 2415 upper surfaces (cosine spacing), a strophoid, a clothoid,
an arc (even and uneven), a closed ellipse, a 3D helix, a 3D (2,3) torus-knot segment, the
smoothed twins of three real airfoils' upper surfaces (R140, UA(2)-180, FX 63-137) and three
hull lines (Gunnerus waterlines 3 and 10, the Block Island sheer in plan) with added noise.
Each case is a clean curve, its noisy copy (Gaussian noise on every coordinate; for a
function y only) and the fairing's input kind. Noise is given in multiples of a family's base
σ (`BASE_SIGMA`, a fraction of the curve's bounding-box diagonal, or of the chord for
airfoils); sizes run from the table's own count (real data) or 40–400 points (analytic
families) to 10^4 (`--dense`); 10^6 is the speed peer's (`shared/peers/speed.py`).

The split is fixed here, before any tuning: TUNING draws use seeds 1000–1999, TEST draws
seeds 9000–9999 (one seed per case, derived from the case's index). A default is chosen on
the tuning set only; the test set is run once per candidate that was chosen, and reported
separately.

The runner fairs each noisy file with the `fair` command (`fair curve NOISY --kind K -o
FAIRED --report R [-m METHOD] [--set NAME=VALUE …]`) and judges it with
`compare_closed.py` (csaps and OpenCASCADE at our S_d; `--closed` for the ellipse), and
compares with csaps's own GCV choice (`gcv_rms`, cached per case). Per case: beats both (fewer vibrations than
both peers, no more inflections than either, no farther from the clean curve than the nearer),
beats csaps (the same against csaps alone), our RMS to the clean curve over csaps-GCV's, and
whether we end farther from the clean curve than the noisy input (and whether every peer
does too). Results go to a JSON-lines file; `--table` prints the summary per family and
noise level.

Usage:
  python examples/default_judge.py --split tuning|test --fair PATH/TO/fair --out DIR
      [--method M] [--set NAME=VALUE …] [--corners auto|none] [--peers DIR] [--jobs 2] [--dense] [--only FAMILY,…]
  python examples/default_judge.py --table DIR/results.jsonl [DIR2/results.jsonl …]
"""
import argparse
import json
import math
import os
import subprocess
import sys
import threading
from concurrent.futures import ThreadPoolExecutor

import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "data")

TUNING_SEEDS = range(1000, 2000)
TEST_SEEDS = range(9000, 10000)
TUNING_NOISE = [0.25, 0.5, 1.0, 2.0, 4.0]
TEST_NOISE = [0.5, 1.0, 2.0]
DRAWS = {"tuning": 2, "test": 4}

# Base noise σ of each family at 1×, as a fraction of the bounding-box diagonal (airfoils: of
# the chord, which is their diagonal within 1 %).
BASE_SIGMA = {
    "sine": 0.004, "sine-uneven": 0.004, "naca0012": 0.001, "naca2415": 0.001,
    "strophoid": 0.004, "clothoid": 0.004, "arc": 0.004, "arc-uneven": 0.004,
    "ellipse": 0.004, "helix": 0.004, "torus-knot": 0.004,
    "r140": 0.001, "ua2-180": 0.001, "fx63137": 0.001,
    "gunnerus-wl03": 0.002, "gunnerus-wl10": 0.002, "block-island-sheer": 0.002,
    "sine-dense": 0.004,
}

# (family, kind, closed, sizes): analytic families draw one of the sizes per case; real data
# keep their own count (None).
FAMILIES = [
    ("sine", "function", False, [50, 100, 200]),
    ("sine-uneven", "function", False, [60, 150]),
    ("naca0012", "function", False, [40, 80, 160]),
    ("naca2415", "function", False, [40, 80, 160]),
    ("strophoid", "parametric", False, [60, 120, 240]),
    ("clothoid", "parametric", False, [60, 120, 240]),
    ("arc", "parametric", False, [30, 60, 120]),
    ("arc-uneven", "parametric", False, [40, 100]),
    ("ellipse", "parametric", True, [40, 80, 160]),
    ("helix", "parametric", False, [100, 200, 400]),
    ("torus-knot", "parametric", False, [100, 200, 400]),
    ("r140", "function", False, None),
    ("ua2-180", "function", False, None),
    ("fx63137", "function", False, None),
    ("gunnerus-wl03", "function", False, None),
    ("gunnerus-wl10", "function", False, None),
    ("block-island-sheer", "function", False, None),
]
DENSE = [("sine-dense", "function", False, [1000, 3000, 10000])]

REAL = {
    "r140": "airfoil_r140/r140sm_upper.csv",
    "ua2-180": "airfoil_ua2-180/ua2-180sm_upper.csv",
    "fx63137": "airfoil_fx63137/fx63137sm_upper.csv",
    "gunnerus-wl03": "hull_gunnerus/waterlines/wl_03.csv",
    "gunnerus-wl10": "hull_gunnerus/waterlines/wl_10.csv",
    "block-island-sheer": "hull_block_island_boat/sheer_plan.csv",
}


def cases(split, dense=False):
    """Every case of a split: dicts with name, family, kind, closed, noise, seed, n."""
    seeds = iter(TUNING_SEEDS if split == "tuning" else TEST_SEEDS)
    noises = TUNING_NOISE if split == "tuning" else TEST_NOISE
    out = []
    for family, kind, closed, sizes in FAMILIES + (DENSE if dense else []):
        for noise in noises:
            for draw in range(DRAWS[split]):
                seed = next(seeds)
                rng = np.random.default_rng(seed)
                n = int(rng.choice(sizes)) if sizes else None
                out.append(dict(name=f"{family}_{noise:g}x_{seed}", family=family, kind=kind,
                                closed=closed, noise=noise, seed=seed, n=n))
    return out


def naca_upper(x, m, p, t):
    """NACA 4-digit upper surface (closed trailing edge) at chord stations x."""
    yt = 5 * t * (0.2969 * np.sqrt(x) - 0.1260 * x - 0.3516 * x**2 + 0.2843 * x**3
                  - 0.1036 * x**4)
    if m == 0:
        return x, yt
    yc = np.where(x < p, m / p**2 * (2 * p * x - x**2),
                  m / (1 - p)**2 * ((1 - 2 * p) + 2 * p * x - x**2))
    dyc = np.where(x < p, 2 * m / p**2 * (p - x), 2 * m / (1 - p)**2 * (p - x))
    th = np.arctan(dyc)
    return x - yt * np.sin(th), yc + yt * np.cos(th)


def uneven(rng, n, lo, hi):
    """n increasing parameters from lo to hi with spacings uniform in a ratio of 3."""
    h = rng.uniform(0.5, 1.5, n - 1)
    return lo + (hi - lo) * np.r_[0.0, np.cumsum(h)] / h.sum()


def clean_curve(case, rng):
    f, n = case["family"], case["n"]
    if f in ("sine", "sine-dense"):
        x = np.linspace(0, 4 * np.pi, n)
        return np.c_[x, np.sin(x)]
    if f == "sine-uneven":
        x = uneven(rng, n, 0, 4 * np.pi)
        return np.c_[x, np.sin(x)]
    if f in ("naca0012", "naca2415"):
        beta = np.linspace(0, np.pi, n)
        x = 0.5 * (1 - np.cos(beta))
        xu, yu = naca_upper(x, 0.0, 0.4, 0.12) if f == "naca0012" else naca_upper(x, 0.02, 0.4, 0.15)
        # The cambered surface's x turns back just behind the nose: a function keeps the
        # stations where x increases strictly.
        keep = np.r_[True, xu[1:] > np.maximum.accumulate(xu)[:-1]]
        return np.c_[xu[keep], yu[keep]]
    if f == "strophoid":
        t = np.linspace(-1.8, 1.8, n)
        return np.c_[(t**2 - 1) / (t**2 + 1), t * (t**2 - 1) / (t**2 + 1)]
    if f == "clothoid":
        from scipy.special import fresnel
        s, c = fresnel(np.linspace(0, 2.2, n))
        return np.c_[c, s]
    if f == "arc":
        t = np.linspace(0, 2 * np.pi / 3, n)
        return np.c_[np.cos(t), np.sin(t)]
    if f == "arc-uneven":
        t = uneven(rng, n, 0, 2 * np.pi / 3)
        return np.c_[np.cos(t), np.sin(t)]
    if f == "ellipse":
        t = np.linspace(0, 2 * np.pi, n, endpoint=False)
        return np.c_[2 * np.cos(t), np.sin(t)]
    if f == "helix":
        t = np.linspace(0, 4 * np.pi, n)
        return np.c_[np.cos(t), np.sin(t), 0.15 * t]
    if f == "torus-knot":
        t = np.linspace(0, np.pi, n)
        r = 2 + np.cos(3 * t)
        return np.c_[r * np.cos(2 * t), r * np.sin(2 * t), np.sin(3 * t)]
    data = np.loadtxt(os.path.join(DATA, REAL[f]), delimiter=",", skiprows=1)
    return data[:, :2]


def make(case):
    """(clean, noisy) point arrays of a case; closed curves carry their first point again."""
    rng = np.random.default_rng(case["seed"])
    clean = clean_curve(case, rng)
    diag = float(np.linalg.norm(clean.max(0) - clean.min(0)))
    sigma = BASE_SIGMA[case["family"]] * case["noise"] * diag
    noisy = clean.copy()
    if case["kind"] == "function":
        noisy[:, 1] += rng.normal(0, sigma, len(clean))
    else:
        noisy += rng.normal(0, sigma, clean.shape)
    if case["closed"]:
        clean, noisy = np.r_[clean, clean[:1]], np.r_[noisy, noisy[:1]]
    return clean, noisy, sigma


def write(path, pts):
    header = "x,y,z" if pts.shape[1] == 3 else "x,y"
    np.savetxt(path, pts, delimiter=",", header=header, comments="", fmt="%.17g")


def judge_one(case, a, folder):
    clean, noisy, sigma = make(case)
    f = lambda s: os.path.join(folder, f"{case['name']}_{s}")  # noqa: E731
    write(f("clean.csv"), clean)
    write(f("noisy.csv"), noisy)
    cmd = [a.fair, "curve", f("noisy.csv"), "--kind", case["kind"], "-o", f("faired.csv"),
           "--report", f("report.json"), "-q"]
    if a.method:
        cmd += ["-m", a.method]
    for s in a.set or []:
        cmd += ["--set", s]
    if a.corners:
        cmd += ["--corners", a.corners]
    row = dict(case, sigma=sigma, n=len(noisy) - case["closed"])
    if a.reuse and os.path.exists(f("faired.csv")):
        run = subprocess.CompletedProcess(cmd, 0, "", "")
    else:
        run = subprocess.run(cmd, capture_output=True, text=True)
    if run.returncode != 0:
        row["refused"] = run.stderr.strip()[-300:]
        return row
    try:
        rep = json.load(open(f("report.json")))
        row["report"] = {k: rep.get(k) for k in ("warnings", "corners")}
        row["strategy"] = rep.get("strategy") or rep.get("stages")
    except Exception:  # noqa: BLE001 - the report is extra information
        pass
    if a.quick:
        row.update(quick(case, row, f, a))
        return row
    jcmd = [a.python, os.path.join(a.peers, "compare_closed.py"), f("noisy.csv"), f("faired.csv"),
            "--kind", case["kind"], "--clean", f("clean.csv")]
    if case["closed"]:
        jcmd.append("--closed")
    j = subprocess.run(jcmd, capture_output=True, text=True, cwd=a.peers)
    try:
        r = json.loads(j.stdout)
    except json.JSONDecodeError:
        # the judge fails as a whole where OpenCASCADE's curve at our S_d has coincident
        # points (its curve shorter than the data, several points projected to its end, which
        # metrics.py refuses): csaps is judged alone then, and the case is not a win over both
        row["judge_error"] = (j.stderr or j.stdout).strip()[-300:]
        try:
            r = csaps_only(case, a, f)
        except Exception:  # noqa: BLE001 - then the case stays unjudged
            return row
        row["occt_failed"] = True
    if "error" in r:
        row["judge_error"] = r["error"]
        return row
    row.update(verdict(r))
    row["rms_gcv"] = gcv_rms(case, a, f)
    row["raw"] = r
    return row


def csaps_only(case, a, f):
    """compare_closed.py's result without OpenCASCADE: csaps at our S_d, the same metrics and
    distances, from the judge's own functions."""
    m = peers_module(a)
    orig = m.coords(*m.read_points(f("noisy.csv")))
    fair = m.coords(*m.read_points(f("faired.csv")))
    clean = m.coords(*m.read_points(f("clean.csv")))
    if case["closed"]:
        orig, fair, clean = orig[:-1], fair[:-1], clean[:-1]
        met = lambda P: m.counts(m.closed_metrics(P), "parametric")  # noqa: E731
        rc = lambda P: m.closed_rms_to_curve(P, clean)  # noqa: E731
    else:
        met = lambda P: m.counts(m.metrics(P, case["kind"]), case["kind"])  # noqa: E731
        key = "rms_pointwise" if case["kind"] == "function" else "rms_to_curve"
        rc = lambda P: m.rms_to_clean(P, clean, case["kind"])[key]  # noqa: E731
    disp = m.displacement(orig, fair)
    if case["closed"]:
        _, out, _ = m.bisect_p(orig, disp["S_d"], m.csaps_closed)
    else:
        _, out, _ = m.mst_matching(orig, disp["S_d"], case["kind"])
    return {"original": met(orig), "ours": {**met(fair), **disp},
            "mst": {**met(out), **m.displacement(orig, out)}, "clean": met(clean),
            "rms_to_clean": {"original": rc(orig), "ours": rc(fair), "mst": rc(out)}}


_PEERS = None
_CACHE_LOCK = threading.Lock()


def peers_module(a):
    """compare_closed.py imported (its metrics, GCV fit and distances), once."""
    global _PEERS
    if _PEERS is None:
        sys.path.insert(0, a.peers)
        import compare_closed
        _PEERS = compare_closed
    return _PEERS


def gcv_rms(case, a, f):
    """RMS to the clean curve of the cubic smoothing spline with GCV's own p. It does not
    depend on our result, so it is cached per case in OUT/../gcv_cache.json. Open curves:
    `fair curve -m smoothing-spline --set rule=gcv` (csaps's objective, MATLAB's p, the exact
    GCV minimum by the O(n) Reinsch form); closed curves: compare_closed.py's periodic csaps
    with its dense GCV (the smoothing spline is open)."""
    path = os.path.join(os.path.dirname(os.path.abspath(a.out)), "gcv_cache.json")
    with _CACHE_LOCK:
        cache = read_cache(path)
    if case["name"] in cache:
        return cache[case["name"]]
    m = peers_module(a)
    orig = m.coords(*m.read_points(f("noisy.csv")))
    clean = m.coords(*m.read_points(f("clean.csv")))
    if case["closed"]:
        orig, clean = orig[:-1], clean[:-1]
        _, fit = m.gcv_fit(orig, case["kind"], case["closed"])
    else:
        run = subprocess.run([a.fair, "curve", f("noisy.csv"), "--kind", case["kind"], "-m",
                              "smoothing-spline", "--set", "rule=gcv", "-o", f("gcv.csv"), "-q"],
                             capture_output=True, text=True)
        if run.returncode != 0:
            return None
        fit = m.coords(*m.read_points(f("gcv.csv")))
    value = rms_of(m, fit, clean, case)
    with _CACHE_LOCK:
        cache = read_cache(path)
        cache[case["name"]] = value
        tmp = f"{path}.{os.getpid()}"
        with open(tmp, "w") as fh:
            json.dump(cache, fh)
        os.replace(tmp, path)  # atomic: runs of both splits may share the cache
    return value


def read_cache(path):
    try:
        with open(path) as fh:
            return json.load(fh)
    except (OSError, json.JSONDecodeError):
        return {}


def rms_of(m, pts, clean, case):
    if case["closed"]:
        return float(m.closed_rms_to_curve(pts, clean))
    key = "rms_pointwise" if case["kind"] == "function" else "rms_to_curve"
    return float(m.rms_to_clean(pts, clean, case["kind"])[key])


def quick(case, row, f, a):
    """Our result against the clean curve and csaps-GCV only (no peers at our S_d): the
    tuning loop's measure."""
    m = peers_module(a)
    orig = m.coords(*m.read_points(f("noisy.csv")))
    fair = m.coords(*m.read_points(f("faired.csv")))
    clean = m.coords(*m.read_points(f("clean.csv")))
    out = {}
    if case["closed"]:
        out["seam_gap"] = float(np.linalg.norm(fair[0] - fair[-1]))
        orig, fair, clean = orig[:-1], fair[:-1], clean[:-1]
        met = lambda P: m.counts(m.closed_metrics(P), "parametric")  # noqa: E731
    else:
        met = lambda P: m.counts(m.metrics(P, case["kind"]), case["kind"])  # noqa: E731
    if fair.shape != orig.shape or not np.all(np.isfinite(fair)):
        return dict(judge_error="faired shape or values")
    out.update(rms_ours=rms_of(m, fair, clean, case), rms_input=rms_of(m, orig, clean, case),
               rms_gcv=gcv_rms(case, a, f) if row["n"] <= 600 or not case["closed"] else None,
               infl=[met(orig)["inflections"], met(fair)["inflections"],
                     met(clean)["inflections"]],
               sd_ours=float(m.displacement(orig, fair)["S_d"]))
    out["worse_than_input"] = out["rms_ours"] > out["rms_input"]
    return out


def verdict(r):
    peers = [p for p in ("mst", "occt") if p in r]
    rms = r["rms_to_clean"]
    beats = {}
    for p in peers:
        beats[p] = (r["ours"]["vibrations"] < r[p]["vibrations"]
                    and r["ours"]["inflections"] <= r[p]["inflections"]
                    and rms["ours"] <= rms[p] * (1 + 1e-9))
    out = dict(beats_both=all(beats.values()) and len(peers) == 2,
               beats_csaps=beats.get("mst", False),
               rms_ours=rms["ours"], rms_input=rms["original"], rms_mst=rms["mst"],
               rms_occt=rms.get("occt"), rms_gcv=rms.get("gcv"),
               sd_ours=r["ours"]["S_d"], sd_gcv=r.get("gcv", {}).get("S_d"),
               infl=[r["original"]["inflections"], r["ours"]["inflections"],
                     r["clean"]["inflections"]],
               worse_than_input=rms["ours"] > rms["original"],
               every_peer_worse=all(rms[p] > rms["original"] for p in peers))
    return out


def run(a):
    os.makedirs(a.out, exist_ok=True)
    folder = os.path.join(a.out, "cases")
    os.makedirs(folder, exist_ok=True)
    todo = cases(a.split, a.dense)
    if a.only:
        todo = [c for c in todo if c["family"] in a.only.split(",")]
    peers_module(a)  # imported once, before the threads (OCP's import is not thread-safe)
    path = os.path.join(a.out, "results.jsonl")
    with open(path, "w") as fh, ThreadPoolExecutor(a.jobs) as pool:
        for k, row in enumerate(pool.map(lambda c: judge_one(c, a, folder), todo)):
            fh.write(json.dumps(row) + "\n")
            fh.flush()
            print(f"{k + 1}/{len(todo)} {row['name']} both={row.get('beats_both')} "
                  f"csaps={row.get('beats_csaps')} {row.get('refused', '')[:80]}"
                  f"{row.get('judge_error', '')[:80]}", file=sys.stderr)
    table([path])


def gmean(v):
    v = [x for x in v if x and x > 0]
    return math.exp(sum(map(math.log, v)) / len(v)) if v else float("nan")


def summary(rows):
    judged = [r for r in rows if "rms_ours" in r]
    gcv = [r["rms_ours"] / r["rms_gcv"] for r in judged if r.get("rms_gcv")]
    return dict(
        cases=len(rows), refused=sum("refused" in r for r in rows),
        both=sum(r.get("beats_both", False) for r in judged),
        csaps=sum(r.get("beats_csaps", False) for r in judged),
        infl=sum(r["infl"][1] > 2 * max(r["infl"][2], 1) for r in judged),
        occt_failed=sum(r.get("occt_failed", False) for r in rows),
        vs_gcv=float(np.median(gcv)) if gcv else float("nan"),
        vs_input=gmean([r["rms_ours"] / r["rms_input"] for r in judged]),
        worse=sum(r["worse_than_input"] and not r.get("every_peer_worse", False)
                  for r in judged))


def fmt(s):
    return (f"| {s['cases']} | {s['refused']} | {s['both']} | {s['csaps']} | "
            f"{s['vs_gcv']:.3f} | {s['vs_input']:.3f} | {s['worse']} | {s['infl']} | "
            f"{s['occt_failed']} |")


def table(paths):
    for path in paths:
        rows = [json.loads(line) for line in open(path)]
        print(f"\n{path}\n")
        print("| family | noise | cases | refused | beats both | beats csaps | median RMS / "
              "csaps-GCV | RMS / input (geo. mean) | farther than input (peers not) | "
              "> 2× clean inflections | OpenCASCADE failed (csaps alone) |")
        print("|---|---|---|---|---|---|---|---|---|---|---|")
        fams = list(dict.fromkeys(r["family"] for r in rows))
        for fam in fams:
            fr = [r for r in rows if r["family"] == fam]
            for noise in sorted({r["noise"] for r in fr}):
                print(f"| {fam} | {noise:g}× " + fmt(summary([r for r in fr if r["noise"] == noise])))
            print(f"| **{fam}** | all " + fmt(summary(fr)))
        for noise in sorted({r["noise"] for r in rows}):
            print(f"| all | {noise:g}× " + fmt(summary([r for r in rows if r["noise"] == noise])))
        print("| **all** | all " + fmt(summary(rows)))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--split", choices=["tuning", "test"])
    ap.add_argument("--fair", default=os.path.join(ROOT, "target", "release", "fair"))
    ap.add_argument("--out")
    ap.add_argument("--method")
    ap.add_argument("--set", action="append")
    ap.add_argument("--corners", help="the command's --corners (auto, none or indices)")
    ap.add_argument("--peers", default=os.environ.get("FAIR_PEERS", "/work/shared/peers"))
    ap.add_argument("--python", default=sys.executable)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--dense", action="store_true", help="add the 10^3–10^4-point sines")
    ap.add_argument("--only", help="comma-separated families")
    ap.add_argument("--quick", action="store_true",
                    help="judge against the clean curve and csaps-GCV only (tuning)")
    ap.add_argument("--reuse", action="store_true",
                    help="judge the faired files already in OUT/cases instead of fairing again")
    ap.add_argument("--table", nargs="*", help="print the tables of these results files")
    a = ap.parse_args()
    if a.table:
        table(a.table)
        return
    if not (a.split and a.out):
        ap.error("--split and --out are required to run")
    run(a)


if __name__ == "__main__":
    main()
