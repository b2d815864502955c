"""The analyses users ask of a run: force against displacement from first contact, coordination number, packing
fraction. Each takes a libdem.Run (or, where it says so, the arrays themselves) and returns numbers in SI units."""
import math

import numpy as np

from .output import Run


def _run(run):
    return run if isinstance(run, Run) else Run(run)


def force_displacement(run, wall):
    """A plane wall's force against its displacement counted from its first contact with the spheres.

    Returns (displacement [m], force [N]), arrays over the series' rows. The displacement is the wall's travel along
    its normal (into the particles) from its position in the first row in which it receives a force; rows before
    that have a negative displacement (mask with displacement >= 0). The force is what the particles exert on it
    against its normal, pushing it back (compression positive), as a piston's gauge reads it. The series' rows set
    the resolution: the contact began between the first row with a force and the row before (a finer
    output.series_every resolves it finer). A wall that never receives a force raises ValueError."""
    run = _run(run)
    w = run.wall(wall)
    if w.kind != "plane":
        raise ValueError(f"wall '{w.name}' is a {w.kind}: force against displacement is a plane's (a piston, a punch)")
    n = w.normal
    force = -(w.force @ n) + 0.0  # + 0.0: no -0 where the wall receives nothing
    touched = np.nonzero(np.any(w.force != 0, axis=1))[0]
    if not len(touched):
        raise ValueError(f"wall '{w.name}' never touches the spheres in {' + '.join(run.paths)}")
    k0 = int(touched[0])
    disp = (w.position - w.position[k0]) @ n
    return disp, force


def contact_counts(i, j, n, walls=False, rattlers=True, min_contacts=2):
    """Contacts per sphere of a network given as arrays i, j (j < 0: a contact of sphere i with wall -1 - j), over n
    spheres; returns (counts [n], kept [n] bool). Wall contacts count only with walls=True. With rattlers=False the
    rattlers are taken out, repeatedly: a sphere with fewer than min_contacts contacts is dropped, its contacts with
    it, until every sphere left has at least min_contacts (a sphere held by one contact carries no load, and without
    it its neighbour may carry none either); kept says which spheres are left, and counts are theirs among them."""
    i, j = np.asarray(i, dtype=np.int64), np.asarray(j, dtype=np.int64)
    pair = j >= 0
    pi, pj = i[pair], j[pair]
    wi = i[~pair] if walls else np.zeros(0, dtype=np.int64)
    kept = np.ones(n, dtype=bool)
    while True:
        live = kept[pi] & kept[pj]
        counts = (np.bincount(pi[live], minlength=n) + np.bincount(pj[live], minlength=n)
                  + np.bincount(wi[kept[wi]], minlength=n))
        if rattlers:
            return counts, kept
        drop = kept & (counts < min_contacts)
        if not drop.any():
            return np.where(kept, counts, 0), kept
        kept &= ~drop


def coordination_number(run, frame=-1, rattlers=True, walls=False):
    """The mean number of contacts per sphere in one frame's contact network (a run with the output field
    `contacts`): Z = (2 pairs + wall contacts) / spheres.

    walls=False counts the contacts between spheres only; walls=True adds each sphere's contacts with walls (one
    each). rattlers=False leaves the rattlers out (contact_counts: spheres with fewer than 2 contacts, taken out
    repeatedly, their contacts with them): the mechanical coordination number of the load-bearing network. NaN when
    no sphere is left."""
    run = _run(run)
    c = run.contacts(frame)
    counts, kept = contact_counts(c["i"], c["j"], len(run.radius), walls=walls, rattlers=rattlers)
    return float(counts[kept].sum() / kept.sum()) if kept.any() else math.nan


