"""The tablet report of a press cycle run by dem run: one PNG and one line of numbers (tools/plot_tablet.py,
`python3 -m libdem report`).

Reads the run's time series (/series: wall_position, wall_force, wall_normal_force, the walls' names and shapes) and
the spheres' radii; a run in parts (--restart) is given as its files in order (libdem.Run joins them by step). The die
is the cylinder wall (or `die`), the punches the planes named upper and lower (or `upper`, `lower`).
  - punch pressure: the normal force the powder exerts on a punch over the bore's area pi R^2;
  - gap: the distance between the punch faces (their lands) along the lower punch's normal; relative density D = the
    spheres' volume / (pi R^2 gap + the punches' cups, pi c (3 r^2 + c^2) / 6 each), as if the compact filled the bore
    between the punches (the elastic recovery below is the gap's: a concave tablet's band);
  - Heckel: ln(1 / (1 - D)) against the upper punch pressure over the loading (up to the largest pressure), a line
    fitted over its upper half; the mean yield pressure is 1 / slope;
  - transmission ratio: the median of lower over upper punch pressure over the loading rows: the upper punch moving
    in and its pressure rising, above 10 % of the largest pressure and up to it (the dwell and the unloading, where
    friction in the die turns round, are left out);
  - radial die-wall pressure: the die's normal force (the sum of the particles' forces along their contact normals,
    radial on a cylinder) over the bore's wall between the punches, 2 pi R gap; its ratio to the upper punch
    pressure at the largest pressure (the radial transmission, Janssen's coefficient);
  - elastic recovery: (gap where the upper punch lets go - gap at the largest pressure) / gap at the largest pressure;
    nan where the run ends before the punch lets go (its pressure above 1e-3 of the largest), and then
    elastic_recovery_min, the same with the gap of the last row: a lower bound (the compact still pushes on the
    punch); where the punch let go, elastic_recovery_min is the recovery itself;
  - quasi-static: the largest kinetic over elastic energy (the series' energies) over the rows where the upper
    punch presses at half its largest pressure or more while loading (the Heckel fit's rows) and at 10 % or more
    after its largest (the dwell and the unloading, over which the recovery is read); above QUASI = 0.1 the report
    warns that the compact moved: the figures read while it moved are not a quasi-static press's (a compact that
    bursts, rings or is pressed faster than it can follow; docs/tableting.md "The tablet report");
  - ejection (the lower punch rising after the upper punch let go): the die-wall friction is the die's axial force
    (the compact drags the die along as it slides out); the lower punch's force is that friction plus the compact's
    inertia and weight, reported apart: a velocity step of the punch accelerates the compact, and its inertia (mass
    scaled in a mass-scaled run) is not the friction a press's ejection force measures. Where the lower punch stays
    and the die is drawn down off the compact instead (withdrawal ejection), the same two forces over the die's
    travel: the die's axial force is the friction (the compact holds the die back), the lower punch's the force the
    compact is held on it with.

Printed keys (`key=value`, SI with pressures in MPa): png, bore_area_m2, solid_m3, max_upper_mpa, density_at_max,
yield_mpa, transmission, radial_mpa, radial_ratio, elastic_recovery, elastic_recovery_min, max_ejection_friction_n,
max_ejection_punch_n, max_kinetic_ratio (the quasi-static check's largest kinetic / elastic energy; nan without
energies);
and where a diametral compression follows (plane walls platen_a and platen_b closing on the ejected tablet; a run
that has the platens but stopped before they touched the tablet is reported without these keys, with a note on
standard error):
tablet_diameter_m, tablet_thickness_m, tablet_density (out of die), max_platen_n (the failure load F: the platen
force before it first falls by 20 %, from at least half its largest), tensile_mpa (2 F / (pi D t)), tablet_failed (1: the force fell so, 0: it never
did and F is the largest force), platen_force_after_peak (the platen force at the end over F), tablet_whole (1: the
tablet held together out of the die, no thicker than 2 times the gap where the upper punch let go and no wider than 2
times the bore; 0: it came apart, and tensile_mpa is nan).
Renamed from the report's earlier keys: max_upper_pa -> max_upper_mpa, yield_pa -> yield_mpa, radial_pa ->
radial_mpa (the values in MPa, no longer Pa); max_ejection_n (the lower punch's largest force, inertia included) ->
max_ejection_punch_n, beside the new max_ejection_friction_n. transmission keeps its name; it is now taken over the
loading rows only (it was a median over every row above 10 % of the largest pressure, dwell and unloading included).
analyse() returns SI values (pressures in Pa).
"""
import math
import sys

