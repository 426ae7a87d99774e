#!/usr/bin/env python3
"""Noisy nets with clean twins for judging surface fairing (issue 46): `python nets.py SPLIT
OUT_DIR` (SPLIT: tuning, test, fresh-tuning, fresh-test, final-test, last-test, next-test) or
`python nets.py --draws D1,D2,... OUT_DIR`.

Families: bump (panels with Gaussian bumps), helicoid (helicoidal strips), height60 (60 x 60
height fields), tube (closed in v), wigley (Wigley hull halves), aniso (height fields on
anisotropic, uneven spacing), teapot (bicubic Bezier patches of the Utah teapot body, the
project's data/surface_utah_teapot), gunnerus (patches of the R/V Gunnerus hull's body and bow,
waterlines 1-8 over 24-37 consecutive stations of stations 23-59 of the project's
data/hull_gunnerus table: a real hull, whose clean twin keeps the table's own ripple; aft of
station 23 the hull steps (half-breadths jump by up to 2.2 m between adjacent stations at the
transom and skeg), which bounds the patch as a knuckle bounds a lines plan's regions). Noise:
isotropic Gaussian, sigma = LEVEL x 0.002 x the bounding-box diagonal, LEVEL in 0.5, 1, 2; the
repeated seam line copied from the first.

The split is fixed here, before any tuning: TUNING draws use seeds 1000 + k, TEST draws
5000 + k; a draw's seed sets both the shape's parameters and the noise. After the test draws
had been looked at while tuning, they joined the tuning data with two fresh draws
(FRESH_TUNING_DRAWS), and a fresh test split (FRESH_TEST_DRAWS) was fixed before that tuning.
After that split had been run, every draw above became tuning data and FINAL_TEST_DRAWS were
fixed before the next tuning (the penalty's difference order). The gunnerus family came after
all of those had been run: its draws 1000-1002 are its tuning data, and LAST_TEST_DRAWS, fixed
with it and run once, is every family's next test split. NEXT_TEST_DRAWS were fixed before the
limit's margin was chosen again on the refined spectrum (tuning: draws 1000-1002).
A net is a function of its family, level and draw alone, so every split's nets are the same
whichever split (or --draws list) writes them.
"""
import os
import sys
import numpy as np

FAMILIES = ["bump", "helicoid", "height60", "tube", "wigley", "aniso", "teapot", "gunnerus"]
LEVELS = [0.5, 1.0, 2.0]
BASE = 0.002
TUNING_DRAWS = [1000]
TEST_DRAWS = [5000, 5001, 5002]
FRESH_TUNING_DRAWS = [1001, 1002]
FRESH_TEST_DRAWS = [7000, 7001, 7002]
FINAL_TEST_DRAWS = [8000, 8001, 8002]
LAST_TEST_DRAWS = [9000, 9001, 9002]
NEXT_TEST_DRAWS = [9500, 9501, 9502]
SPLITS = {"tuning": TUNING_DRAWS, "test": TEST_DRAWS,
          "fresh-tuning": FRESH_TUNING_DRAWS, "fresh-test": FRESH_TEST_DRAWS,
          "final-test": FINAL_TEST_DRAWS, "last-test": LAST_TEST_DRAWS,
          "next-test": NEXT_TEST_DRAWS}
HERE = os.path.dirname(os.path.abspath(__file__))
GUNNERUS = os.environ.get("GUNNERUS", os.path.join(HERE, "..", "..", "data", "hull_gunnerus", "offsets_m.csv"))
TEAPOT = os.environ.get("TEAPOT", os.path.join(HERE, "..", "..", "data", "surface_utah_teapot", "teapot_patches.csv"))


def bump(r):
    m, n = 40, 40
    x, y = np.meshgrid(np.linspace(0, 1, m), np.linspace(0, 1, n), indexing="ij")
    z = np.zeros_like(x)
    for _ in range(r.integers(1, 4)):
        cx, cy = r.uniform(0.25, 0.75, 2)
        s = r.uniform(0.12, 0.25)
        z += r.uniform(0.1, 0.3) * np.exp(-((x - cx) ** 2 + (y - cy) ** 2) / (2 * s * s))
    return np.stack([x, y, z], -1)


def helicoid(r):
    m, n = 20, 60
    turns = r.uniform(0.5, 1.2)
    rr, t = np.meshgrid(np.linspace(r.uniform(0.2, 0.6), 1.5, m),
                        np.linspace(0, 2 * np.pi * turns, n), indexing="ij")
    c = r.uniform(0.2, 0.5)
    return np.stack([rr * np.cos(t), rr * np.sin(t), c * t], -1)


def height60(r):
    m = n = 60
    x, y = np.meshgrid(np.linspace(0, 1, m), np.linspace(0, 1, n), indexing="ij")
    z = np.zeros_like(x)
    for _ in range(3):
        a, b = r.uniform(0.5, 3.0, 2) * np.pi
        ph = r.uniform(0, 2 * np.pi)
        z += r.uniform(0.03, 0.1) * np.sin(a * x + b * y + ph)
    return np.stack([x, y, z], -1)


