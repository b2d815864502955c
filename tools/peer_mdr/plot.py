#!/usr/bin/python3
"""Draws the MDR peer check: LAMMPS's single-contact curves with the independent reference on top, a zoom on the
adhesive (tensile) branch, and the die compaction's punch force against punch displacement.

usage: plot.py OUTDIR   (reads OUTDIR/single_*.csv, reference_*.csv, die_force.csv, libdem_die_force.csv when there;
writes OUTDIR/peer_mdr.png)
"""
import os
import sys

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cases as C  # noqa: E402


def load(path, skip):
    return np.loadtxt(path, delimiter=",", skiprows=skip)


def main():
    out = sys.argv[1]
    fig, ax = plt.subplots(2, 3, figsize=(19, 9.5))
    colors = {"g0": "C0", "adh": "C1", "adh50": "C3"}
    for col, kind in enumerate(("pair", "wall")):
        a = ax[0, col]
        for tag, color in colors.items():
            case = f"{kind}_{tag}"
            lam = load(os.path.join(out, f"single_{case}.csv"), 3)
            ref = load(os.path.join(out, f"reference_{case}.csv"), 2)
            g = C.SINGLE[case]["gamma"]
            a.plot(lam[:, 3] / C.R, lam[:, 5], color=color, lw=2.5, alpha=0.45,
                   label=f"LAMMPS, surface energy {g:g} J/m$^2$")
            a.plot(ref[:, 2] / C.R, ref[:, 4], color=color, lw=0.8, ls="--", label="reference (docs/laws/mdr.md)")
        if kind == "pair":
            lam = load(os.path.join(out, "single_pair_uneq.csv"), 3)
            ref = load(os.path.join(out, "reference_pair_uneq.csv"), 2)
            r2 = C.SINGLE["pair_uneq"]["R2"]
            a.plot(lam[:, 3] / C.R, lam[:, 5], color="C2", lw=2.5, alpha=0.45,
                   label=f"LAMMPS, R {C.R * 1e3:g} and {r2 * 1e3:g} mm, {C.SINGLE['pair_uneq']['gamma']:g} J/m$^2$")
            a.plot(ref[:, 2] / C.R, ref[:, 4], color="C2", lw=0.8, ls="--", label="reference")
        a.set_xlabel("apparent overlap / R" + (" (two spheres: sum of both)" if kind == "pair" else ""))
        a.set_ylabel("normal force (N)")
        a.set_title(("two equal spheres" if kind == "pair" else "sphere on a flat wall")
                    + f", R {C.R * 1e3:g} mm: load, unload, reload, unload")
        a.grid(alpha=0.3)
        a.legend(fontsize=7)
    # one sphere between six closing planes: force of one plane, and the free-surface fraction psi
    a = ax[0, 2]
    lam = load(os.path.join(out, "single_box_g0.csv"), 3)
    ref = load(os.path.join(out, "reference_box_g0.csv"), 2)
    a.plot(lam[:, 3] / C.R, lam[:, 5], color="C4", lw=2.5, alpha=0.45, label="LAMMPS: force of one plane")
    a.plot(ref[:, 2] / C.R, ref[:, 4], color="C4", lw=0.8, ls="--", label="reference")
    a.set_xlabel("apparent overlap of each plane / R")
    a.set_ylabel("normal force (N)")
    a.set_title(f"sphere between six closing planes (bulk below psi_b {C.PSI_B:g})")
    a.grid(alpha=0.3)
    a.legend(fontsize=7, loc="upper left")
    b = ax[1, 2]
    b.plot(lam[:, 3] / C.R, lam[:, 6], color="C5", lw=2.5, alpha=0.45, label="LAMMPS psi")
    b.plot(ref[:, 2] / C.R, ref[:, 5], color="C5", lw=0.8, ls="--", label="reference psi")
    b.axhline(C.PSI_B, color="k", lw=0.6, ls=":")
    b.set_xlabel("apparent overlap of each plane / R")
    b.set_ylabel("free-surface fraction psi")
    b.set_title("the six-plane sphere's free-surface fraction")
    b.grid(alpha=0.3)
    b.legend(fontsize=7)
    # the last pull-off, strong adhesion: the final unloading's rows below 0.5 N, against the overlap measured
    # from where the force last is not zero
    a = ax[1, 0]
    for kind, color in (("pair", "C3"), ("wall", "C2")):
        case = f"{kind}_adh50"
        start = sum(C.phase_steps(C.SINGLE[case]["path"])[:3])
        lam = load(os.path.join(out, f"single_{case}.csv"), 3)
        ref = load(os.path.join(out, f"reference_{case}.csv"), 2)
        lam = lam[(lam[:, 0] > start) & (lam[:, 5] < 0.5)]
        ref = ref[(ref[:, 0] > start) & (ref[:, 4] < 0.5)]
        x0 = lam[np.nonzero(lam[:, 5])[0][-1], 3]
        a.plot((lam[:, 3] - x0) * 1e6, lam[:, 5], "o", color=color, ms=3, alpha=0.5, label=f"LAMMPS {case}")
        a.plot((ref[:, 2] - x0) * 1e6, ref[:, 4], "-", color="k", lw=0.7, label=f"reference {case}")
    a.set_xlim(-0.3, 2.5)
    a.set_xlabel("apparent overlap above the pull-off point (µm)")
    a.set_ylabel("normal force (N)")
    a.set_title(f"the final pull-off, surface energy {C.GAMMA_STRONG:g} J/m$^2$ (every step)")
    a.grid(alpha=0.3)
    a.legend(fontsize=7)
    # die
    a = ax[1, 1]
    die = os.path.join(out, "die_force.csv")
    if os.path.exists(die):
        d = load(die, 3)
        area = np.pi * C.DIE["die_radius"] ** 2
        a.plot(d[:, 0] * 1e3, d[:, 1], label="upper punch, LAMMPS")
        a.plot(d[:, 0] * 1e3, d[:, 2], label="lower punch, LAMMPS")
        ours = os.path.join(out, "libdem_die_force.csv")
        if os.path.exists(ours):  # the same press by libdem's MDR law (libdem_die.py)
            o = load(ours, 2)
            a.plot(o[:, 0] * 1e3, o[:, 1], "k--", lw=0.9, label="upper punch, libdem")
            a.plot(o[:, 0] * 1e3, o[:, 2], "k:", lw=0.9, label="lower punch, libdem")
        a.set_xlabel("upper punch travel (mm)")
        a.set_ylabel("punch force (N)")
        sec = a.secondary_yaxis("right", functions=(lambda f: f / area / 1e6, lambda p: p * area * 1e6))
        sec.set_ylabel("punch pressure (MPa)")
        a.set_title(f"MDR die: {C.DIE['n']} spheres, die radius {C.DIE['die_radius'] * 1e3:g} mm, "
                    f"punch {C.DIE['punch_speed'] * 1e3:g} mm/s")
        a.grid(alpha=0.3)
        a.legend(fontsize=8, loc="upper left")
        if d.shape[1] > 3:
            ld = d[:np.argmax(d[:, 0]) + 1]           # loading rows: travel and solid fraction both increase
            top = a.secondary_xaxis("top", functions=(
                lambda x: np.interp(x, ld[:, 0] * 1e3, ld[:, 3]), lambda p: np.interp(p, ld[:, 3], ld[:, 0] * 1e3)))
            top.set_xlabel("solid fraction")
    fig.tight_layout()
    png = os.path.join(out, "peer_mdr.png")
    fig.savefig(png, dpi=110)
    print(f"plot: {png}")


if __name__ == "__main__":
    main()