import numpy as np

from .output import Run

MPA = 1e-6
QUASI = 0.1  # the largest kinetic / elastic energy of a compact still called quasi-static while pressed


class TabletError(ValueError):
    """A run that is not a press cycle the report can read."""


def _wall(names, want, what):
    if want in names:
        return names.index(want)
    raise TabletError(f"no wall named '{want}' for the {what} (walls: {', '.join(names)}; name it with --{what})")


def analyse(run, die=None, upper="upper", lower="lower"):
    """The press cycle of one run (a libdem.Run, a file, or the files of a run continued by --restart, in order): a
    dict of the series (arrays over the rows) and the report's numbers, in SI units (pressures in Pa)."""
    if not isinstance(run, Run):
        run = Run(run)
    s, names, sh = run.series, run.wall_names, run.wall_shape
    if "wall_force" not in s or "wall_radius" not in sh:
        raise TabletError(f"{' + '.join(run.paths)}: no wall series with the walls' shapes (a run of a scene with "
                          "walls, a libdem that writes the wall shapes)")
    t, pos, force = s["time"], s["wall_position"], s["wall_force"]
    radius, normal = sh["wall_radius"], sh["wall_normal"]
    cup_r = sh.get("wall_cup_radius", np.zeros(len(radius)))
    cup_d = sh.get("wall_cup_depth", np.zeros(len(radius)))
    fnorm, r = s.get("wall_normal_force"), run.radius
    model = run.attrs.get("model", "")
    kinetic = s["kinetic"] if "kinetic" in s else np.full(len(t), np.nan)
    elastic = s["elastic"] if "elastic" in s else np.full(len(t), np.nan)
    if die:
        k_die = _wall(names, die, "die")
    else:
        cyl = [k for k in range(len(names)) if radius[k] > 0]
        if not cyl:
            raise TabletError("no cylinder wall (the die); name it with --die")
        k_die = cyl[0]
    up, lo = _wall(names, upper, "upper"), _wall(names, lower, "lower")
    area = math.pi * radius[k_die] ** 2
    solid = float(np.sum(4.0 / 3.0 * math.pi * r**3))
    n_up, n_lo, axis = normal[up], normal[lo], normal[k_die]
    # the force the powder exerts on a plane along -normal (pushing it back) counts positive, as a servo's
    p_up = -(force[:, up, :] @ n_up) / area
    p_lo = -(force[:, lo, :] @ n_lo) / area
    die_axial = force[:, k_die, :] @ axis
    gap = (pos[:, up, :] - pos[:, lo, :]) @ n_lo  # between the punches' lands
    cups = sum(math.pi * cup_d[k] * (3 * cup_r[k] ** 2 + cup_d[k] ** 2) / 6 for k in (up, lo))
    dens = solid / (area * gap + cups)
    p_rad = fnorm[:, k_die] / (2 * math.pi * radius[k_die] * gap) if fnorm is not None else np.full(len(t), np.nan)
    travel_up = (pos[0, up, :] - pos[:, up, :]) @ n_lo  # downwards travel of the upper punch
    rows = np.arange(len(t))
    k_max = int(np.argmax(p_up))
    p_max = p_up[k_max]
    if not p_max > 0:
        raise TabletError("the upper punch never pressed on the powder")
    after = np.nonzero((rows > k_max) & (p_up <= 1e-3 * p_max))[0]
    k_rel = int(after[0]) if len(after) else None
    # Heckel over the loading: from where the punch starts pressing (2 % of the largest) to the largest pressure
    load = np.nonzero((rows <= k_max) & (p_up > 0.02 * p_max) & (dens < 1))[0]
    heckel = -np.log(1 - dens[load])
    fit = load[p_up[load] >= 0.5 * p_max]
    slope = intercept = yield_p = float("nan")
    if len(fit) >= 2:
        slope, intercept = np.polyfit(p_up[fit], -np.log(1 - dens[fit]), 1)
        yield_p = 1 / slope if slope > 0 else float("nan")
    # transmission over the loading rows: the upper punch moving in, its pressure rising, up to the largest
    rising = np.zeros(len(t), dtype=bool)
    rising[1:] = (travel_up[1:] > travel_up[:-1]) & (p_up[1:] > p_up[:-1])
    loading = np.nonzero(rising & (rows <= k_max) & (p_up > 0.1 * p_max))[0]
    ratio = float(np.median(p_lo[loading] / p_up[loading])) if len(loading) else float("nan")
    recovery = (gap[k_rel] - gap[k_max]) / gap[k_max] if k_rel is not None else float("nan")
    # a run that ends with the compact still pushing on the punch: at least the gap's growth to its last row
    recovery_min = recovery if k_rel is not None else float((gap[-1] - gap[k_max]) / gap[k_max])
    radial_ratio = float(p_rad[k_max] / p_max)
    # ejection: the lower punch rising after the upper one let go, or else the die drawn down off the compact (which
    # then rests on the lower punch); the travel is the moving wall's, counted positive
    ej, by_die = np.array([], dtype=int), False
    if k_rel is not None:
        z_lo = pos[:, lo, :] @ n_lo
        ej = np.nonzero((rows >= k_rel) & (z_lo > z_lo[k_rel] + 1e-12))[0]
        if not len(ej):
            z_die = pos[:, k_die, :] @ n_lo
            ej = np.nonzero((rows >= k_rel) & (z_die < z_die[k_rel] - 1e-12))[0]
            by_die = len(ej) > 0
    mover = k_die if by_die else lo
    eject_travel = abs((pos[ej, mover, :] - pos[k_rel, mover, :]) @ n_lo) if len(ej) else np.array([])
    eject_force = -(force[ej, lo, :] @ n_lo) if len(ej) else np.array([])
    # the die is dragged along the compact's way out (+n_lo) by the friction that holds the compact back
    eject_friction = force[ej, k_die, :] @ n_lo if len(ej) else np.array([])
    nan = float("nan")
    # quasi-static: kinetic over elastic energy where the upper punch presses at half its largest pressure or more
    # while loading, and at 10 % or more after its largest (the early loading, where the elastic energy is small and
    # the fill is swept into place, is left out)
    pressed = np.nonzero(p_up >= np.where(rows <= k_max, 0.5, 0.1) * p_max)[0]
    with np.errstate(divide="ignore", invalid="ignore"):
        ke_ratio = np.where(elastic[pressed] > 0, kinetic[pressed] / elastic[pressed], nan)
    k_ke = int(pressed[np.nanargmax(ke_ratio)]) if np.isfinite(ke_ratio).any() else None
    has_platens = all(w in names for w in PLATENS)
    dia = diametral(run, lo) if has_platens else None
    if dia is not None:
        # a tablet came out of the die only if it holds together: no thicker than WHOLE times the gap where the upper
        # punch let go (or at the largest pressure), no wider than WHOLE times the bore; a compact that came apart
        # (spheres flying off as it springs back) has no tensile strength, whatever force the platens meet
        g_rel = gap[k_rel] if k_rel is not None else gap[k_max]
        dia["whole"] = bool(dia["thickness"] <= WHOLE * g_rel and dia["diameter"] <= WHOLE * 2 * radius[k_die])
        if not dia["whole"]:
            dia["tensile"] = float("nan")
    return dict(dia=dia, platens_untouched=has_platens and dia is None,
                t=t, model=model, area=area, solid=solid, p_up=p_up, p_lo=p_lo, p_rad=p_rad, die_axial=die_axial,
                gap=gap, dens=dens, travel_up=travel_up, k_max=k_max, p_max=p_max, k_rel=k_rel, load=load,
                heckel=heckel, slope=slope, intercept=intercept, yield_p=yield_p, loading=loading, ratio=ratio,
                recovery=recovery, recovery_min=recovery_min, radial_ratio=radial_ratio, ej=ej, eject_by_die=by_die, eject_travel=eject_travel,
                eject_force=eject_force, eject_friction=eject_friction,
                max_ejection_friction=float(np.max(eject_friction)) if len(ej) else nan,
                max_ejection_punch=float(np.max(eject_force)) if len(ej) else nan, kinetic=kinetic, elastic=elastic,
                k_ke=k_ke, max_kinetic_ratio=float(kinetic[k_ke] / elastic[k_ke]) if k_ke is not None else nan)


