#!/usr/bin/python3
"""A press at several mass scales, several fills each: what mass scaling changes (`make tablet-mass-scale`).

usage: tools/plot_tablet_mass_scale.py RUN.h5 [RUN.h5 ...] [-o mass_scale.png] [--table mass_scale.md]
                                       [--times times.txt]

Each RUN.h5 is a `dem run` of one press scene with `time.mass_scale` S (the file's mass_scale attribute) and some
random fill (tools/tablet_mass_scale.sh, `make tablet-mass-scale`). The press quantities are tools/plot_tablet.py's
(analyse). Per S the table gives the mean over the fills and, in brackets, their range, of: the relative density
where the upper punch pressure first reached 10, 25 and 45 MPa (interpolated on the loading), the Heckel yield
pressure, the transmission (lower / upper punch), the radial over the axial pressure and the elastic recovery of the
gap, the kinetic over the elastic energy at the end of the dwell, and the wall time (--times: lines "name status
seconds"); the last two columns are the densities at 10 and 45 MPa less the means at the smallest S. Panels:
pressure against relative density (one fill per S), the densities at 10 and 45 MPa against S (every fill a dot), the
radial over axial pressure and the recovery against S, and the wall time against S. Uses Debian's python3-h5py,
python3-numpy and python3-matplotlib.
"""
import argparse
import math
import os
import sys

import h5py
import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_tablet import analyse  # noqa: E402
from plot_tablet_models import dwell_end, read_times  # noqa: E402

PRESSURES = (10e6, 25e6, 45e6)  # 45, not 50: a stage that ends at 50 MPa may peak just below it between rows


def density_at(c, p):
    """relative density where the upper punch pressure first reaches p on the loading (nan if it never does)"""
    pu, d = c["p_up"], c["dens"]
    hit = np.nonzero((np.arange(len(pu)) <= c["k_max"]) & (pu >= p))[0]
    if not len(hit) or hit[0] == 0:
        return math.nan
    k = int(hit[0])
    w = (p - pu[k - 1]) / (pu[k] - pu[k - 1])
    return float(d[k - 1] + w * (d[k] - d[k - 1]))


def one(run, times):
    with h5py.File(run, "r") as f:
        scale = float(f.attrs.get("mass_scale", 1.0))
    c = analyse(run)
    k = dwell_end(c)
    ke = c["kinetic"][k] / c["elastic"][k] if c["elastic"][k] > 0 else math.nan
    name = os.path.basename(run)[:-3]
    return dict(name=name, scale=scale, c=c, dens=[density_at(c, p) for p in PRESSURES], yield_p=c["yield_p"],
                ratio=c["ratio"], radial=c["radial_ratio"], recovery=c["recovery"], ke=ke,
                wall=times.get(name, math.nan))


def finite_mean(values):
    """mean of the finite values, nan if there are none (S = 6400's recovery: the compact never let go)"""
    v = [x for x in values if np.isfinite(x)]
    return float(np.mean(v)) if v else math.nan