# The quadrature over the slices of a sphere cut by a box (sphere_box_volume), on each piece [a, b] between kinks:
# z = a + (b - a) (1 - cos u) / 2 with Gauss-Legendre nodes in u over [0, pi]. A slice's area goes as
# (z - z*)^(3/2) where the slice's circle starts to cross a box edge; in u that is sin^3(u / 2), smooth, so the rule
# converges fast (16 nodes: within 1e-9 of the closed forms).
_GL_U, _GL_W = np.polynomial.legendre.leggauss(16)
_GL_U, _GL_W = 0.5 * np.pi * (_GL_U + 1), 0.5 * np.pi * _GL_W
_GL_X, _GL_W = 0.5 * (1 - np.cos(_GL_U)), _GL_W * 0.5 * np.sin(_GL_U)


def _corner(a, b, rho):
    """Area of the part of a disk (radius rho, centre 0) with x < a and y < b (arrays)."""
    # integral over x < min(a, rho) of the chord's length below b: where |x| < c (c the half width at height b)
    # the chord is cut at b, elsewhere it lies wholly below b (b > 0) or wholly above (b < 0)
    a = np.minimum(a, rho)
    b = np.clip(b, -rho, rho)
    c = np.sqrt(np.maximum(rho**2 - b**2, 0))

    def h_int(x):  # integral of sqrt(rho^2 - x^2) from -rho to x
        x = np.clip(x, -rho, rho)
        return 0.5 * (x * np.sqrt(np.maximum(rho**2 - x**2, 0)) + rho**2 * np.arcsin(np.clip(x / np.where(rho > 0, rho, 1), -1, 1))) + 0.25 * np.pi * rho**2

    lo, hi = -c, np.minimum(a, c)
    mid = np.where(hi > lo, b * (hi - lo) + h_int(hi) - h_int(lo), 0.0)  # chord from -h up to b
    # outside |x| < c: full chords (2h) when b > 0
    left = np.where(b > 0, 2 * h_int(np.minimum(a, -c)), 0.0)
    right = np.where((b > 0) & (a > c), 2 * (h_int(a) - h_int(c)), 0.0)
    return np.where(a > -rho, mid + left + right, 0.0)


def sphere_box_volume(x, r, lo, hi):
    """Volume of each sphere (centres x [n, 3], radii r [n]) inside the box [lo, hi]: whole for a sphere inside,
    0 outside, and for one cut by the box the integral over its slices (z) of the disk's area within the box's
    rectangle, exact in x and y and by a Gauss rule in z between the heights where a slice's edge crosses a box
    edge or corner (relative error about 1e-9)."""
    x, r = np.atleast_2d(np.asarray(x, dtype=float)), np.asarray(r, dtype=float).reshape(-1)
    lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
    vol = 4.0 / 3.0 * np.pi * r**3
    inside = np.all((x - r[:, None] >= lo) & (x + r[:, None] <= hi), axis=1)
    outside = np.any((x + r[:, None] <= lo) | (x - r[:, None] >= hi), axis=1)
    out = np.where(inside, vol, 0.0)
    for k in np.nonzero(~inside & ~outside)[0]:
        c, rk = x[k], r[k]
        z0, z1 = max(c[2] - rk, lo[2]), min(c[2] + rk, hi[2])
        # the slice's circle meets a box edge (x or y face) or corner where its radius equals their distance
        d = [abs(lo[0] - c[0]), abs(hi[0] - c[0]), abs(lo[1] - c[1]), abs(hi[1] - c[1])]
        d += [math.hypot(a, b) for a in d[:2] for b in d[2:]]
        cuts = {z0, z1}
        for e in d:
            if e < rk:
                s = math.sqrt(rk * rk - e * e)
                cuts.update(z for z in (c[2] - s, c[2] + s) if z0 < z < z1)
        cuts = sorted(cuts)
        z = np.concatenate([a + (b - a) * _GL_X for a, b in zip(cuts, cuts[1:])])
        w = np.concatenate([(b - a) * _GL_W for a, b in zip(cuts, cuts[1:])])
        rho = np.sqrt(np.maximum(rk * rk - (z - c[2]) ** 2, 0))
        ax, bx, ay, by = lo[0] - c[0], hi[0] - c[0], lo[1] - c[1], hi[1] - c[1]
        area = _corner(bx, by, rho) - _corner(ax, by, rho) - _corner(bx, ay, rho) + _corner(ax, ay, rho)
        out[k] = float(np.sum(w * area))
    return out