PLATENS = ("platen_a", "platen_b")
UNTOUCHED = ("{name}: note: the platens (platen_a, platen_b) never touched the tablet in this run (stopped before its "
             "diametral compression?); the press part is reported alone, with no tablet_* or tensile keys")
TRIM = 0.005
DROP = 0.2
WHOLE = 2.0  # a tablet thicker than WHOLE times its gap at release, or wider than WHOLE bores, came apart


def tablet_size(x, r, axis):
    """The diameter and thickness [m] of a tablet of spheres at x [n, 3] with radii r, its axis along the unit vector
    axis: the extreme surfaces across the axis and along it, leaving out the outermost TRIM of the spheres on each
    side (a loose grain at the edge is not the tablet a caliper measures)."""
    h = x @ axis
    thick = float(np.quantile(h + r, 1 - TRIM) - np.quantile(h - r, TRIM))
    centre = np.median(x, axis=0)
    rad = x - centre - np.outer((x - centre) @ axis, axis)
    return float(2 * np.quantile(np.sqrt(np.sum(rad * rad, axis=1)) + r, 1 - TRIM)), thick


def diametral(run, lower):
    """The diametral compression (Brazilian test) of the ejected tablet between two plane walls named platen_a and
    platen_b that close on it across a diameter: the failure load F (the platen force, the mean of the two platens'
    normal forces, which agree in a quasi-static test, at its largest before it first falls by DROP = 20 % from a
    level of at least half the test's largest force: the crack; the largest force of a run in which it never falls
    so), the tablet's diameter D and thickness t, measured on the last frame
    before the platens touch it (the extreme spheres' surfaces across the axis of the lower punch and along it, the
    outermost 0.5 % of the spheres on each side left out), and
    the tensile strength 2 F / (pi D t) (Fell and Newton 1970); the out-of-die relative density is the spheres'
    volume over pi D^2 t / 4."""
    s, names = run.series, run.wall_names
    ka, kb = names.index(PLATENS[0]), names.index(PLATENS[1])
    n_a, n_b, axis = run.wall_shape["wall_normal"][ka], run.wall_shape["wall_normal"][kb], \
        run.wall_shape["wall_normal"][lower]
    force, pos, t = s["wall_force"], s["wall_position"], s["time"]
    f = 0.5 * (-(force[:, ka, :] @ n_a) - (force[:, kb, :] @ n_b))
    travel = ((pos[:, ka, :] - pos[0, ka, :]) @ n_a + (pos[:, kb, :] - pos[0, kb, :]) @ n_b)  # closing: > 0
    touched = np.nonzero(f > 0)[0]
    if not len(touched):
        return None  # a run stopped before the diametral test (SIGTERM, --stop-after): its press part stands alone
    k0 = int(touched[0])
    frames = [k for k in range(len(run.frames)) if run.frames.time[k] <= t[k0]]
    if "position" not in run.frame_fields or not frames:
        raise TabletError("no frame with positions before the platens touch the tablet (output.fields: position)")
    x, r = run.frame(frames[-1])["position"], run.radius
    diam, thick = tablet_size(x, r, axis)
    # the failure load: the largest force before the first drop below (1 - DROP) of the largest so far, once that
    # is at least half the largest force of the test (the crack; the first contacts' flicker is not, and what the
    # platens crush afterwards is not the tablet's strength); without such a drop, the largest force
    runmax = np.maximum.accumulate(np.where(np.arange(len(f)) >= k0, f, 0.0))
    drop = np.nonzero((np.arange(len(f)) > k0) & (f < (1 - DROP) * runmax) & (runmax >= 0.5 * np.max(f)))[0]
    failed = len(drop) > 0
    k_peak = int(np.argmax(f[: drop[0]])) if failed else int(np.argmax(f))
    f_peak = float(f[k_peak])
    solid = float(np.sum(4.0 / 3.0 * math.pi * r**3))
    return dict(force=f, travel=travel - travel[k0], k0=k0, k_peak=k_peak, peak=f_peak, failed=failed,
                largest=float(np.max(f)), diameter=diam, thickness=thick,
                frame_time=float(run.frames.time[frames[-1]]), density=solid / (math.pi * diam * diam / 4 * thick),
                tensile=2 * f_peak / (math.pi * diam * thick), after_peak=float(f[-1] / f_peak))


