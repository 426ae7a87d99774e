"""Judge the known-hull tables that `cargo run --release -p fair-lines --example lines_plan --
OUTDIR SEEDS...` wrote, one line per table (issue 47, docs/experiments/lines-plan.md):

    python examples/lines_judge/summary.py OUTDIR FORMS KINDS SEEDS... > OUT.sum

FORMS: comma-separated `chine`, `wigley`; KINDS: comma-separated `rounded`, `noisy`,
`planted`. Each table's judge result is left in OUTDIR/<form>_<kind>_<seed>/judge.json.
Environment: PYTHON (with numpy and scipy), JUDGE (lines_check.py; default
../shared/peers/lines_check.py). Compare two runs' lines with compare.py.
"""
import json, subprocess, sys, os
J = [os.environ.get("PYTHON", sys.executable),
     os.environ.get("JUDGE", "../shared/peers/lines_check.py")]
out, forms, tags, seeds = sys.argv[1], sys.argv[2].split(","), sys.argv[3].split(","), sys.argv[4:]
for form in forms:
    for tag in tags:
        for s in seeds:
            d = f"{out}/{form}_{tag}_{s}"
            if not os.path.isdir(d):
                continue
            jp = f"{d}/judge.json"
            args = J + [f"{d}/table.csv", f"{d}/faired.csv", "--truth", f"{d}/truth.csv", "--json", jp]
            if tag in ("planted", "adjacent"):
                args += ["--planted", f"{d}/planted.json"]
            subprocess.run(args, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, check=True)
            r = json.load(open(jp))
            c = r["views"]["faired"]["consistency"]
            def rm(k):
                x = c[k]
                return f"{x['rms_steps']:.2f}/{x['max_steps']:.2f}" if x and 'rms_steps' in x else "-"
            tt = r["to_truth"]
            fam = r["views"]["faired"]["fairness"]["families"]
            tf = r["views"]["truth"]["fairness"]["families"]
            infl = f"{fam['waterlines']['inflections']}/{fam['buttocks']['inflections']}/{fam['stations']['inflections']};{tf['waterlines']['inflections']}/{tf['buttocks']['inflections']}/{tf['stations']['inflections']}"
            kk = r["knuckles_kept"]
            kn = f"{kk['min_ratio']:.3f}/{kk['median_ratio']:.3f}" if kk.get("n") else "-"
            pl = ""
            if tag in ("planted", "adjacent"):
                rep = json.load(open(f"{d}/report.json"))
                fl = {(o["line"], o["station_index"]) for o in rep["offsets"] if o["flagged"]}
                pe = json.load(open(f"{d}/planted.json"))["errors"]
                P = r["planted"]
                nf = sum(all((c["line"], c["station_index"]) in fl for c in e["cells"]) for e in pe)
                pl = f"flag {nf}/{len(pe)} restored {sum(e['restored'] for e in P)}/{len(P)} off " + ",".join(f"{e['faired_err_max_steps']:.2f}" for e in P)
            print(f"{form:6} {tag:7} {s:>3} swl {rm('station_x_waterline'):11} sbt {rm('station_x_buttock'):11} truth {tt['input']['rms_steps']:.2f}/{tt['input']['max_steps']:.2f} -> {tt['faired']['rms_steps']:.2f}/{tt['faired']['max_steps']:.2f}  infl {infl:14} kn {kn} {pl}", flush=True)