def stat(values, fmt):
    v = np.array([x for x in values if np.isfinite(x)])
    if not len(v):
        return "-"
    if len(v) == 1:
        return fmt.format(v[0])
    return (fmt + " (" + fmt + " - " + fmt + ")").format(v.mean(), v.min(), v.max())


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("runs", nargs="+", help="HDF5 files written by dem run")
    ap.add_argument("-o", "--output", default="mass_scale.png")
    ap.add_argument("--table", help="Markdown table to write")
    ap.add_argument("--times", help="lines 'name status seconds' (tools/tablet_mass_scale.sh)")
    a = ap.parse_args()
    times = read_times(a.times)
    rows = [one(r, times) for r in a.runs]
    scales = sorted({r["scale"] for r in rows})
    by = {s: [r for r in rows if r["scale"] == s] for s in scales}
    ref = [finite_mean([r["dens"][j] for r in by[scales[0]]]) for j in (0, 2)]

    head = ("| mass scale | fills | D at 10 MPa | D at 25 MPa | D at 45 MPa | Heckel yield [MPa] | lower / upper | "
            "radial / axial | elastic recovery [%%] | kinetic / elastic, end of dwell | wall time [s] | "
            "D at 10 MPa less S = %g | D at 45 MPa less S = %g |" % (scales[0], scales[0]))
    lines = [head, "|" + "---|" * 2 + "---:|" * 11]
    for s in scales:
        g = by[s]
        d = [finite_mean([r["dens"][j] for r in g]) for j in (0, 2)]
        lines.append("| %g | %d | %s | %s | %s | %s | %s | %s | %s | %s | %s | %+.4f | %+.4f |" % (
            s, len(g), stat([r["dens"][0] for r in g], "{:.4f}"), stat([r["dens"][1] for r in g], "{:.4f}"),
            stat([r["dens"][2] for r in g], "{:.4f}"), stat([r["yield_p"] / 1e6 for r in g], "{:.0f}"),
            stat([r["ratio"] for r in g], "{:.3f}"), stat([r["radial"] for r in g], "{:.3f}"),
            stat([100 * r["recovery"] for r in g], "{:.1f}"), stat([r["ke"] for r in g], "{:.1e}"),
            stat([r["wall"] for r in g], "{:.1f}"), d[0] - ref[0], d[1] - ref[1]))
    table = "\n".join(lines) + "\n"
    print(table, end="")
    if a.table:
        with open(a.table, "w") as f:
            f.write(table)

    fig, ax = plt.subplots(2, 2, figsize=(12, 9))
    cmap = plt.get_cmap("viridis")
    for i, s in enumerate(scales):
        c = by[s][0]["c"]
        col = cmap(i / max(1, len(scales) - 1))
        k = c["k_max"]
        ax[0, 0].plot(c["dens"][: k + 1], c["p_up"][: k + 1] / 1e6, color=col, label="S = %g" % s)
        ax[0, 0].plot(c["dens"][k:], c["p_up"][k:] / 1e6, color=col, ls=":")
    ax[0, 0].set(xlabel="relative density between the punches", ylabel="upper punch pressure [MPa]",
                 title="compaction (solid) and unloading (dotted), first fill of each S", ylim=(0, None))
    ax[0, 0].legend()
    for s in scales:
        x = [s] * len(by[s])
        ax[0, 1].plot(x, [r["dens"][2] for r in by[s]], "o", color="k", alpha=0.6)
        ax[0, 1].plot(x, [r["dens"][0] for r in by[s]], "s", color="C2", alpha=0.6)
        ax[1, 0].plot(x, [r["radial"] for r in by[s]], "o", color="C0", alpha=0.6)
        ax[1, 0].plot(x, [r["recovery"] for r in by[s]], "s", color="C3", alpha=0.6)
        ax[1, 1].plot(x, [r["wall"] for r in by[s]], "o", color="k", alpha=0.6)
    for j, col, lab in ((2, "k", "45 MPa"), (0, "C2", "10 MPa")):
        ax[0, 1].plot(scales, [finite_mean([r["dens"][j] for r in by[s]]) for s in scales], "-", color=col, label=lab)
    ax[0, 1].set(xscale="log", xlabel="mass scale S", ylabel="relative density",
                 title="density at 10 and 45 MPa: every fill a point, the line their mean")
    ax[0, 1].legend()
    ax[1, 0].plot(scales, [finite_mean([r["radial"] for r in by[s]]) for s in scales], "-", color="C0",
                  label="radial / axial pressure at the largest")
    ax[1, 0].plot(scales, [finite_mean([r["recovery"] for r in by[s]]) for s in scales], "-", color="C3",
                  label="elastic recovery of the gap")
    ax[1, 0].set(xscale="log", xlabel="mass scale S", ylabel="ratio", title="die wall and spring-back")
    ax[1, 0].legend()
    ax[1, 1].set(xscale="log", yscale="log", xlabel="mass scale S", ylabel="wall time [s]",
                 title="cost: the step grows as sqrt(S)")
    for x in ax.flat:
        x.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(a.output, dpi=110)
    print("wrote", a.output)


if __name__ == "__main__":
    main()
