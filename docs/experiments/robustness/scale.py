# Usage: python3 scale.py FAIR DATA.csv METHOD
# Scales and shifts a CSV curve x,y; runs `fair curve` on each; compares with the ×1 result.
import csv, subprocess, sys, os, tempfile, time
tmp = tempfile.mkdtemp()
fair, src, method = sys.argv[1], sys.argv[2], sys.argv[3]
rows = list(csv.reader(open(src)))
head, data = rows[0], [[float(v) for v in r] for r in rows[1:] if r]
size = max(max(abs(v) for v in r) for r in data)
def run(k, shift):
    s = 2.0 ** k
    name = os.path.join(tmp, f"in_{method}_{k}_{int(shift)}.csv")
    with open(name, "w") as f:
        f.write(",".join(head) + "\n")
        for r in data:
            f.write(",".join(repr(v * s + shift) for v in r) + "\n")
    out = name.replace("in_", "out_")
    t = time.time()
    p = subprocess.run([fair, "curve", name, "--method", method, "-o", out], capture_output=True, text=True)
    dt = time.time() - t
    if p.returncode != 0:
        return None, p.returncode, p.stderr.strip().splitlines()[-1][:160] if p.stderr.strip() else "", dt
    res = [[float(v) for v in r] for r in list(csv.reader(open(out)))[1:] if r]
    return res, 0, "", dt
base, rc, err, dt0 = run(0, 0.0)
print(f"{method}: ×1 exit {rc} {err} ({dt0:.1f} s)")
for k, shift in [(3, 0.0), (-20, 0.0), (45, 0.0), (-45, 0.0), (0, 1e5)]:
    res, rc, err, dt = run(k, shift)
    if res is None or base is None:
        print(f"  2^{k} +{shift:g}: exit {rc} {err} ({dt:.1f} s)")
        continue
    s = 2.0 ** k
    dev = max(abs(b * s + shift - r) for rb, rr in zip(base, res) for b, r in zip(rb, rr)) / (size * s)
    print(f"  2^{k} +{shift:g}: exit 0, largest difference {dev:.1e} of the size ({dt:.1f} s)")
