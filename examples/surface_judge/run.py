#!/usr/bin/env python3
"""Run `fair surface` on a split's nets and judge each with compare_surface.py.

python run.py SPLIT_DIR LABEL [fair args...]   -> SPLIT_DIR/LABEL/<net>.json
python run.py --table SPLIT_DIR LABEL          -> per-family table
Environment: FAIR (the release binary), JUDGE (compare_surface.py), PYTHON (with csaps and
OCP), FAMILIES (a comma-separated subset). The judge runs with --no-occt-iso --no-csaps-trace.
"""
import glob
import json
import os
import statistics
import subprocess
import sys

FAIR = os.environ.get("FAIR", "target/release/fair")
PY = os.environ.get("PYTHON", sys.executable)
JUDGE = os.environ.get("JUDGE", "../shared/peers/compare_surface.py")


def run(split, label, extra):
    out = os.path.join(split, label)
    os.makedirs(out, exist_ok=True)
    only = os.environ.get("FAMILIES")
    for noisy in sorted(glob.glob(os.path.join(split, "*_noisy.csv"))):
        if only and os.path.basename(noisy).split("_")[0] not in only.split(","):
            continue
        name = os.path.basename(noisy)[: -len("_noisy.csv")]
        dest = os.path.join(out, name + ".json")
        if os.path.exists(dest):
            continue
        faired = os.path.join(out, name + "_faired.csv")
        report = os.path.join(out, name + "_report.json")
        p = subprocess.run([FAIR, "surface", noisy, "--quiet", "-o", faired, "--report", report]
                           + extra, capture_output=True, text=True)
        if p.returncode != 0:
            json.dump({"error": p.stderr}, open(dest, "w"))
            print(name, "FAILED", p.stderr.strip()[:200], flush=True)
            continue
        clean = noisy.replace("_noisy", "_clean")
        j = subprocess.run([PY, JUDGE, noisy, faired, "--clean", clean, "--closed", "auto",
                            "--no-occt-iso", "--no-csaps-trace"], capture_output=True, text=True)
        try:
            res = json.loads(j.stdout)
        except Exception:
            res = {"error": j.stderr[-2000:]}
        try:
            res["fair_report"] = {k: v for k, v in json.load(open(report)).items()
                                  if k in ("method", "s_d", "m_d", "elapsed_ms", "extras", "params")}
        except Exception:
            pass
        json.dump(res, open(dest, "w"))
        v = res.get("verdict", {})
        print(name, "both" if v.get("beats_both") else "-",
              "csaps" if v.get("vs_csaps", {}).get("beats") else "-",
              res.get("rms_to_clean"), flush=True)


def table(split, label):
    rows = {}
    for f in sorted(glob.glob(os.path.join(split, label, "*.json"))):
        if f.endswith("_report.json"):
            continue
        name = os.path.basename(f)[:-5]
        fam = name.split("_")[0]
        res = json.load(open(f))
        rows.setdefault(fam, []).append(res)
    print(f"| family | nets | beats both | beats csaps | beats OCCT | median RMS ours | csaps | OCCT | ours/csaps | ours/OCCT | vib ours/csaps/occt | infl ours/csaps/occt |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|")
    tot = [0, 0, 0, 0]
    for fam, rs in rows.items():
        ok = [r for r in rs if "verdict" in r]
        both = sum(bool(r["verdict"].get("beats_both")) for r in ok)
        cs = sum(bool(r["verdict"]["vs_csaps"]["beats"]) for r in ok)
        oc = sum(bool(r["verdict"].get("vs_occt", {}).get("beats")) for r in ok)
        med = lambda k: statistics.median(r["rms_to_clean"][k] for r in ok if k in r["rms_to_clean"])
        mo, mc, mk = med("ours"), med("csaps"), med("occt")
        ratio = lambda k: statistics.median(r["rms_to_clean"]["ours"] / r["rms_to_clean"][k] for r in ok if k in r["rms_to_clean"])
        s = lambda who, k: sum(r[who][k] for r in ok if who in r and k in r[who])
        print(f"| {fam} | {len(rs)} | {both} | {cs} | {oc} | {mo:.3g} | {mc:.3g} | {mk:.3g} | {ratio('csaps'):.3f} | {ratio('occt'):.3f} | "
              f"{s('ours','vibrations')}/{s('csaps','vibrations')}/{s('occt','vibrations')} | {s('ours','inflections')}/{s('csaps','inflections')}/{s('occt','inflections')} |")
        tot[0] += len(rs); tot[1] += both; tot[2] += cs; tot[3] += oc
    print(f"| all | {tot[0]} | {tot[1]} | {tot[2]} | {tot[3]} | | | | | | | |")


if __name__ == "__main__":
    if sys.argv[1] == "--table":
        table(sys.argv[2], sys.argv[3])
    else:
        run(sys.argv[1], sys.argv[2], sys.argv[3:])
