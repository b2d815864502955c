#!/usr/bin/python3
"""The tablet report of a press cycle run by dem run: one PNG and a few numbers.

usage: tools/plot_tablet.py RUN.h5 [MORE.h5 ...] [-o RUN_tablet.png] [--die NAME] [--upper NAME] [--lower NAME]

A run continued with `dem run --restart` (each output file holds the steps from its restart on) is given as its
files in order: their series are joined by step number, a later file's rows replacing the earlier's from its first
step on (a restart from an earlier checkpoint repeats steps), and a gap between them is refused.
Reads the run's time series (/series: wall_position, wall_force, the walls' names and shapes) and the spheres' radii.
The die is the cylinder wall (or --die), the punches the planes named upper and lower (or --upper, --lower).
  - punch pressure: the normal force the powder exerts on a punch over the bore's area pi R^2 [Pa];
  - gap: the distance between the punch faces (their lands) along the lower punch's normal; relative density D = the
    spheres' volume / (pi R^2 gap + the punches' cups, pi c (3 r^2 + c^2) / 6 each), as if the compact filled the bore
    between the punches (the elastic recovery below is the gap's: a concave tablet's band);
  - Heckel: ln(1 / (1 - D)) against the upper punch pressure over the loading (up to the largest pressure), a line
    fitted over its upper half; the mean yield pressure is 1 / slope;
  - transmission ratio: lower over upper punch pressure while the upper punch is loaded (above 10 % of its largest);
    the die-wall friction is the die's force along its axis;
  - radial die-wall pressure: the die's normal force (/series/wall_normal_force: the sum of the particles' forces
    along their contact normals, radial on a cylinder) over the bore's wall between the punches, 2 pi R gap; its
    ratio to the upper punch pressure at the largest pressure (the radial transmission, Janssen's coefficient);
  - elastic recovery: (gap where the upper punch lets go - gap at the largest pressure) / gap at the largest pressure;
  - ejection: the lower punch's force against its travel once it rises after the upper punch let go.
Panels: pressures against upper punch travel (with the radial die-wall pressure and the wall friction), pressure
against relative density, the Heckel plot with its fit, and the ejection force against lower punch travel. Prints
one line of numbers: `key=value` pairs. Uses Debian's python3-h5py, python3-numpy and python3-matplotlib.
"""
import argparse
import math
import sys

import h5py
import numpy as np
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def fail(msg):
    sys.exit(f"plot_tablet: {msg}")


def wall_index(names, want, what):
    if want in names:
        return names.index(want)
    fail(f"no wall named '{want}' for the {what} (walls: {', '.join(names)}; name it with --{what})")


SERIES_ROWS = ("time", "step", "wall_position", "wall_force", "wall_normal_force", "kinetic", "elastic")


def read_part(path):
    """one output file of dem run: its per-row series, the walls' names and shapes, the radii and the model"""
    try:
        f = h5py.File(path, "r")
    except OSError as e:
        fail(f"cannot open {path}: {e}")
    with f:
        s = f.get("series")
        if s is None or "wall_force" not in s or "wall_radius" not in s:
            fail(f"{path}: no wall series with the walls' shapes (a run of a scene with walls, a libdem that writes the wall shapes)")
        raw = s.attrs["wall_names"]
        p = dict(names=(raw.decode() if isinstance(raw, bytes) else str(raw)).split("\n"),
                 radius=s["wall_radius"][:], normal=s["wall_normal"][:], r=f["particles/radius"][:])
        n = len(s["time"])
        p["step"] = s["step"][:] if "step" in s else np.arange(n, dtype=float)
        for k in SERIES_ROWS:
            if k != "step":
                p[k] = s[k][:] if k in s else None
        # concave punches (dem_wall.cup_radius, cup_depth): their cups add to the space between the punches
        for k in ("wall_cup_radius", "wall_cup_depth"):
            p[k] = s[k][:] if k in s else np.zeros(len(p["radius"]))
        model = f.attrs.get("model", b"")
        p["model"] = model.decode() if isinstance(model, bytes) else str(model)
    return p


def read_run(paths):
    """a run's parts (a str: one file) joined by step: each later part replaces the rows from its first step on"""
    paths = [paths] if isinstance(paths, str) else list(paths)
    run = read_part(paths[0])
    start = run["step"][0] if len(run["step"]) else -math.inf  # the previous part's first step
    for prev, path in zip(paths, paths[1:]):
        p = read_part(path)
        if p["names"] != run["names"] or not np.array_equal(p["r"], run["r"]) or p["model"] != run["model"]:
            fail(f"{path} does not continue {prev}: other walls, spheres or contact model (not a --restart of the "
                 "same run)")
        if not len(p["step"]):
            continue
        first = p["step"][0]
        if first <= start:
            fail(f"{path} starts at step {first:.0f}, not after {prev} does (step {start:.0f}): give the parts in the "
                 "order they ran")
        if first > run["step"][-1]:
            fail(f"{path} starts at step {first:.0f}, after {prev} ends (step {run['step'][-1]:.0f}): a part between "
                 "them is missing")
        keep, start = run["step"] < first, first
        for k in SERIES_ROWS:
            both = run[k] is not None and p[k] is not None
            run[k] = np.concatenate([run[k][keep], p[k]]) if both else None
    return run


