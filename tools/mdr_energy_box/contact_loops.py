#!/usr/bin/python3
"""tools/mdr_energy_box/contact_loops.py OUT.h5 [SPHERE]: which contacts feed a swinging sphere. OUT.h5 must have a
frame at every step with the contacts field (run.sh's b7_d2_steps.h5). SPHERE: a particle id (default: the fastest at
the last frame). The sphere's swing is cut into cycles at the upward zero crossings of its velocity along the axis
where it swings most; for each of its contacts, the work the contact takes per cycle, the loop integral of
|normal force| d(overlap) (trapezoidal rule; positive: the contact takes work, as damping does; negative: it gives
work back), cycle by cycle. The normal force is the whole one, MDR's damping included."""
import sys
import h5py
import numpy as np

h = h5py.File(sys.argv[1], "r")
V = h["frames/velocity"][:]
step = h["frames/step"][:]
if not np.all(np.diff(step) == 1):
    sys.exit("contact_loops: the frames are not one per step")
P = int(sys.argv[2]) if len(sys.argv) > 2 else int(np.argmax(np.linalg.norm(V[-1], axis=1)))
fs, ids, d = h["contacts/frame_start"][:], h["contacts/ids"][:], h["contacts/data"][:]
nf = len(step)
ov, fn = {}, {}
for f in range(nf):
    a, b = fs[f], fs[f + 1] if f + 1 < nf else len(ids)
    for r in range(a, b):
        i, j = int(ids[r, 0]), int(ids[r, 1])
        if P in (i, j):
            k = j if i == P else i  # the partner: a particle id, or -1 - wall
            ov.setdefault(k, np.full(nf, np.nan))[f] = d[r, 0]
            fn.setdefault(k, np.full(nf, np.nan))[f] = np.linalg.norm(d[r, 1:4])
ax = int(np.argmax(np.ptp(V[:, P, :], axis=0)))
v = V[:, P, ax]
up = np.nonzero((v[:-1] < 0) & (v[1:] >= 0))[0]
if len(up) < 2:
    sys.exit("contact_loops: sphere %d makes no whole cycle in these frames" % P)
walls = h["series"].attrs["wall_names"]
walls = (walls.decode() if isinstance(walls, bytes) else walls).split("\n")
print("sphere %d swings along %s: %d cycles of %s steps, speed up to %.3g m/s" %
      (P, "xyz"[ax], len(up) - 1, "/".join(str(int(x)) for x in sorted(set(np.diff(up)))),
       np.abs(V[up[0]:up[-1], P]).max()))
print("contact | overlap range [um] | |normal force| range [N] | work taken per cycle [J], cycle by cycle")
total = np.zeros(len(up) - 1)
for k in sorted(ov):
    w = []
    for c in range(len(up) - 1):
        p, q = up[c], up[c + 1]
        o, f = ov[k][p:q + 1], fn[k][p:q + 1]
        w.append(np.nansum(0.5 * (f[1:] + f[:-1]) * np.diff(o)))
    total += np.array(w)
    name = "particle %d" % k if k >= 0 else "wall %s" % walls[-1 - k]
    print("%s | %.3f to %.3f | %.3g to %.3g | %s" % (name, np.nanmin(ov[k]) * 1e6, np.nanmax(ov[k]) * 1e6,
                                                    np.nanmin(fn[k]), np.nanmax(fn[k]), " ".join("%.2e" % x for x in w)))
print("all its contacts | | | %s" % " ".join("%.2e" % x for x in total))
