#!/usr/bin/env python3
"""Run the judge on the curves `examples/jump_lsq_judge.rs` wrote and print the table.

For every open test curve: `compare.py NAME_noisy.csv NAME_faired.csv --kind K --clean
NAME_clean.csv` (csaps and OpenCASCADE at the S_d of our result), then one markdown row with
the inflections, vibrations and RMS distance to the clean curve of ours / csaps / OCCT, and
whether the goal holds: fewer vibrations than both peers, no more inflections than either,
no farther from the clean curve than the closer peer.

The closed ellipse is judged too, as the open curve from its first to its last point (the
judge's splines are open; csaps and OpenCASCADE then fit it open).

Usage: python3 examples/jump_lsq_judge.py [DIR…] [--peers PEERS_DIR] [--python PYTHON]
  DIR     the example's output folders (default out/jump_lsq), e.g. one per seed and noise
          level: a table for each, then for each curve the number of folders where the goal
          holds
  PEERS   the judge's folder (default $FAIR_PEERS or /work/peers), PYTHON its interpreter
          (default PEERS/.venv/bin/python)
"""
import argparse
import json
import os
import subprocess
import sys

CURVES = [
    ("sine", "function"),
    ("airfoil", "function"),
    ("airfoil-synthetic", "function"),
    ("strophoid", "parametric"),
    ("clothoid", "parametric"),
    ("arc", "parametric"),
    ("ellipse", "parametric"),
]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("dirs", nargs="*", default=["out/jump_lsq"])
    ap.add_argument("--peers", default=os.environ.get("FAIR_PEERS", "/work/peers"))
    ap.add_argument("--python")
    ap.add_argument("--json", help="also write the raw judge output to this file")
    a = ap.parse_args()
    python = a.python or os.path.join(a.peers, ".venv", "bin", "python")
    raw, tally = {}, {name: 0 for name, _ in CURVES}
    for d in a.dirs:
        raw[d] = table(d, python, a.peers, tally)
    if len(a.dirs) > 1:
        print(f"\ngoal met, of {len(a.dirs)} folders: " +
              ", ".join(f"{name} {k}" for name, k in tally.items()))
    if a.json:
        with open(a.json, "w") as fh:
            json.dump(raw, fh, indent=1)


def table(folder, python, peers_dir, tally):
    rows, raw = [], {}
    met = 0
    for name, kind in CURVES:
        f = lambda suffix: os.path.join(folder, f"{name}_{suffix}.csv")
        out = subprocess.run(
            [python, os.path.join(peers_dir, "compare.py"), f("noisy"), f("faired"),
             "--kind", kind, "--clean", f("clean")],
            capture_output=True, text=True, check=True).stdout
        r = json.loads(out)
        raw[name] = r
        peers = [p for p in ("mst", "occt") if p in r]
        infl = {k: r[k]["inflections"] for k in ["ours"] + peers}
        vib = {k: r[k]["vibrations"] for k in ["ours"] + peers}
        rms = {k: r["rms_to_clean"][k] for k in ["ours"] + peers}
        fewer_vib = all(vib["ours"] < vib[p] for p in peers)
        no_more_infl = all(infl["ours"] <= infl[p] for p in peers)
        closer = rms["ours"] <= min(rms[p] for p in peers) * (1 + 1e-9)
        ok = fewer_vib and no_more_infl and closer
        met += ok
        tally[name] += ok
        fmt = lambda d: " / ".join(str(d[k]) for k in ["ours"] + peers)
        fmt_rms = lambda d: " / ".join(f"{d[k]:.3g}" for k in ["ours"] + peers)
        rows.append(
            f"| {name} | {kind} | {len(open(f('noisy')).readlines()) - 1} | {r['ours']['S_d']:.4g} "
            f"| {r['original']['inflections']} / {r['original']['vibrations']} "
            f"| {fmt(infl)} | {fmt(vib)} | {fmt_rms(rms)} (noisy {r['rms_to_clean']['original']:.3g}) "
            f"| {'yes' if ok else 'no: ' + ', '.join(w for w, c in (('vibrations', fewer_vib), ('inflections', no_more_infl), ('distance', closer)) if not c)} |")
    print(f"\n{folder}\n")
    print("| curve | kind | n | S_d | noisy infl / vib | inflections ours / csaps / OCCT "
          "| vibrations ours / csaps / OCCT | RMS to clean ours / csaps / OCCT | goal |")
    print("|---|---|---|---|---|---|---|---|---|")
    print("\n".join(rows))
    print(f"\ngoal met on {met} of {len(CURVES)} curves")
    return raw


if __name__ == "__main__":
    sys.exit(main())
