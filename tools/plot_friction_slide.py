#!/usr/bin/python3
"""Seed 001 Fig. 6: the friction force along the sliding direction and the height of a sphere pushed across a flat
membrane, against its horizontal position, for each run given (the first particle is the sphere).
usage: plot_friction_slide.py -o OUT.png RUN.h5 [RUN.h5 ...]
Prints, per run, the mean friction force after the first millimetre and its spread: max |F - mean| / mean and the
peak-to-peak height variation."""
import argparse

import h5py
import numpy as np


def slide(path):
    with h5py.File(path, "r") as f:
        x = f["frames/position"][:, 0, :]
        force = f["frames/force"][:, 0, :]
        name = f.attrs["scene_name"]
        name = name.decode() if isinstance(name, bytes) else str(name)
    friction = -force[:, 0]  # the force on the sphere against its motion (+x)
    sliding = x[:, 0] >= x[0, 0] + 1e-3  # past the first millimetre: the spring has built up
    mean = friction[sliding].mean()
    spread = np.abs(friction[sliding] - mean).max() / mean
    height = np.ptp(x[sliding, 2])
    return name, x, friction, mean, spread, height


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("-o", required=True)
    ap.add_argument("runs", nargs="+")
    a = ap.parse_args()
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, (top, bottom) = plt.subplots(2, 1, figsize=(7, 6), sharex=True)
    for path in a.runs:
        name, x, friction, mean, spread, height = slide(path)
        print(f"{name}: friction {mean * 1e6:.2f} uN mean, largest deviation {100 * spread:.3g} % of it; "
              f"height varies by {height * 1e6:.3g} um")
        top.plot(x[:, 0] * 1e3, friction * 1e6, label=f"{name} ({100 * spread:.2g} % spread)")
        bottom.plot(x[:, 0] * 1e3, x[:, 2] * 1e3, label=name)
    top.set_ylabel("friction force [uN]")
    bottom.set_ylabel("sphere centre height [mm]")
    bottom.set_xlabel("horizontal position [mm]")
    top.legend(fontsize=8)
    top.set_title("seed 001 Fig. 6: sphere (r 2 mm) pushed at 0.05 m/s across a flat membrane", fontsize=10)
    fig.tight_layout()
    fig.savefig(a.o, dpi=120)


if __name__ == "__main__":
    main()
