#!/usr/bin/python3
"""Runs seed 000's two MC-stress calibration points under every pressure convention and prints the table.

usage: tools/mc_stress_conventions.py [--dem build/dem] [--out out/conventions]

The calibrations (section 3.3 and 4.1): the rubber sphere between plates at d/r = 0.4 (beta 1.71 against MC-strain
with gamma 0.55, Fig. 4) and the 514 hydrogel packing at 13.4 % strain (beta 1.65 against gamma 1.12, Fig. 11b).
Each convention is written into a copy of the scene (key mc_stress_convention, docs/scenes.md) next to the original,
run with `dem run --model mc_stress`, and compared with the classical and MC-strain runs of the same scene.
docs/multicontact.md quotes the table this prints.
"""
import argparse
import itertools
import os
import subprocess
import sys

import h5py
import numpy as np

SCENES = [("rubber_plates", "scenes/validation/rubber_plates.yaml", "force at d/r = 0.4 [N]", 10.0),
          ("hydrogel_514", "scenes/hydrogel_514.yaml", "stress at 13.4 % [Pa]", 15.0)]
OWN = ["in", "out"]
LEVER = ["centres", "contact_point"]
SCALE = ["mean_trace", "text", "mean_pressure"]


def peak(path, name):
    with h5py.File(path, "r") as f:
        s = f["series"]
        if name == "rubber_plates":  # stress = plate force / (pi r^2): back to the force, at the deepest point
            return float(np.max(s["stress"][:]) * f["series"].attrs["sample_area"])
        return float(np.max(s["stress"][:]))


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
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    rows = {}
    ref = {}
    for name, scene, what, _ in SCENES:
        ref[name] = {m: peak(run(a.dem, scene, f"{a.out}/{name}-{m}.h5", m), name) for m in ("classical", "mc_strain")}
        for conv in itertools.product(OWN, LEVER, SCALE):
            h5 = f"{a.out}/{name}-mc_stress-{'-'.join(conv)}.h5"
            rows.setdefault(conv, {})[name] = peak(run(a.dem, scene, h5, "mc_stress", conv), name)
    hdr = "| own contact | lever | scale |"
    for name, _, what, tol in SCENES:
        hdr += f" {name} {what} | vs MC-strain (target within {tol:g} %) |"
    print(hdr)
    print("|---" * (3 + 2 * len(SCENES)) + "|")
    for name, _, what, _ in SCENES:
        c, s = ref[name]["classical"], ref[name]["mc_strain"]
        print(f"| reference: {name} | classical {c:.5g} | MC-strain {s:.5g} ({100 * (s / c - 1):+.1f} % over classical) |")
    for conv, r in rows.items():
        line = f"| {conv[0]} | {conv[1]} | {conv[2]} |"
        for name, _, _, tol in SCENES:
            c, s, v = ref[name]["classical"], ref[name]["mc_strain"], r[name]
            dev = 100 * (v / s - 1)
            line += f" {v:.5g} ({100 * (v / c - 1):+.1f} %) | {dev:+.1f} %{' ok' if abs(dev) <= tol else ''} |"
        print(line)


if __name__ == "__main__":
    sys.exit(main())
