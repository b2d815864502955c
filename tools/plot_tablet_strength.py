#!/usr/bin/env python3
"""Tensile strength against relative density from tablet-strength runs (tools/tablet_strength.sh): OUT/strength.png
and OUT/strength.md.

Usage: plot_tablet_strength.py OUT RUN.h5 [RUN.h5 ...]

Each run is a press cycle followed by a diametral compression (libdem.tablet.analyse: its "dia" part). The table
lists, per run: the largest upper punch pressure, the relative density in the die there, the tablet's diameter,
thickness and relative density out of the die, the failure load (libdem.tablet.diametral) and the tensile strength
2 F / (pi D t).
A Ryshkewitch-Duckworth line, sigma_t = sigma_0 exp(-b (1 - D)), is fitted to the runs (least squares on ln sigma_t)
and drawn beside the published MCC tablet that could be verified here (PUBLISHED below).
"""
import math
import os
import sys

import numpy as np

from libdem import tablet
from libdem.output import Run

# Published MCC tablets (diametral compression), each (relative density, tensile strength [MPa], source). Only values
# read in the source itself are listed: virgin MCC compacts at solid fraction 0.85, unlubricated and lubricated die
# (AAPS PharmSciTech 12(3) (2011) 834-853, doi:10.1208/s12249-011-9640-z, Table III).
PUBLISHED = [(0.85, 8.69, "MCC, solid fraction 0.85, unlubricated (AAPS PharmSciTech 2011, Table III)"),
             (0.85, 8.12, "MCC, solid fraction 0.85, lubricated (AAPS PharmSciTech 2011, Table III)")]


def law_of(path):
    """The run's normal contact law, from its effects attribute"""
    fx = str(Run(path).attrs.get("effects", ""))
    law = next((w for w in ("mdr", "thornton_ning", "mc_stress", "mc_strain") if w in fx.split("+")), "classical")
    return law + (" + bonds" if law == "thornton_ning" else "")


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__)
    out, paths = argv[1], argv[2:]
    rows = []
    for p in paths:
        c = tablet.analyse(p)
        d = c.get("dia")
        if not d:
            print(f"plot_tablet_strength: {p} has no diametral compression (walls platen_a, platen_b)", file=sys.stderr)
            continue
        rows.append(dict(path=os.path.basename(p), p_max=c["p_max"] * 1e-6, d_die=c["dens"][c["k_max"]],
                         d_out=d["density"], diam=d["diameter"], thick=d["thickness"], peak=d["peak"],
                         tensile=d["tensile"] * 1e-6, failed=d["failed"], whole=d["whole"], law=law_of(p)))
    if not rows:
        sys.exit("plot_tablet_strength: no run to draw")
    rows.sort(key=lambda r: r["p_max"])
    dens = np.array([r["d_out"] for r in rows])
    sig = np.array([r["tensile"] for r in rows])
    b = s0 = float("nan")
    ok = np.isfinite(sig) & (sig > 0)  # the tablets that held together out of the die
    if np.count_nonzero(ok) >= 2:
        slope, icpt = np.polyfit(1 - dens[ok], np.log(sig[ok]), 1)
        b, s0 = -slope, math.exp(icpt)
    with open(os.path.join(out, "strength.md"), "w") as f:
        f.write("| run | pressure [MPa] | density in die at it | D [mm] | t [mm] | density out of die | failure load "
                "[N] | tensile strength [MPa] | cracked |\n|---|---|---|---|---|---|---|---|---|\n")
        for r in rows:
            cracked = ("yes" if r["failed"] else "no (largest force)") if r["whole"] else "came apart out of the die"
            f.write(f"| {r['path']} | {r['p_max']:.1f} | {r['d_die']:.3f} | {1e3 * r['diam']:.3f} | "
                    f"{1e3 * r['thick']:.3f} | {r['d_out']:.3f} | {r['peak']:.3g} | {r['tensile']:.3g} | {cracked} |\n")
        f.write(f"\nRyshkewitch-Duckworth fit to these runs: sigma_0 = {s0:.3g} MPa, b = {b:.3g} "
                "(sigma_t = sigma_0 exp(-b (1 - D)), D out of die)\n")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(1, 2, figsize=(12, 4.8))
    ax[0].plot(dens, sig, "o-", label=f"libdem: {rows[0]['law']} (out-of-die density)")
    for r in rows:
        ax[0].annotate(f"{r['p_max']:.0f} MPa", (r["d_out"], r["tensile"]), fontsize=8, xytext=(4, -10),
                       textcoords="offset points")
    if math.isfinite(b):
        dd = np.linspace(min(dens.min(), 0.5), 1.0, 50)
        ax[0].plot(dd, s0 * np.exp(-b * (1 - dd)), "--", lw=0.8,
                   label=f"Ryshkewitch-Duckworth fit: {s0:.3g} MPa exp(-{b:.3g} (1 - D))")
    for k, (d, s, what) in enumerate(PUBLISHED):
        ax[0].plot([d], [s], "s", color="k", ms=5, label=what if k == 0 else None)
    ax[0].set(xlabel="relative density D (out of die)", ylabel="tensile strength 2F/(pi D t) [MPa]",
              title="tensile strength against density")
    ax[0].legend(fontsize=7)
    pr = np.array([r["p_max"] for r in rows])
    ax[1].plot(pr, sig, "o-", label="tensile strength [MPa]")
    ax2 = ax[1].twinx()
    ax2.plot(pr, [r["d_die"] for r in rows], "s--", color="C1", label="density in the die at the pressure")
    ax2.plot(pr, dens, "^--", color="C2", label="density out of the die")
    ax2.set_ylabel("relative density")
    ax[1].set(xlabel="compaction pressure [MPa]", ylabel="tensile strength [MPa]", title="tabletability")
    h1, l1 = ax[1].get_legend_handles_labels()
    h2, l2 = ax2.get_legend_handles_labels()
    ax[1].legend(h1 + h2, l1 + l2, fontsize=7, loc="upper left")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "strength.png"), dpi=110)
    print(open(os.path.join(out, "strength.md")).read())


if __name__ == "__main__":
    main(sys.argv)
