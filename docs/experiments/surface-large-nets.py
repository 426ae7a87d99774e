#!/usr/bin/env python3
"""Large noisy nets with clean twins for the coarse basis of `jump-lsq` on surfaces
(surface-fairing.md, "A coarse basis first").

    python surface-large-nets.py OUT FAMILY:SIZE:SEED:LEVEL ...   write OUT/NAME_{clean,noisy}.csv
    python surface-large-nets.py OUT FAMILY:SIZE:SEED:LEVEL:join ...  and OUT/NAME_nb.csv
    python surface-large-nets.py --rms CLEAN NOISY FAIRED_A [FAIRED_B]

Families over the unit square, SIZE x SIZE nodes, z only noisy (sigma = LEVEL x 0.002 x the
bounding-box diagonal): smooth (0.2 sin(3 pi a u) cos(2 pi b v)), detail (40 Gaussian bumps of
1/60..1/25 of the side), fine (300 bumps of 1/300..1/120), waves (4 plane waves of 2..12 pi).
With `join` the family is drawn on 2 SIZE - 1 rows over u in [0, 1]: the net is the rows of
u >= 1/2 (SIZE x SIZE, noisy, and its clean twin), its neighbour (NAME_nb.csv, clean) the rows
of u <= 1/2, so the two share the edge u = 1/2 (the net's u0; `fair surface NET --join
u0=NB:g1`, surface-fairing.md, "Joins on reduced bases").
--rms prints the RMS distance to the clean net of each faired net, the input's, and the largest
node difference between A and B over the input's RMS.
"""
import os
import sys

import numpy as np


def net(fam, m, seed, level=1.0, rows=None):
    r = np.random.default_rng(seed)
    u, v = np.meshgrid(np.linspace(0, 1, rows or m), np.linspace(0, 1, m), indexing="ij")
    if fam == "smooth":
        z = 0.2 * np.sin(3 * u * np.pi * r.uniform(0.5, 1.5)) * np.cos(2 * v * np.pi * r.uniform(0.5, 1.5))
    elif fam in ("detail", "fine"):
        count, lo, hi, amp = (40, 1 / 60, 1 / 25, (0.02, 0.06)) if fam == "detail" else (300, 1 / 300, 1 / 120, (0.01, 0.03))
        z = np.zeros_like(u)
        for _ in range(count):
            cx, cy = r.uniform(0.05, 0.95, 2) if fam == "detail" else r.uniform(0.02, 0.98, 2)
            s = r.uniform(lo, hi)
            z += r.uniform(*amp) * np.exp(-((u - cx) ** 2 + (v - cy) ** 2) / (2 * s * s))
    elif fam == "waves":
        z = np.zeros_like(u)
        for _ in range(4):
            a, b = r.uniform(2, 12, 2) * np.pi
            ph = r.uniform(0, 2 * np.pi)
            z += r.uniform(0.01, 0.04) * np.sin(a * u + b * v + ph)
    else:
        raise SystemExit(f"unknown family {fam}")
    G = np.stack([u, v, z], -1)
    P = G.reshape(-1, 3)
    sigma = level * 0.002 * np.linalg.norm(P.max(0) - P.min(0))
    return G, G + np.r_[0, 0, 1][None, None, :] * r.normal(0, sigma, G.shape)


def write(path, G):
    m, n, _ = G.shape
    I, J = np.meshgrid(np.arange(m), np.arange(n), indexing="ij")
    A = np.column_stack([I.ravel(), J.ravel(), G.reshape(-1, 3)])
    np.savetxt(path, A, fmt=["%d", "%d", "%.17g", "%.17g", "%.17g"], delimiter=",",
               header="i,j,x,y,z", comments="")


def load(path):
    return np.loadtxt(path, delimiter=",", skiprows=1)[:, 2:]


if __name__ == "__main__":
    if sys.argv[1] == "--rms":
        clean, noisy = load(sys.argv[2]), load(sys.argv[3])
        rms = lambda P: np.sqrt(np.mean(np.sum((P - clean) ** 2, 1)))
        faired = [load(p) for p in sys.argv[4:]]
        gap = np.max(np.abs(faired[0] - faired[1])) / rms(noisy) if len(faired) > 1 else 0.0
        print(" ".join(f"{rms(F):.4e}" for F in faired), f"input {rms(noisy):.4e}", f"gap/input {gap:.3f}")
    else:
        os.makedirs(sys.argv[1], exist_ok=True)
        for spec in sys.argv[2:]:
            fam, m, seed, level, *join = spec.split(":")
            m = int(m)
            clean, noisy = net(fam, m, int(seed), float(level), 2 * m - 1 if join else None)
            name = f"{fam}_{m}_{seed}_{level}"
            if join:
                write(os.path.join(sys.argv[1], name + "_nb.csv"), clean[:m])
                clean, noisy = clean[m - 1:], noisy[m - 1:]
            write(os.path.join(sys.argv[1], name + "_clean.csv"), clean)
            write(os.path.join(sys.argv[1], name + "_noisy.csv"), noisy)
            print(name)
