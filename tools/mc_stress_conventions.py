#!/usr/bin/python3
"""Runs seed 000's validation scenes under every MC-stress pressure convention and prints the comparison table.

usage: tools/mc_stress_conventions.py [--dem build/dem] [--out out/conventions] [--scenes a,b,...]

Each convention (own contact in/out x lever centres/contact_point x scale mean_trace/text/mean_pressure; see
docs/multicontact.md) is written into a copy of the scene (key mc_stress_convention, docs/scenes.md) next to the
original, run with `dem run --model mc_stress`, and compared with the classical and the MC-strain runs of the scene:
  rubber_plates   plate force at d/r = 0.4 (Fig. 4: beta 1.71 and gamma 0.55 calibrated on this point)
  three_/five_*   largest overlap of the central sphere and when (Figs. 6-9: MC-stress lowest, both earlier)
  five_box        x+ wall force at full strain against Eq. 11 with delta_4 = strain d (Fig. 10)
  compression     peak stress (Fig. 11b hydrogel_514, 14 hydrogel_1921, 15 rubber_514, 16 glass_die)
Prints one Markdown table; docs/multicontact.md quotes it. make conventions runs it (about 8 minutes on 2 cores).
"""
import argparse
import itertools
import math
import os
import subprocess
import sys

import h5py
import numpy as np

ALL = ["rubber_plates", "three_hydrogel", "five_hydrogel", "three_rubber", "five_rubber", "five_box",
       "hydrogel_514", "hydrogel_1921", "rubber_514", "glass_die"]
CONVENTIONS = list(itertools.product(["in", "out"], ["centres", "contact_point"], ["mean_trace", "text", "mean_pressure"]))


def path_of(name):
    p = f"scenes/validation/{name}.yaml"
    return p if os.path.exists(p) else f"scenes/{name}.yaml"


def metric(name, h5):
    """(value, text) of one run"""
    with h5py.File(h5, "r") as f:
        s = f["series"]
        if name == "rubber_plates":
            v = float(np.max(s["stress"][:]) * s.attrs["sample_area"])
            return v, f"{v:.4g} N"
        if name == "five_box":
            v = float(np.max(s["stress"][:]) * s.attrs["sample_area"])
            return v, f"{v:.4g} N"
        if "strain" in s:
            v = float(np.max(s["stress"][:]))
            return v, f"{v:.4g} Pa"
        fr = f["frames"]
        x, r, t = fr["position"][:], f["particles/radius"][:], fr["time"][:]
        d = r[0] + r[1] - np.linalg.norm(x[:, 0, :] - x[:, 1, :], axis=1)
        k = int(np.argmax(d))
        return float(d[k]), f"{1e3 * d[k]:.3f} mm at {1e3 * t[k]:.2f} ms"


def eq11_box(h5):
    """Eq. 11 at the five-box's full strain (delta_4 = strain d, d = 2r; hydrogel, beta 1.65)"""
    with h5py.File(h5, "r") as f:
        eps = float(np.max(f["series/strain"][:]))
    r, E, nu, beta = 0.01, 23.3e3, 0.5, 1.65
    es = E / (2 * (1 - nu * nu))
    dl = eps * 2 * r
    V, A = 4 / 3 * math.pi * r ** 3, math.pi * r / 2 * dl
    return 4 / 3 * es * math.sqrt(r / 2 * dl) * dl * (1 + 4 * (2 * r - dl) * beta * nu * A / V)


def run(dem, scene, out, model, conv=None):
    src = scene
    if conv:
        src = os.path.join(os.path.dirname(scene), ".conv-" + os.path.basename(scene))
        with open(scene) as f, open(src, "w") as g:
            g.write(f.read())
            g.write("\nmc_stress_convention: {own_contact: %s, lever: %s, scale: %s}\n" % conv)
    try:
        subprocess.run([dem, "run", src, "--model", model, "-o", out, "--quiet"], check=True)
    finally:
        if conv:
            os.remove(src)
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dem", default="build/dem")
    ap.add_argument("--out", default="out/conventions")
    ap.add_argument("--scenes", default=",".join(ALL))
    a = ap.parse_args()
    names = a.scenes.split(",")
    os.makedirs(a.out, exist_ok=True)
    res = {}
    for name in names:
        for m in ("classical", "mc_strain"):
            res[(name, m)] = metric(name, run(a.dem, path_of(name), f"{a.out}/{name}-{m}.h5", m))
        for conv in CONVENTIONS:
            h5 = run(a.dem, path_of(name), f"{a.out}/{name}-mc_stress-{'-'.join(conv)}.h5", "mc_stress", conv)
            res[(name, conv)] = metric(name, h5)
            if name == "five_box":
                res[(name, "eq11")] = eq11_box(h5)
    print("| run | " + " | ".join(names) + " |")
    print("|---" * (1 + len(names)) + "|")
    for m in ("classical", "mc_strain"):
        print(f"| {m} | " + " | ".join(res[(n, m)][1] for n in names) + " |")
    if "five_box" in names:
        print("| Eq. 11 (delta_4 = strain d) | " + " | ".join(
            f"{res[(n, 'eq11')]:.4g} N" if n == "five_box" else "" for n in names) + " |")
    for conv in CONVENTIONS:
        cells = []
        for n in names:
            v, txt = res[(n, conv)]
            c, s = res[(n, "classical")][0], res[(n, "mc_strain")][0]
            cells.append(f"{txt} ({100 * (v / c - 1):+.1f} % vs classical, {100 * (v / s - 1):+.1f} % vs MC-strain)")
        print(f"| mc_stress {'/'.join(conv)} | " + " | ".join(cells) + " |")


if __name__ == "__main__":
    sys.exit(main())
