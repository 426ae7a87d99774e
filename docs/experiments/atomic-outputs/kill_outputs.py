#!/usr/bin/env python3
"""Kill `fair curve` (SIGKILL) at seeded moments and classify each output: old (byte for
byte), new (complete: every point / valid JSON / closed SVG) or BROKEN. Half the moments
anywhere in the run, half while it writes. Usage: kill_outputs.py FAIR N [KILLS]."""
import json, math, os, signal, subprocess, sys, tempfile, time

fair, n = os.path.abspath(sys.argv[1]), int(sys.argv[2])
kills = int(sys.argv[3]) if len(sys.argv) > 3 else 8
d = tempfile.mkdtemp(prefix="fair-kill-")
state = 20261206
def u():
    global state
    state = (state * 6364136223846793005 + 1442695040888963407) % (1 << 64)
    return ((state >> 11) + 0.5) / (1 << 53)
x, rows = 0.0, ["x,y"]
for _ in range(n):
    x += (0.5 + u()) * 4 * math.pi / n
    g = math.sqrt(-2 * math.log(u())) * math.cos(2 * math.pi * u())
    rows.append(f"{x!r},{math.sin(x / 2) + 0.01 * g!r}")
open(os.path.join(d, "in.csv"), "w").write("\n".join(rows) + "\n")
OUT = ["out.csv", "report.json", "plot.svg"]
OLD = [b"x,y\n0,0\n1,1\n", b'{"old": true}\n', b'<svg xmlns="http://www.w3.org/2000/svg"></svg>\n']
def reset():
    for f in os.listdir(d):
        if ".fair-tmp-" in f: os.remove(os.path.join(d, f))
    for f, o in zip(OUT, OLD): open(os.path.join(d, f), "wb").write(o)
def read(f):
    try: return open(os.path.join(d, f), "rb").read()
    except FileNotFoundError: return None
def writing():
    return any(".fair-tmp-" in f for f in os.listdir(d)) or any(read(f) != o for f, o in zip(OUT, OLD))
def complete(i, b):
    if i == 0:
        t = b.decode(errors="replace"); r = t.splitlines()[1:]
        return t.endswith("\n") and len(r) == n and all(len(l.split(",")) == 2 for l in r)
    if i == 1:
        try: return isinstance(json.loads(b), dict)
        except ValueError: return False
    return b.startswith(b"<svg") and b.endswith(b"</svg>\n")
def states():
    out = []
    for i, f in enumerate(OUT):
        b = read(f)
        out.append("missing" if b is None else "old" if b == OLD[i] else
                   "new" if complete(i, b) else f"BROKEN({len(b)} B)")
    left = [f for f in os.listdir(d) if f not in OUT + ["in.csv"]]
    return out, left
def spawn():
    return subprocess.Popen([fair, "curve", "in.csv", "--method", "strain-energy", "--kind", "parametric",
        "-o", "out.csv", "--report", "report.json", "--plot", "plot.svg", "-q"], cwd=d,
        stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
reset(); t0 = time.monotonic(); p = spawn(); began = None
while p.poll() is None:
    if began is None and writing(): began = time.monotonic() - t0
    time.sleep(0.001)
total = time.monotonic() - t0; began = began or total; wr = total - began
print(f"{os.path.basename(fair)} n={n}: run {total:.2f} s, writing {wr*1000:.0f} ms, exit {p.returncode}, outputs {states()}")
broken = 0
for k in range(kills):
    reset(); t0 = time.monotonic(); p = spawn(); v = u()
    if k % 2 == 0:
        time.sleep(total * v)
    else:
        while p.poll() is None and not writing() and time.monotonic() - t0 < 4 * total: time.sleep(0.001)
        time.sleep(wr * v)
    w = writing(); p.send_signal(signal.SIGKILL); p.wait()
    s, left = states(); broken += sum(x.startswith("BROKEN") for x in s)
    print(f"  kill {k} at {time.monotonic()-t0:.3f} s ({'while writing' if w else 'before writing'}, status {p.returncode}): {s} left {left}")
print(f"  broken outputs: {broken} of {3*kills}")