def _container(run, row):
    """The volume the walls enclose at series row `row`: a die (cylinder) between two punches facing each other
    along its axis (pi R^2 gap plus their cups), or six planes facing each other in pairs (a box); None otherwise."""
    sh, pos = run.wall_shape, run.series.get("wall_position")
    if pos is None or "wall_normal" not in sh:
        return None
    nrm = np.asarray(sh["wall_normal"], dtype=float)
    rad = np.asarray(sh.get("wall_radius", np.zeros(len(nrm))))
    cup_r = np.asarray(sh.get("wall_cup_radius", np.zeros(len(nrm))))
    cup_d = np.asarray(sh.get("wall_cup_depth", np.zeros(len(nrm))))
    planes = [k for k in range(len(nrm)) if rad[k] == 0]

    def facing(axis):  # the nearest pair of planes facing each other along axis, with the gap between them
        best = None
        for a in planes:
            for b in planes:
                if nrm[a] @ axis > 1 - 1e-9 and nrm[b] @ axis < -1 + 1e-9:
                    gap = (pos[row, b] - pos[row, a]) @ axis
                    if gap > 0 and (best is None or gap < best[2]):
                        best = (a, b, gap)
        return best

    dies = [k for k in range(len(nrm)) if rad[k] > 0]
    if dies:
        die = dies[0]
        f = facing(nrm[die]) or facing(-nrm[die])
        if f is None:
            return None
        cups = sum(math.pi * cup_d[k] * (3 * cup_r[k] ** 2 + cup_d[k] ** 2) / 6 for k in f[:2])
        return math.pi * rad[die] ** 2 * f[2] + cups
    vol = 1.0
    for axis in np.eye(3):
        f = facing(axis)
        if f is None:
            return None
        vol *= f[2]
    return vol


def packing_fraction(run, frame=-1, lo=None, hi=None):
    """The solid fraction of a frame's spheres (a run whose output has positions).

    With a box (lo, hi: its corners [m]): the spheres' volume inside the box (each cut exactly by the box's faces:
    sphere_box_volume) over the box's volume; choose a box away from walls for the bulk's packing fraction. Without
    one: all spheres' volume (4/3 pi r^3 each; overlaps counted twice, as a press reports relative density) over the
    volume the walls enclose at that frame's step: a die between two punches facing each other along its axis
    (pi R^2 gap plus the punches' cups), or six planes facing in pairs (a box); ValueError when the walls enclose
    neither. The walls' positions are those of the series row at the frame's step, or of the last row before it."""
    run = _run(run)
    fr = run.frame(frame)
    r = fr["radius"]
    if lo is not None or hi is not None:
        if lo is None or hi is None:
            raise ValueError("packing_fraction: give both corners of the box, lo and hi")
        if "position" not in fr:
            raise ValueError("packing_fraction: the run's frames have no positions (output.fields: position)")
        lo, hi = np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)
        if np.any(hi <= lo):
            raise ValueError("packing_fraction: the box's hi must exceed lo along every axis")
        return float(sphere_box_volume(fr["position"], r, lo, hi).sum() / np.prod(hi - lo))
    steps = run.series["step"]
    row = int(np.searchsorted(steps, fr["step"], side="right")) - 1
    vol = _container(run, max(row, 0))
    if vol is None:
        raise ValueError("packing_fraction: the walls enclose no die between punches nor a box: give a box (lo, hi)")
    return float(np.sum(4.0 / 3.0 * np.pi * r**3) / vol)
