"""Aggregate summary.py's lines per kind of hard-chine table (rounded, noisy, planted, adjacent), one row per run:

    python examples/lines_judge/compare.py BEFORE.sum AFTER.sum ...
"""
import re, sys, statistics as st
def load(p):
    d = {}
    for l in open(p):
        m = re.match(r"(\w+)\s+(\w+)\s+(\d+) .*truth \S+ -> ([\d.]+)/([\d.]+)\s+infl (\d+)/(\d+)/(\d+);", l)
        if not m: continue
        f, t, s, rms, mx, iw, ib, ist = m.groups()
        r = dict(rms=float(rms), max=float(mx), ist=int(ist), iw=int(iw), ib=int(ib))
        fm = re.search(r"flag (\d+)/(\d+) restored (\d+)/(\d+) off (\S+)", l)
        if fm:
            r['flag'] = int(fm.group(1)); r['rest'] = int(fm.group(3)); r['n']=int(fm.group(2)); r['off']=max(map(float, fm.group(5).split(',')))
        sw = re.search(r"swl (\S+)\s+sbt (\S+)", l)
        r['swl'], r['sbt'] = sw.groups()
        d[(f, t, s)] = r
    return d
ds = [load(p) for p in sys.argv[1:]]
keys = [k for k in ds[0] if all(k in d for d in ds)]
for tag in ['rounded', 'noisy', 'planted', 'adjacent']:
    ks = [k for k in keys if k[1] == tag and k[0]=='chine']
    if not ks: continue
    print(f"== chine {tag}: {len(ks)} tables")
    for name, d in zip(sys.argv[1:], ds):
        rms = [d[k]['rms'] for k in ks]; mx = [d[k]['max'] for k in ks]; ist = [d[k]['ist'] for k in ks]
        s = f"{name:18} rms med {st.median(rms):.2f} max {max(rms):.2f} | max med {st.median(mx):.2f} largest {max(mx):.2f} | st infl med {st.median(ist)} range {min(ist)}-{max(ist)} sum {sum(ist)}"
        if tag=='noisy': s += f" | meet1/3 {sum(d[k]['rms']<=1.0 and d[k]['max']<=3 for k in ks)} max>3 {sum(m>3 for m in mx)}"
        if tag=='rounded': s += f" | max>1 {sum(m>1 for m in mx)}"
        if tag in ('planted', 'adjacent'): s += f" | flag {sum(d[k]['flag'] for k in ks)}/{sum(d[k]['n'] for k in ks)} rest {sum(d[k]['rest'] for k in ks)} off max {max(d[k]['off'] for k in ks):.2f} max>1 {sum(m>1 for m in mx)}"
        print(s)