def numbers(c):
    """The report's numbers as (key, value) pairs, pressures in MPa (the printed line's keys)."""
    k = c["k_max"]
    return [("bore_area_m2", c["area"]), ("solid_m3", c["solid"]), ("max_upper_mpa", MPA * c["p_max"]),
            ("density_at_max", c["dens"][k]), ("yield_mpa", MPA * c["yield_p"]), ("transmission", c["ratio"]),
            ("radial_mpa", MPA * c["p_rad"][k]), ("radial_ratio", c["radial_ratio"]),
            ("elastic_recovery", c["recovery"]), ("elastic_recovery_min", c["recovery_min"]),
            ("max_ejection_friction_n", c["max_ejection_friction"]),
            ("max_ejection_punch_n", c["max_ejection_punch"]),
            ("max_kinetic_ratio", c["max_kinetic_ratio"])] + (
            [("tablet_diameter_m", c["dia"]["diameter"]), ("tablet_thickness_m", c["dia"]["thickness"]),
             ("tablet_density", c["dia"]["density"]), ("max_platen_n", c["dia"]["peak"]),
             ("tensile_mpa", MPA * c["dia"]["tensile"]), ("tablet_failed", float(c["dia"]["failed"])),
             ("tablet_whole", float(c["dia"]["whole"])),
             ("platen_force_after_peak", c["dia"]["after_peak"])]
            if c.get("dia") else [])


