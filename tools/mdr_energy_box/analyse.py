#!/usr/bin/python3
"""tools/mdr_energy_box/analyse.py OUT.h5 ...: for each run of box.yaml, the upper plane's force when the hold began
and at the end, the kinetic energy's largest value in each 0.1 ms of the hold and after it, and the fastest sphere at
the last frame."""
import sys
import h5py
import numpy as np

print("run | upper force at the hold's start, end [N] | largest kinetic energy in each 0.1 ms from the hold's "
      "start [J] | fastest sphere at the end [m/s]")
for path in sys.argv[1:]:
    h = h5py.File(path, "r")
    s = h["series"]
    t, ke = s["time"][:], s["kinetic"][:]
    z = s["wall_position"][:, 5, 2]
    f = s["wall_normal_force"][:, 5]
    moving = np.nonzero(np.abs(np.diff(z)) > 0)[0]
    t0 = t[moving[-1] + 1]  # the first row with the plane at rest
    windows = []
    a = t0
    while a < t[-1]:
        m = (t >= a) & (t < a + 1e-4)
        windows.append("%.2e" % ke[m].max())
        a += 1e-4
    v = h["frames/velocity"][-1]
    sp = np.linalg.norm(v, axis=1)
    print("%s | %.3f, %.3f | %s | %.3g (sphere %d)" % (path, f[t >= t0][0], f[-1], ", ".join(windows), sp.max(),
                                                      int(np.argmax(sp))))
