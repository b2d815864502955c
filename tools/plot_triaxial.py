#!/usr/bin/python3
"""Seed 001 Fig. 5: the deviatoric stress sigma_d = sigma_p - sigma_c against the axial strain eps = log(h0/h) of a
triaxial run (walls 0 and 1 the bottom and top platens; sigma_p the top platen's force over the initial cross-section;
h0 the platen distance when the shearing starts), for each run given on one plot.
usage: plot_triaxial.py -o OUT.png [--sigma-c PA] [--area M2] [--start S] RUN.h5 [RUN.h5 ...]
Prints each run's peak sigma_d and, with two or more runs, the largest and the mean difference between the first and
each other over their common strain range (200 points), relative to the first run's peak."""
import argparse

import h5py
import numpy as np


def curve(path, sigma_c, area, start):
    with h5py.File(path, "r") as f:
        t = f["series/time"][:]
        z = f["series/wall_position"][:, :, 2]
        fz = f["series/wall_force"][:, 1, 2]  # the top platen: the grains push it up
        name = f.attrs["scene_name"]
        name = name.decode() if isinstance(name, bytes) else str(name)
    h = z[:, 1] - z[:, 0]
    # the row nearest the start: stages last whole steps, so the start is up to a step off the time asked (with
    # dt 5.8004e-7 s, 10 ms of servo ends at 0.0099999 s)
    shear = t >= start - 0.5 * (t[1] - t[0])
    h0 = h[shear][0]
    eps = np.log(h0 / h[shear])
    sd = fz[shear] / area - sigma_c
    return name, eps, sd


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("-o", required=True)
    ap.add_argument("--sigma-c", type=float, default=1e5)
    ap.add_argument("--area", type=float, default=np.pi * 0.025**2)
    ap.add_argument("--start", type=float, default=0.01, help="time the shearing starts [s]")
    ap.add_argument("runs", nargs="+")
    a = ap.parse_args()
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    curves = [curve(p, a.sigma_c, a.area, a.start) for p in a.runs]
    for name, eps, sd in curves:
        print(f"{name}: strain to {eps.max():.4f}, peak sigma_d {sd.max() / 1e3:.1f} kPa")
        ax.plot(eps, sd / 1e3, label=name)
    name0, e0, s0 = curves[0]
    for name, eps, sd in curves[1:]:
        top = min(e0.max(), eps.max())
        grid = np.linspace(0, top, 200)
        d = np.abs(np.interp(grid, e0, s0) - np.interp(grid, eps, sd)) / s0.max()
        print(f"{name} vs {name0}: largest difference {100 * d.max():.3g} % of the peak (at strain "
              f"{grid[d.argmax()]:.4f}), mean {100 * d.mean():.3g} %, strain 0 to {top:.4f}")
    ax.set_xlabel("axial strain log(h0 / h)")
    ax.set_ylabel("deviatoric stress sigma_p - sigma_c [kPa]")
    ax.set_title("seed 001 Fig. 5: triaxial test, confining 100 kPa", fontsize=10)
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(a.o, dpi=120)


if __name__ == "__main__":
    main()