def report_line(c, png):
    return f"png={png} " + " ".join(f"{k}={float(v):.6g}" for k, v in numbers(c))


def plot(c, out, title):
    """The report's four panels into the PNG `out`."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t, p_up, p_lo, p_rad, die_axial, area = c["t"], c["p_up"], c["p_lo"], c["p_rad"], c["die_axial"], c["area"]
    dens, travel_up, k_max, p_max, k_rel = c["dens"], c["travel_up"], c["k_max"], c["p_max"], c["k_rel"]
    load, heckel, slope, intercept, yield_p = c["load"], c["heckel"], c["slope"], c["intercept"], c["yield_p"]
    ej, eject_travel, eject_force, eject_friction = c["ej"], c["eject_travel"], c["eject_force"], c["eject_friction"]
    dia = c.get("dia")
    fig, ax = plt.subplots(2, 3 if dia else 2, figsize=(16 if dia else 11, 8.5))
    cyc = slice(0, (k_rel if k_rel is not None else len(t) - 1) + 1)  # loading and unloading, before the punch leaves
    ax[0, 0].plot(1e3 * travel_up[cyc], MPA * p_up[cyc], label="upper punch")
    ax[0, 0].plot(1e3 * travel_up[cyc], MPA * p_lo[cyc], label="lower punch")
    ax[0, 0].plot(1e3 * travel_up[cyc], MPA * p_rad[cyc], label="die wall, radial")
    ax[0, 0].plot(1e3 * travel_up[cyc], MPA * die_axial[cyc] / area, label="die wall, axial (friction) / bore area",
                  lw=0.8)
    ax[0, 0].set(xlabel="upper punch travel [mm]", ylabel="pressure [MPa]", title="pressure against displacement")
    ax[0, 0].legend(fontsize=8)
    ax[0, 1].plot(dens[: k_max + 1], MPA * p_up[: k_max + 1], label="loading")
    if k_rel is not None:
        ax[0, 1].plot(dens[k_max: k_rel + 1], MPA * p_up[k_max: k_rel + 1], label="unloading")
    ax[0, 1].set(xlabel="relative density D", ylabel="upper punch pressure [MPa]", title="compaction curve")
    ax[0, 1].legend(fontsize=8)
    ax[1, 0].plot(MPA * p_up[load], heckel, "o", ms=3, label="ln 1/(1-D)")
    if math.isfinite(slope):
        pp = np.linspace(0, p_max, 50)
        ax[1, 0].plot(MPA * pp, slope * pp + intercept, "--",
                      label=f"fit: yield pressure {MPA * yield_p:.3g} MPa" if math.isfinite(yield_p) else "fit")
    ax[1, 0].set(xlabel="upper punch pressure [MPa]", ylabel="ln 1/(1 - D)", title="Heckel plot")
    ax[1, 0].legend(fontsize=8)
    if len(ej):
        ax[1, 1].plot(1e3 * eject_travel, eject_friction, label="die-wall friction (the die's axial force)")
        ax[1, 1].plot(1e3 * eject_travel, eject_force, lw=0.8, label="lower punch force")
        ax[1, 1].plot(1e3 * eject_travel, eject_force - eject_friction, lw=0.8, ls="--",
                      label="punch - friction: the compact's inertia and weight")
        ax[1, 1].legend(fontsize=8)
    else:
        ax[1, 1].text(0.5, 0.5, "no ejection (lower punch or die) in this run", ha="center", va="center",
                      transform=ax[1, 1].transAxes)
    ax[1, 1].set(xlabel="die travel, drawn down off the compact [mm]" if c["eject_by_die"] else
                 "lower punch travel [mm]", ylabel="force [N]",
                 title="ejection by withdrawing the die" if c["eject_by_die"] else "ejection")
    if dia:
        k0 = dia["k0"]
        ax[0, 2].plot(1e6 * dia["travel"][k0:], dia["force"][k0:])
        ax[0, 2].plot([1e6 * dia["travel"][dia["k_peak"]]], [dia["peak"]], "o",
                      label=(f"{'failure' if dia['failed'] else 'largest (no failure)'} {dia['peak']:.3g} N: tensile "
                             f"strength {MPA * dia['tensile']:.3g} MPa") if dia["whole"] else
                      f"no tablet: the compact came apart out of the die (largest force {dia['peak']:.3g} N)")
        ax[0, 2].set(xlabel="platens' closing [um]", ylabel="platen force [N]",
                     title=f"diametral compression: D {1e3 * dia['diameter']:.3g} mm, t {1e3 * dia['thickness']:.3g} "
                           f"mm, density {dia['density']:.3f}")
        ax[0, 2].legend(fontsize=8)
        ax[1, 2].axis("off")
    rec = (f"{100 * c['recovery']:.2f} %" if c["k_rel"] is not None
           else f">= {100 * c['recovery_min']:.2f} % (the punch had not let go)")
    fig.suptitle(f"{title}: transmission {c['ratio']:.3f} (loading), radial/axial {c['radial_ratio']:.3f}, elastic "
                 f"recovery {rec}", fontsize=10)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def quasi_static_warning(c, name):
    """The report's warning where the compact was not quasi-static while pressed (max_kinetic_ratio above QUASI), else
    None."""
    if not c["max_kinetic_ratio"] > QUASI:
        return None
    k = c["k_ke"]
    return (f"{name}: warning: not quasi-static: the kinetic energy reached {c['max_kinetic_ratio']:.3g} of the "
            f"elastic energy at t = {c['t'][k]:.6g} s, the upper punch at {MPA * c['p_up'][k]:.4g} MPa "
            f"({'loading' if k <= c['k_max'] else 'after the largest pressure'}); above {QUASI:g} the compact moved, "
            f"and {'the density and Heckel fit' if k <= c['k_max'] else 'the elastic recovery'} read while it moved "
            "are not a quasi-static press's "
            "(docs/tableting.md \"The tablet report\")")


def report(paths, out=None, die=None, upper="upper", lower="lower"):
    """analyse() the run, draw its PNG (default: the first file's name with _tablet.png) and return the printed line;
    the quasi-static warning, if any, goes to standard error."""
    paths = [paths] if isinstance(paths, str) else list(paths)
    first = paths[0]
    out = out or (first[:-3] if first.endswith(".h5") else first) + "_tablet.png"
    c = analyse(paths, die, upper, lower)
    plot(c, out, " + ".join(paths))
    warning = quasi_static_warning(c, " + ".join(paths))
    if warning:
        print(warning, file=sys.stderr)
    if c["platens_untouched"]:
        print(UNTOUCHED.format(name=" + ".join(paths)), file=sys.stderr)
    return report_line(c, out)