def tube(r):
    m, n = 30, 33  # n - 1 = 32 distinct around, last column repeats the first
    s = np.linspace(0, 1, m)
    th = np.linspace(0, 2 * np.pi, n)
    th[-1] = 0.0
    k = r.uniform(0.5, 1.5)
    amp = r.uniform(0.05, 0.2)
    rad = 0.3 + amp * np.sin(np.pi * k * s)[:, None] * np.ones(n)[None]
    bend = r.uniform(0.1, 0.4)
    S, T = np.meshgrid(s, th, indexing="ij")
    x = 3 * S
    y = bend * np.sin(np.pi * S) + rad * np.cos(T)
    z = rad * np.sin(T)
    G = np.stack([x, y, z], -1)
    G[:, -1] = G[:, 0]
    return G


def wigley(r):
    L, B, T = 1.0, r.uniform(0.08, 0.12), r.uniform(0.05, 0.08)
    m, n = 41, 16
    x, z = np.meshgrid(np.linspace(-L / 2, L / 2, m), np.linspace(0, T, n), indexing="ij")
    y = B / 2 * (1 - (2 * x / L) ** 2) * (1 - (z / T) ** 2)
    return np.stack([x, y, z], -1)


def aniso(r):
    m, n = 30, 50
    u = np.linspace(0, 1, m) ** r.uniform(1.3, 2.0)
    v = np.linspace(0, 1, n)
    v = v + 0.3 * np.sin(2 * np.pi * v) / (2 * np.pi)
    x, y = np.meshgrid(3 * u, v, indexing="ij")
    a, b = r.uniform(0.5, 1.5, 2)
    z = 0.2 * np.sin(a * x + 0.5) * np.cos(b * np.pi * y) + 0.05 * x * y
    return np.stack([x, y, z], -1)


def bezier(Pc, s, t):
    bs = lambda u: np.stack([(1 - u) ** 3, 3 * u * (1 - u) ** 2, 3 * u * u * (1 - u), u ** 3], -1)
    Bu, Bv = bs(s), bs(t)
    return np.einsum("ia,jb,abk->ijk", Bu, Bv, Pc)


def teapot(r):
    d = np.loadtxt(TEAPOT, delimiter=",", skiprows=1)
    patches = sorted(set(d[:, 0].astype(int)))
    p = patches[r.integers(0, min(len(patches), 16))]  # rim and body patches
    q = d[d[:, 0] == p]
    Pc = np.zeros((4, 4, 3))
    Pc[q[:, 1].astype(int), q[:, 2].astype(int)] = q[:, 3:6]
    m = n = 24
    return bezier(Pc, np.linspace(0, 1, m), np.linspace(0, 1, n))


def gunnerus(r):
    d = np.loadtxt(GUNNERUS, delimiter=",", skiprows=1)
    grid = np.full((16, 64, 3), np.nan)
    grid[d[:, 0].astype(int), d[:, 1].astype(int)] = d[:, 2:5]
    body = grid[1:9, 23:60]  # waterlines 1-8, from the stern's step to the bow
    length = int(r.integers(24, 38))
    start = int(r.integers(0, body.shape[1] - length + 1))
    G = body[:, start:start + length]
    assert np.isfinite(G).all()
    return G


def diag(G):
    P = G.reshape(-1, 3)
    return float(np.linalg.norm(P.max(0) - P.min(0)))


def make(family, level, seed):
    r = np.random.default_rng(seed)
    clean = globals()[family](r)
    sigma = level * BASE * diag(clean)
    noisy = clean + r.normal(0.0, sigma, clean.shape)
    if family == "tube":
        noisy[:, -1] = noisy[:, 0]
    return clean, noisy


def write(path, G):
    m, n, _ = G.shape
    with open(path, "w") as f:
        f.write("i,j,x,y,z\n")
        for i in range(m):
            for j in range(n):
                f.write("%d,%d,%.17g,%.17g,%.17g\n" % (i, j, *G[i, j]))


def cases(split):
    draws = split if isinstance(split, list) else SPLITS[split]
    for fam in FAMILIES:
        for level in LEVELS:
            for d in draws:
                seed = d * 100 + FAMILIES.index(fam) * 10 + LEVELS.index(level)
                yield f"{fam}_{level:g}_{d}", fam, level, seed


if __name__ == "__main__":
    if sys.argv[1] == "--draws":
        split, out = [int(d) for d in sys.argv[2].split(",")], sys.argv[3]
    else:
        split, out = sys.argv[1], sys.argv[2]
    os.makedirs(out, exist_ok=True)
    for name, fam, level, seed in cases(split):
        clean, noisy = make(fam, level, seed)
        write(os.path.join(out, name + "_clean.csv"), clean)
        write(os.path.join(out, name + "_noisy.csv"), noisy)
        print(name)
