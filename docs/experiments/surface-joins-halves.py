# Two halves of one smooth noisy surface, 30 x 41 nodes each, sharing the line x = 0.5
# (noise independent on each half, amplitude 0.003 on a unit square).
import math
def noise(i, j, s):
    t = math.sin((i * 7919 + j * 104729 + s * 1299709) * 12.9898) * 43758.5453
    return 2.0 * (t - math.floor(t)) - 1.0
def half(name, x0, x1, seed, rows=30, cols=41):
    with open(name, "w") as f:
        f.write("i,j,x,y,z\n")
        for i in range(rows):
            for j in range(cols):
                x = x0 + (x1 - x0) * i / (rows - 1); y = j / (cols - 1)
                z = 0.3 * (x - 0.4) ** 2 + 0.15 * math.sin(3 * y) * (1 + x) + 0.1 * x * y
                p = (x + 0.003 * noise(i, j, seed), y + 0.003 * noise(i, j, seed + 1), z + 0.003 * noise(i, j, seed + 2))
                f.write(f"{i},{j},{p[0]!r},{p[1]!r},{p[2]!r}\n")
half("first-raw.csv", 0.0, 0.5, 1)
half("second.csv", 0.5, 1.0, 11)
