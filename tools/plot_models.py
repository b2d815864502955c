#!/usr/bin/python3
"""Compares runs of one scene under different contact models (dem run --model ...) in one PNG.

usage: tools/plot_models.py -o OUT.png [--eq11 K=V,...] [--hertz K=V,...] RUN.h5 [RUN.h5 ...]

Scenes with a sample (a piston): engineering stress against strain, one curve per run (compression and return).
Scenes without one (the 3- and 5-sphere collisions of seed 000 section 3.4): kinetic energy against time and the
overlap of particles 0 and 1 (2 r - |x0 - x1|, geometric) against time. Each curve is labelled with the run's
model attribute (and MC-stress runs with their pressure convention). Closed forms drawn on a stress-strain plot:
  --eq11 r=,E=,nu=,beta=,area=   seed 000 Eq. 11, f = k_H d4^{3/2} [1 + 4 d beta nu A / V] with d4 = strain 2r,
                                 d = 2r - d4, A = pi (r/2) d4, V = 4/3 pi r^3 (the five-sphere box, Fig. 10)
  --hertz r=,E=,nu=,E2=,nu2=,area=,height=   Hertz f = 4/3 E* sqrt(r) d^{3/2}, d = strain height, sphere on a
                                 rigid-ish plate of E2, nu2 (the rubber sphere between plates, Fig. 4)
Reads the runs with the Python package (python/libdem: libdem.Run). Uses Debian's python3-h5py, python3-numpy and
python3-matplotlib; run it with /usr/bin/python3.
"""
import argparse
import os
import sys

import matplotlib
import numpy as np

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
from libdem import OutputError, Run  # noqa: E402


def attr(run, name, default=""):
    return str(run.attrs.get(name, default))


def kv(text):
    """"a=1,b=2" -> {"a": 1.0, "b": 2.0}"""
    try:
        return {k.strip(): float(v) for k, v in (item.split("=") for item in text.split(","))}
    except ValueError:
        sys.exit(f"plot_models: cannot read '{text}' (want key=value,...)")


def label_of(f):
    m = attr(f, "model")
    conv = attr(f, "mc_stress_convention")
    return f"{m} ({conv})" if conv and "stress" in m else m


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+", help="HDF5 files written by dem run")
    ap.add_argument("-o", "--output", required=True, help="PNG file")
    ap.add_argument("--eq11", help="r=,E=,nu=,beta=,area= : draw Eq. 11 (stress against strain)")
    ap.add_argument("--hertz", help="r=,E=,nu=,E2=,nu2=,area=,height= : draw the Hertz force (stress against strain)")
    a = ap.parse_args()
    try:
        files = [Run(path) for path in a.runs]
    except OutputError as e:
        sys.exit(f"plot_models: {e}")
    title = attr(files[0], "scene_name")
    sample = "strain" in files[0].series
    if sample:
        fig, ax = plt.subplots(figsize=(6.5, 4.5))
        top = 0.0
        for f in files:
            s = f.series
            strain = 100 * s["strain"]
            top = max(top, float(np.nanmax(strain)))
            ax.plot(strain, s["stress"], label=label_of(f))
        eps = np.linspace(0, top / 100, 200)
        if a.eq11:
            k = kv(a.eq11)
            r, es = k["r"], k["E"] / (2 * (1 - k["nu"] ** 2))
            d4 = eps * 2 * r
            f = 4 / 3 * es * np.sqrt(r / 2 * d4) * d4 * (
                1 + 4 * (2 * r - d4) * k["beta"] * k["nu"] * np.pi * (r / 2) * d4 / (4 / 3 * np.pi * r ** 3))
            ax.plot(100 * eps, f / k["area"], "k--", label="Eq. 11 (δ4 = strain · d)")
        if a.hertz:
            k = kv(a.hertz)
            es = 1 / ((1 - k["nu"] ** 2) / k["E"] + (1 - k["nu2"] ** 2) / k["E2"])
            d = eps * k["height"]
            ax.plot(100 * eps, 4 / 3 * es * np.sqrt(k["r"] * d) * d / k["area"], "k--", label="Hertz")
        ax.set_xlabel("engineering strain [%] (from the piston touching the sample)")
        ax.set_ylabel("stress [Pa]")
        ax.set_xlim(0, 1.05 * top if top > 0 else None)
        ax.legend()
    else:
        fig, (ax1, ax2) = plt.subplots(1, 2, figsize=(11, 4.2))
        for f in files:
            s = f.series
            label = label_of(f)
            ax1.plot(1e3 * s["time"], s["kinetic"], label=label)
            x = f.frame_field("position")
            r = f.radius
            d = r[0] + r[1] - np.linalg.norm(x[:, 0, :] - x[:, 1, :], axis=1)
            ax2.plot(1e3 * f.frame_time, 1e3 * np.maximum(d, 0), label=label)
        ax1.set_xlabel("time [ms]")
        ax1.set_ylabel("kinetic energy [J]")
        ax2.set_xlabel("time [ms]")
        ax2.set_ylabel("overlap of the central particle [mm]")
        ax1.legend()
        ax2.legend()
    fig.suptitle(title)
    fig.tight_layout()
    fig.savefig(a.output, dpi=120)
    print(f"plot_models: wrote {a.output}")


if __name__ == "__main__":
    main()