def analyse(run, die_name=None, upper="upper", lower="lower"):
    """The press cycle of one run (a file, or the files of a run continued by --restart, in order): a dict of the
    series (arrays over the rows) and the report's numbers."""
    d = read_run(run)
    names, t, pos, force, radius, normal = d["names"], d["time"], d["wall_position"], d["wall_force"], d["radius"], \
        d["normal"]
    cup_r, cup_d, fnorm, r, model = d["wall_cup_radius"], d["wall_cup_depth"], d["wall_normal_force"], d["r"], \
        d["model"]
    kinetic = d["kinetic"] if d["kinetic"] is not None else np.full(len(t), np.nan)
    elastic = d["elastic"] if d["elastic"] is not None else np.full(len(t), np.nan)
    if die_name:
        die = wall_index(names, die_name, "die")
    else:
        cyl = [k for k in range(len(names)) if radius[k] > 0]
        if not cyl:
            fail("no cylinder wall (the die); name it with --die")
        die = cyl[0]
    up, lo = wall_index(names, upper, "upper"), wall_index(names, lower, "lower")
    area = math.pi * radius[die] ** 2
    solid = float(np.sum(4.0 / 3.0 * math.pi * r**3))
    n_up, n_lo, axis = normal[up], normal[lo], normal[die]
    # the force the powder exerts on a plane along -normal (pushing it back) counts positive, as a servo's
    p_up = -(force[:, up, :] @ n_up) / area
    p_lo = -(force[:, lo, :] @ n_lo) / area
    die_axial = force[:, die, :] @ axis
    gap = (pos[:, up, :] - pos[:, lo, :]) @ n_lo  # between the punches' lands
    cups = sum(math.pi * cup_d[k] * (3 * cup_r[k] ** 2 + cup_d[k] ** 2) / 6 for k in (up, lo))
    dens = solid / (area * gap + cups)
    p_rad = fnorm[:, die] / (2 * math.pi * radius[die] * gap) if fnorm is not None else np.full(len(t), np.nan)
    travel_up = (pos[0, up, :] - pos[:, up, :]) @ n_lo  # downwards travel of the upper punch
    k_max = int(np.argmax(p_up))
    p_max = p_up[k_max]
    if not p_max > 0:
        fail("the upper punch never pressed on the powder")
    after = np.nonzero((np.arange(len(t)) > k_max) & (p_up <= 1e-3 * p_max))[0]
    k_rel = int(after[0]) if len(after) else None
    # Heckel over the loading: from where the punch starts pressing (2 % of the largest) to the largest pressure
    load = np.nonzero((np.arange(len(t)) <= k_max) & (p_up > 0.02 * p_max) & (dens < 1))[0]
    heckel = -np.log(1 - dens[load])
    fit = load[p_up[load] >= 0.5 * p_max]
    slope = intercept = yield_p = float("nan")
    if len(fit) >= 2:
        slope, intercept = np.polyfit(p_up[fit], -np.log(1 - dens[fit]), 1)
        yield_p = 1 / slope if slope > 0 else float("nan")
    loaded = p_up > 0.1 * p_max
    ratio = float(np.median(p_lo[loaded] / p_up[loaded])) if loaded.any() else float("nan")
    recovery = (gap[k_rel] - gap[k_max]) / gap[k_max] if k_rel is not None else float("nan")
    radial_ratio = float(p_rad[k_max] / p_max)
    # ejection: the lower punch rising after the upper one let go
    ej = np.array([], dtype=int)
    if k_rel is not None:
        z_lo = pos[:, lo, :] @ n_lo
        ej = np.nonzero((np.arange(len(t)) >= k_rel) & (z_lo > z_lo[k_rel] + 1e-12))[0]
    eject_travel = (pos[ej, lo, :] - pos[k_rel, lo, :]) @ n_lo if len(ej) else np.array([])
    eject_force = -(force[ej, lo, :] @ n_lo) if len(ej) else np.array([])
    return dict(t=t, model=model, area=area, solid=solid, p_up=p_up, p_lo=p_lo, p_rad=p_rad, die_axial=die_axial,
                gap=gap, dens=dens, travel_up=travel_up, k_max=k_max, p_max=p_max, k_rel=k_rel, load=load,
                heckel=heckel, slope=slope, intercept=intercept, yield_p=yield_p, ratio=ratio, recovery=recovery,
                radial_ratio=radial_ratio, ej=ej, eject_travel=eject_travel, eject_force=eject_force,
                kinetic=kinetic, elastic=elastic)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("run", nargs="+", help="HDF5 file written by dem run (several: a run and its --restart "
                    "continuations, in order)")
    ap.add_argument("-o", "--output", help="PNG file (default: RUN_tablet.png)")
    ap.add_argument("--die", help="the die's wall name (default: the first cylinder)")
    ap.add_argument("--upper", default="upper", help="the upper punch's wall name")
    ap.add_argument("--lower", default="lower", help="the lower punch's wall name")
    a = ap.parse_args()
    first = a.run[0]
    out = a.output or (first[:-3] if first.endswith(".h5") else first) + "_tablet.png"
    c = analyse(a.run, a.die, a.upper, a.lower)
    t, p_up, p_lo, p_rad, die_axial, area = c["t"], c["p_up"], c["p_lo"], c["p_rad"], c["die_axial"], c["area"]
    dens, travel_up, k_max, p_max, k_rel = c["dens"], c["travel_up"], c["k_max"], c["p_max"], c["k_rel"]
    load, heckel, slope, intercept, yield_p = c["load"], c["heckel"], c["slope"], c["intercept"], c["yield_p"]
    ratio, recovery, radial_ratio = c["ratio"], c["recovery"], c["radial_ratio"]
    ej, eject_travel, eject_force, solid = c["ej"], c["eject_travel"], c["eject_force"], c["solid"]

    fig, ax = plt.subplots(2, 2, figsize=(11, 8.5))
    cyc = slice(0, (k_rel if k_rel is not None else len(t) - 1) + 1)  # loading and unloading, before the punch leaves
    ax[0, 0].plot(1e3 * travel_up[cyc], 1e-3 * p_up[cyc], label="upper punch")
    ax[0, 0].plot(1e3 * travel_up[cyc], 1e-3 * p_lo[cyc], label="lower punch")
    ax[0, 0].plot(1e3 * travel_up[cyc], 1e-3 * p_rad[cyc], label="die wall, radial")
    ax[0, 0].plot(1e3 * travel_up[cyc], 1e-3 * die_axial[cyc] / area, label="die wall, axial (friction) / bore area",
                  lw=0.8)
    ax[0, 0].set(xlabel="upper punch travel [mm]", ylabel="pressure [kPa]", title="pressure against displacement")
    ax[0, 0].legend(fontsize=8)
    ax[0, 1].plot(dens[: k_max + 1], 1e-3 * p_up[: k_max + 1], label="loading")
    if k_rel is not None:
        ax[0, 1].plot(dens[k_max : k_rel + 1], 1e-3 * p_up[k_max : k_rel + 1], label="unloading")
    ax[0, 1].set(xlabel="relative density D", ylabel="upper punch pressure [kPa]", title="compaction curve")
    ax[0, 1].legend(fontsize=8)
    ax[1, 0].plot(1e-3 * p_up[load], heckel, "o", ms=3, label="ln 1/(1-D)")
    if math.isfinite(slope):
        pp = np.linspace(0, p_max, 50)
        ax[1, 0].plot(1e-3 * pp, slope * pp + intercept, "--",
                      label=f"fit: yield pressure {1e-3 * yield_p:.3g} kPa" if math.isfinite(yield_p) else "fit")
    ax[1, 0].set(xlabel="upper punch pressure [kPa]", ylabel="ln 1/(1 - D)", title="Heckel plot")
    ax[1, 0].legend(fontsize=8)
    if len(ej):
        ax[1, 1].plot(1e3 * eject_travel, eject_force)
    ax[1, 1].set(xlabel="lower punch travel [mm]", ylabel="lower punch force [N]", title="ejection")
    fig.suptitle(f"{' + '.join(a.run)}: transmission {ratio:.3f}, radial/axial {radial_ratio:.3f}, elastic recovery "
                 f"{100 * recovery:.2f} %", fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    print(f"png={out} bore_area_m2={area:.6g} solid_m3={solid:.6g} max_upper_pa={p_max:.6g} "
          f"density_at_max={dens[k_max]:.6g} yield_pa={yield_p:.6g} transmission={ratio:.6g} "
          f"radial_pa={p_rad[k_max]:.6g} radial_ratio={radial_ratio:.6g} "
          f"elastic_recovery={recovery:.6g} max_ejection_n={float(np.max(eject_force)) if len(ej) else float('nan'):.6g}")


if __name__ == "__main__":
    main()
