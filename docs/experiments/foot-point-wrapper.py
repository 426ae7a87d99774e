#!/usr/bin/env python3
"""Prototype (docs/experiments/default-smoothing.md, "Foot points"): run fair (FAIR, default
target/release/fair), then move a parametric result's points to the foot points of the data
on the faired curve (interpolant of the result over its own chord lengths), window 0.45 span."""
import os, sys, subprocess, numpy as np
from scipy.interpolate import CubicSpline
from scipy.optimize import minimize_scalar
args = sys.argv[1:]
r = subprocess.run([os.environ.get("FAIR", "target/release/fair")] + args)
if r.returncode != 0:
    sys.exit(r.returncode)
kind = args[args.index("--kind") + 1]
if kind != "parametric":
    sys.exit(0)
inp = args[1]; out = args[args.index("-o") + 1]
def load(f):
    with open(f) as fh: header = fh.readline().strip()
    return header, np.loadtxt(f, delimiter=",", skiprows=1, ndmin=2)
h, Q = load(inp); h2, F = load(out)
closed = len(Q) > 3 and np.allclose(Q[0], Q[-1])
P = F[:-1] if closed else F
Qd = Q[:-1] if closed else Q
n = len(P)
if closed:
    pts = np.vstack([P, P[:1]])
    t = np.concatenate([[0], np.cumsum(np.linalg.norm(np.diff(pts, axis=0), axis=1))])
    cs = CubicSpline(t, pts, bc_type="periodic"); period = t[-1]
else:
    t = np.concatenate([[0], np.cumsum(np.linalg.norm(np.diff(P, axis=0), axis=1))])
    cs = CubicSpline(t, P, bc_type="natural")
W = 0.45
G = P.copy()
for i in range(n):
    q = Qd[i]
    best = (((P[i] - q) ** 2).sum(), P[i])
    wins = []
    if i > 0: wins.append((t[i] - W * (t[i] - t[i-1]), t[i]))
    elif closed: wins.append((t[0] - W * (period - t[n-1]), t[0]))
    if i < n - 1 or closed: wins.append((t[i], t[i] + W * (t[i+1] - t[i])))
    for a, b in wins:
        ev = (lambda s: cs(s % period)) if closed else cs
        ss = np.linspace(a, b, 17); d = ((ev(ss) - q) ** 2).sum(1); k = d.argmin()
        res = minimize_scalar(lambda s: ((ev(s) - q) ** 2).sum(), bounds=(ss[max(k-1,0)], ss[min(k+1,16)]), method="bounded", options={"xatol": 1e-12})
        if res.fun < best[0]: best = (res.fun, ev(res.x))
    G[i] = best[1]
if closed: G = np.vstack([G, G[:1]])
np.savetxt(out, G, delimiter=",", header=h2, comments="", fmt="%.17g")
