#!/usr/bin/python3
"""tools/mdr_held_bulk/windows.py LAW.txt HELD.txt [WINDOW]: the two continuations of continue.c side by side, window
by window (WINDOW seconds, default 5e-5): per run the largest kinetic energy [J], the largest kinetic / elastic energy,
the fastest sphere [m/s], the most spheres above 1 m/s at one sample, and the wall's normal force at the window's
last sample [N]. Only whole windows: one the runs' samples do not cover to its end is left out."""
import sys
import numpy as np


def load(path):
    rows = [line.split() for line in open(path) if line[:1].isdigit()]
    if not rows:
        sys.exit("windows: no samples in %s" % path)
    return np.array([[float(x) for x in r[:6]] for r in rows])


law, held = load(sys.argv[1]), load(sys.argv[2])
w = float(sys.argv[3]) if len(sys.argv) > 3 else 5e-5
t0 = min(law[0, 0], held[0, 0])
t0 -= t0 % w  # windows start on a multiple of w
end = max(law[-1, 0], held[-1, 0])
print("| window [ms] | the law: largest kinetic [J], kinetic / elastic, fastest [m/s], spheres > 1 m/s, wall force [N] "
      "| bulk increments held: the same |")
print("|---|---|---|")
a = t0
while a + w <= end * (1 + 1e-9):
    cells = []
    for d in (law, held):
        m = (d[:, 0] > a) & (d[:, 0] <= a + w * (1 + 1e-9))
        if not m.any():
            cells.append("-")
            continue
        r = d[m]
        cells.append("%.2e, %.2e, %.2g, %d, %.1f" % (r[:, 1].max(), (r[:, 1] / r[:, 2]).max(), r[:, 3].max(),
                                                      int(r[:, 4].max()), r[-1, 5]))
    print("| %.2f-%.2f | %s | %s |" % (a * 1e3, (a + w) * 1e3, cells[0], cells[1]))
    a += w
