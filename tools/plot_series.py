#!/usr/bin/python3
"""Draws a dem run's time series (HDF5 /series) to a PNG.

usage: tools/plot_series.py RUN.h5 [-o RUN.png]

Panels: kinetic and elastic energy against time; wall forces along each wall's normal axis; and, when the scene
names a sample, engineering stress against strain (compression positive). Reads the run with the Python package
(python/libdem: libdem.Run). Uses Debian's python3-h5py, python3-numpy and python3-matplotlib (installed by
scripts/install-deps.sh); run it with /usr/bin/python3.
"""
import argparse
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "python"))
from libdem import OutputError, Run  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run", help="HDF5 file written by dem run")
    ap.add_argument("-o", "--output", help="PNG file (default: RUN with .png)")
    a = ap.parse_args()
    out = a.output or (a.run[:-3] if a.run.endswith(".h5") else a.run) + ".png"
    try:
        run = Run(a.run)
    except OutputError as e:
        sys.exit(f"plot_series: {e}")
    s = run.series
    t = s["time"]
    sample = "strain" in s
    panels = 3 if sample else 2
    fig, ax = plt.subplots(1, panels, figsize=(5.2 * panels, 4.2))
    name = run.attrs.get("scene_name", run.paths[0])
    fig.suptitle(f"{name} ({run.attrs.get('precision', '')}, {run.attrs.get('effects', '')})", fontsize=10)
    ax[0].plot(t, s["kinetic"], label="kinetic")
    ax[0].plot(t, s["elastic"], label="elastic (Hertz)")
    ax[0].set_xlabel("time [s]")
    ax[0].set_ylabel("energy [J]")
    ax[0].set_yscale("symlog", linthresh=1e-9)
    ax[0].legend()
    if "wall_force" in s:
        wf = s["wall_force"]
        for k in range(wf.shape[1]):
            mag = (wf[:, k, :] ** 2).sum(axis=1) ** 0.5
            if mag.max() > 0:
                ax[1].plot(t, mag, label=run.wall_names[k] if k < len(run.wall_names) else f"wall {k}")
        ax[1].legend(fontsize=7)
    ax[1].set_xlabel("time [s]")
    ax[1].set_ylabel("|force on wall| [N]")
    if sample:
        eps, sig = s["strain"], s["stress"]
        keep = eps >= -0.002  # the loading part: leave out a piston still approaching the sample
        ax[2].plot(eps[keep] * 100, sig[keep], ".-", ms=2)
        ax[2].set_xlabel("strain [%]")
        ax[2].set_ylabel("stress [Pa]")
        ax[2].set_title("piston: compression positive", fontsize=9)
    for x in ax:
        x.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"plot_series: wrote {out}")


if __name__ == "__main__":
    main()
