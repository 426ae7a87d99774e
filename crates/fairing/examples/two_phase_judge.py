#!/usr/bin/env python3
"""Runs the judge (the peers' compare.py) over the files `two_phase_judge.rs` wrote and prints
the table: inflections / vibrations / RMS to the clean curve of two-phase (default settings and
the paper's), csaps and OpenCASCADE at the same S_d, and whether the default beats csaps
(fewer vibrations, no more inflections, no farther from the clean curve).

Run (with the peers' virtualenv, whose python has numpy, scipy, csaps and OCP):
  cargo run --release -p fairing --example two_phase_judge -- out/two_phase_judge 3
  PEERS/.venv/bin/python crates/fairing/examples/two_phase_judge.py out/two_phase_judge PEERS/compare.py [PREFIX]

(PREFIX: judge only the curves whose name starts with it.)

The judge is not part of this repository; its path is the second argument.
"""
import json
import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path


def judge(compare, original, faired, kind, clean):
    cmd = [sys.executable, compare, str(original), str(faired), "--kind", kind]
    if clean:
        cmd += ["--clean", str(clean)]
    out = subprocess.run(cmd, capture_output=True, text=True, check=False)
    try:
        return json.loads(out.stdout)
    except json.JSONDecodeError:
        return {"error": out.stderr.strip().splitlines()[-1] if out.stderr else "no output"}


def clean_counts(compare, clean, kind):
    """Inflections/vibrations of the clean curve, by the judge's own measures."""
    sys.path.insert(0, str(Path(compare).parent))
    from metrics import coords, metrics, read_points  # the judge's module
    m = metrics(coords(*read_points(str(clean))), kind)
    if kind == "function":
        return f"{m['Infl_num']}/{m['Vib_num']}"
    return f"{m['inflections']}/{m['vibrations2']}"


def cell(result, key):
    if key not in result:
        return "-"
    r = result[key]
    rms = result.get("rms_to_clean", {}).get(key)
    text = f"{r['inflections']}/{r['vibrations']}"
    return text + (f"/{rms:.3g}" if rms is not None else "")


def main():
    out = Path(sys.argv[1] if len(sys.argv) > 1 else "out/two_phase_judge")
    compare = sys.argv[2] if len(sys.argv) > 2 else "compare.py"
    cases = [line.split("\t") for line in (out / "cases.tsv").read_text().splitlines()]
    only = sys.argv[3] if len(sys.argv) > 3 else ""
    cases = [c for c in cases if c[0].startswith(only)]

    def both(case):
        name, kind, closed, has_clean = case
        clean = out / f"{name}_clean.csv" if has_clean.lower() == "true" else None
        noisy = out / f"{name}_noisy.csv"
        return (judge(compare, noisy, out / f"{name}_default.csv", kind, clean),
                judge(compare, noisy, out / f"{name}_paper.csv", kind, clean))

    with ThreadPoolExecutor(max_workers=os.cpu_count() or 2) as pool:
        results = list(pool.map(both, cases))
    wins = total = 0
    print("| curve | kind | clean | noisy | two-phase (paper) | two-phase (default) | S_d | csaps at S_d | OCCT at S_d | default beats csaps |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for (name, kind, closed, _), (default, paper) in zip(cases, results):
        if "ours" not in default:
            print(f"| {name} | error: {default.get('error')} |")
            continue
        ours, mst = default["ours"], default["mst"]
        rms = default.get("rms_to_clean", {})
        checks = [ours["vibrations"] < mst["vibrations"], ours["inflections"] <= mst["inflections"]]
        if "ours" in rms:
            checks.append(rms["ours"] <= rms["mst"])
        verdict = "yes" if all(checks) else "NO (" + ", ".join(
            what for ok, what in zip(checks, ["vibrations", "inflections", "distance"]) if not ok) + ")"
        wins += all(checks)
        total += 1
        label = kind + (", closed" if closed.lower() == "true" else "")
        clean = out / f"{name}_clean.csv"
        truth = clean_counts(compare, clean, kind) if clean.exists() else "-"
        print(f"| {name} | {label} | {truth} | {cell(default, 'original')} | {cell(paper, 'ours')} | "
              f"{cell(default, 'ours')} | {ours['S_d']:.4g} | {cell(default, 'mst')} | "
              f"{cell(default, 'occt')} | {verdict} |", flush=True)
    print(f"\ndefault beats csaps on {wins} of {total}")


if __name__ == "__main__":
    main()
