#!/usr/bin/python3
"""The MDR normal force of a single contact, written from docs/laws/mdr.md (equation numbers (Mn) there), in plain
Python doubles, and its comparison with LAMMPS's single-contact curves (lammps_single.py).

It walks the same prescribed path as the LAMMPS run (cases.py), step by step, with Part II's per-particle step
(M28-M36: volumes, free-surface fraction, radius update, mean surface displacement, bulk force) between and
within steps, and prints the largest difference along each branch (loading, unloading, reloading, final
unloading) relative to the largest force of the case. Pairs of equal spheres, a sphere on a wall and a sphere
between six planes (the bulk response); no penalty (M40: it needs three particles).

usage: mdr_reference.py OUTDIR        (reads OUTDIR/single_<case>.csv, writes OUTDIR/reference_<case>.csv and
                                       OUTDIR/comparison.txt; exit status 1 if a case differs by more than TOL;
                                       compares the C law's core too where OUTDIR/c_<case>.csv exists, which
                                       build/dem-mdr-walk writes)
       mdr_reference.py --selftest    (checks of the closed forms against quadrature and of the fixed-count
                                       replacements for acos, exp and the adhesive Newton solve)
       mdr_reference.py --walk        (every case's walk on stdout, for tests/test_mdr.c: a line "case NAME KIND
                                       NSTEPS R R2 MASS1 MASS2 DT ES G KAPPA NU Y GAMMA PSI_B DAMP", then a line
                                       "APPROACH DELTA RADIUS PSI FORCE" per step, every digit; needs no mpmath)
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cases as C  # noqa: E402
import fixed_count  # noqa: E402

TOL = 1e-3          # largest difference allowed, relative to the case's largest force
A_FAC = 0.99        # (M22) the adhesive contact radius kept after a compressive step, fraction of a_na
OVERLAP_LIMIT = 0.95


class Material:
    def __init__(self, E, nu, Y, gamma, psi_b, damp):
        self.E, self.nu, self.Y, self.gamma, self.psi_b, self.damp = E, nu, Y, gamma, psi_b, damp
        self.Es = E / (1.0 - nu * nu)                    # (M1) plane-strain modulus of one sphere on a rigid flat
        self.G = E / (2.0 * (1.0 + nu))
        self.kappa = E / (3.0 * (1.0 - 2.0 * nu))


# ---- the one-dimensional elliptical indenter (M5-M9) ----

def h_shape(u):
    """h(u) = acos(1-2u) - 2(1-2u) sqrt(u(1-u)) = 8 int_0^u sqrt(v(1-v)) dv, u = d/A in [0, 1/2] (M7), written
    as (F2) so that it keeps its digits at small u (the acos form loses them all by u ~ 1e-12)."""
    return fixed_count.h_fixed(u)


def f_na(d, A, B, Es):
    """(M7) force of the 1D ellipse (height A, width B) pressed to depth d without adhesion."""
    if d <= 0.0:
        return 0.0
    return 0.25 * Es * A * B * h_shape(d / A)


def a_of_depth(d, A, B):
    """(M6) contact half-width of the ellipse at depth d."""
    return B / A * math.sqrt(d * (A - d)) if d > 0.0 else 0.0


def g_of_a(a, A, B):
    """(M5) depth of the ellipse's profile at x = a."""
    g = 0.5 * A - A / B * math.sqrt(max(0.25 * B * B - a * a, 0.0))
    return max(g, 0.0)


def crit_poly(a, A, B, mat):
    """(M26) P(a) = 2 E* A^2 a^3 + pi gamma B^2 a^2 - pi gamma B^4/4: negative below the critical radius."""
    return 2.0 * mat.Es * A * A * a ** 3 + math.pi * mat.gamma * B * B * a * a - 0.25 * math.pi * mat.gamma * B ** 4


def solve_adhesive_radius(d, A, B, mat, a_hi):
    """(M25) the a in (a_crit, a_hi] at which d - g(a) + sqrt(2 pi gamma a / E*) = 0, by bisection to the last
    bit (the reference's own solver: nothing about its count or start carries over to the C law)."""
    def f(a):
        return d - g_of_a(a, A, B) + math.sqrt(2.0 * math.pi * mat.gamma * a / mat.Es)
    # f decreases from a_crit upwards (g' > l' there); f(a_hi) < 0 is the case's condition.
    # Lower end: the critical radius, where f is largest (the sign change of P, by bisection)
    clo, chi = 0.0, a_hi
    for _ in range(200):
        m = 0.5 * (clo + chi)
        if crit_poly(m, A, B, mat) < 0.0:
            clo = m
        else:
            chi = m
    a_crit = chi
    if f(a_crit) < 0.0:
        return 0.0, a_crit            # no root above a_crit: the contact lets go
    lo, hi = a_crit, a_hi
    for _ in range(200):
        m = 0.5 * (lo + hi)
        if f(m) >= 0.0:
            lo = m
        else:
            hi = m
        if hi - lo <= 1e-17 * hi:
            break
    return 0.5 * (lo + hi), a_crit


# ---- per-particle and per-contact state ----

class Particle:
    def __init__(self, R, mass):
        self.Ro = R            # (M30) radius at creation
        self.R = R             # apparent radius, grows by (M34)
        self.mass = mass
        self.dRavg = 0.0
        self.Acon0 = 0.0
        self.clear_sums()
        self.psi = 1.0
        self.Velas = 4.0 / 3.0 * math.pi * R ** 3
        self.Vgeo = self.Velas
        self.ddelta_bar = 0.0

    def clear_sums(self):
        self.Vcaps = 0.0
        self.eps_sum = 0.0
        self.dRnum = 0.0
        self.dRden = 0.0
        self.Acon1 = 0.0
        self.Atot_sum = 0.0

    def begin_step(self, mat):
        """(M31, M34, M36) between steps: the particle's volumes, free-surface fraction and radius from the sums
        its contacts left in the previous step; then the sums restart."""
        R = self.R
        Vo = 4.0 / 3.0 * math.pi * self.Ro ** 3
        self.Vgeo = min(4.0 / 3.0 * math.pi * R ** 3 - self.Vcaps, Vo)
        self.Velas = Vo * (1.0 + self.eps_sum)
        Atot = 4.0 * math.pi * R * R + self.Atot_sum
        self.psi = (Atot - self.Acon1) / Atot
        if mat.psi_b < self.psi:
            w = 1.0 / (1.0 + math.exp(-75.0 * (self.psi - 0.2))) if self.psi > 0.1 else 0.0
            dR = max(self.dRnum / (self.dRden - 4.0 * math.pi * R * R) * w, 0.0)
            if dR > 0.0:
                self.dRavg += (dR - self.dRavg) / 10.0
                if R + dR < 1.5 * self.Ro:
                    self.R = R + self.dRavg
        self.Acon0 = self.Acon1
        self.clear_sums()
        self.ddelta_bar = 0.0

    def add_surface_motion(self, side, delta_now):
        """(M33) one contact's share of the mean surface displacement increment, at the step's start."""
        if self.Acon0 != 0.0:
            self.ddelta_bar += side.Ac / self.Acon0 * (delta_now - side.delta)


class Side:
    """What one side of a contact remembers (M37)."""
    def __init__(self):
        self.delta = 0.0        # side's apparent overlap at the last step
        self.deltao = 0.0       # the same against the initial radius
        self.delta_mdr = 0.0
        self.delta_bulk = 0.0
        self.Ac = 0.0           # last step's contact area (M33)
        self.deltamax = 0.0     # largest delta_mdr
        self.yielded = False
        self.cA = 0.0           # area intercept fixed at yield (M12)
        self.aAdh = 0.0         # adhesive contact radius
        self.eps_c = 0.0        # this contact's last strain contribution
        self.deltap = 0.0       # plastic overlap at which this side's force vanishes (M18)


def side_force(mat, s, p, delta):
    """One side: a sphere of apparent radius p.R pressed on a rigid flat by `delta`. Returns
    (F_MDR + F_BULK, a_damp) and leaves the side's and the particle's updates (M10-M35)."""
    R, Ro = p.R, p.Ro
    ddelta = delta - s.delta
    s.delta = delta
    deltao = delta - (R - Ro)
    ddeltao = deltao - s.deltao
    s.deltao = deltao
    if p.psi < mat.psi_b:                                       # (M10) the bulk response takes its share
        dd_mdr = min(ddelta - p.ddelta_bar, delta - s.delta_mdr)
        dd_bulk = p.ddelta_bar
    else:
        dd_mdr = ddelta
        dd_bulk = 0.0
    s.delta_mdr += dd_mdr
    s.delta_bulk = max(0.0, s.delta_bulk + dd_bulk)
    if s.delta_mdr > s.deltamax:
        s.deltamax = s.delta_mdr
    dm = s.deltamax
    pY = mat.Y * (1.75 * math.exp(-4.4 * dm / R) + 1.0)         # (M11)
    if not s.yielded and s.delta_mdr >= dm:
        p_hertz = 4.0 * mat.Es * math.sqrt(s.delta_mdr) / (3.0 * math.pi * math.sqrt(R))   # (M12)
        if p_hertz > pY:
            s.yielded = True
            dY = s.delta_mdr
            s.cA = math.pi * (dY * dY - dY * R)
    if not s.yielded:                                           # (M13)
        A, B = 4.0 * R, 2.0 * R
        de = s.delta_mdr
        amax = math.sqrt(dm * R)
    else:                                                       # (M14-M18)
        amax = math.sqrt(2.0 * dm * R - dm * dm + s.cA / math.pi)
        A = 4.0 * pY * amax / mat.Es
        B = 2.0 * amax
        Fmax = math.pi * pY * amax * amax                       # = f_na(A/2, A, B)
        zR = R - (dm - 0.5 * A)
        q = math.sqrt(amax * amax + zR * zR)
        dR = Fmax / (2.0 * math.pi * amax * amax * mat.G * q) * (
            2.0 * amax * amax * (mat.nu - 1.0) + (1.0 - 2.0 * mat.nu) * zR * (q - zR))   # (M16)
        de = (s.delta_mdr - dm + 0.5 * A + dR) / (1.0 + 2.0 * dR / A)                    # (M17)
        s.deltap = dm - (0.5 * A + dR)                                                    # (M18)
    a_na = a_of_depth(de, A, B)
    a_prev = min(s.aAdh, A_FAC * amax)
    if mat.gamma <= 0.0:
        F = f_na(de, A, B, mat.Es)
        s.aAdh = a_na
        a_damp = a_na
    elif s.delta_mdr >= dm or a_na >= a_prev:                   # (M22) compressive: springs all in contact
        F = f_na(de, A, B, mat.Es)
        s.aAdh = A_FAC * a_na
        a_damp = a_na
    else:
        g = g_of_a(a_prev, A, B)
        lmax = math.sqrt(2.0 * math.pi * a_prev * mat.gamma / mat.Es)   # (M23)
        if de + lmax - g >= 0.0:                                # (M24) edge springs within their reach
            a = a_prev
        else:                                                   # (M25, M26) the contact radius recedes
            if crit_poly(a_prev, A, B, mat) < 0.0:
                a = 0.0
            else:
                a, _ = solve_adhesive_radius(de, A, B, mat, a_prev)
            s.aAdh = a
        if a > 0.0:
            g = g_of_a(a, A, B)
            F = f_na(g, A, B, mat.Es) + 2.0 * mat.Es * (de - g) * a      # (M21)
        else:
            F = 0.0
        a_damp = a
    # (M28, M29, M32) areas, cap volume, strain and radius-update sums of the particle
    Ac = math.pi * (2.0 * delta * R - delta * delta) + s.cA if s.yielded else math.pi * delta * R
    Ac = max(Ac, 0.0)
    p.Atot_sum += Ac - 2.0 * math.pi * R * (dm + s.delta_bulk)
    p.Acon1 += Ac
    s.Ac = Ac
    F_bulk = p.Acon0 * s.delta_bulk * mat.kappa * Ac / p.Vgeo if s.delta_bulk > 0.0 else 0.0   # (M35)
    p.Vcaps += math.pi / 3.0 * delta * delta * (3.0 * R - delta)
    eps_c = -(F + F_bulk) * (Ro - deltao) / (3.0 * mat.kappa * p.Velas)
    p.eps_sum += eps_c
    if s.delta_mdr >= dm and s.yielded and F > 0.0:
        Vo = 4.0 / 3.0 * math.pi * Ro ** 3
        p.dRnum -= Vo * (eps_c - s.eps_c)
        p.dRnum -= math.pi * ddeltao * (2.0 * deltao * Ro - deltao * deltao + R * R - Ro * Ro)
        p.dRden += 2.0 * math.pi * R * (deltao + R - Ro)
    s.eps_c = eps_c
    return F + F_bulk, a_damp


class Contact:
    def __init__(self):
        self.reset()

    def reset(self):
        self.deltamax = 0.0
        self.sides = [Side(), Side()]


def pair_split(c, p_hi, p_lo, delta):
    """(M3) the two spheres' shares of the apparent overlap: side 0 is the higher-id sphere."""
    dmax = c.deltamax
    out = []
    for k, (pi, pj) in enumerate(((p_hi, p_lo), (p_lo, p_hi))):
        Ri, Rj = pi.R, pj.R
        denom = 2.0 * (dmax - Ri - Rj)
        o1 = dmax * (dmax - 2.0 * Rj) / denom
        o2 = dmax * (dmax - 2.0 * Ri) / denom
        geo, alt = (max(o1, o2), min(o1, o2)) if Ri < Rj else (min(o1, o2), max(o1, o2))
        if geo / Ri > OVERLAP_LIMIT:
            geo = Ri * OVERLAP_LIMIT
        elif alt / Rj > OVERLAP_LIMIT:
            geo = dmax - Rj * OVERLAP_LIMIT
        dp = c.sides[0].deltap + c.sides[1].deltap
        out.append(geo + (c.sides[k].deltap - geo) * (delta - dmax) / (dp - dmax))
    return out


def run_box(spec, mat, mass):
    """One sphere between six planes closing in by the path's approach u (no damping: spec's damp is 0)."""
    path = spec["path"]
    nsteps = sum(C.phase_steps(path))
    p = Particle(C.R, mass)
    walls = [Contact() for _ in range(6)]
    rows = []
    for step in range(nsteps + 1):
        u = C.approach_at(path, step)
        F = 0.0
        if step > 0:
            p.begin_step(mat)
            # each plane at distance R - u from the centre: its overlap with the (grown) sphere
            delta = p.R - (C.R - u)
            for c in walls:
                if delta > 0.0:
                    p.add_surface_motion(c.sides[0], delta)
            for k, c in enumerate(walls):
                if delta > 0.0:
                    if delta >= c.deltamax:
                        c.deltamax = delta
                    F0, _ = side_force(mat, c.sides[0], p, delta)
                    wfm = math.exp(10.7 * c.sides[0].deltao / p.Ro - 10.0) + 1.0
                    if k == 0:
                        F = F0 * wfm
                else:
                    c.reset()
        rows.append((step, u, p.R - (C.R - u), p.R, F, p.psi))
    return rows


def run_case(case, spec):
    mat = Material(*C.material_of(spec))
    if spec["kind"] == "box":
        return run_box(spec, mat, C.RHO * 4.0 / 3.0 * math.pi * C.R ** 3)
    mass = C.RHO * 4.0 / 3.0 * math.pi * C.R ** 3
    path = spec["path"]
    nsteps = sum(C.phase_steps(path))
    rows = []
    if spec["kind"] == "pair":
        R2 = spec.get("R2", C.R)
        m2 = C.RHO * 4.0 / 3.0 * math.pi * R2 ** 3
        p1, p2 = Particle(C.R, mass), Particle(R2, m2)       # p2 has the higher id: side 0
        parts = (p1, p2)
    else:
        p1 = Particle(C.R, mass)
        parts = (p1,)
    c = Contact()
    for step in range(nsteps + 1):
        u = C.approach_at(path, step)
        # the rate of approach of the phase this step belongs to (the velocity the damping sees)
        v_app = (u - C.approach_at(path, step - 1)) / C.DT if step > 0 else 0.0
        if step > 0:
            for p in parts:
                p.begin_step(mat)
        if spec["kind"] == "pair":
            dist = C.R + p2.Ro - u
            delta = p1.R + p2.R - dist
            meff = mass * p2.mass / (mass + p2.mass)
        else:
            dist = C.R - u
            delta = p1.R - dist
            meff = mass
        F = 0.0
        if delta > 0.0 and step > 0:
            if delta >= c.deltamax:
                c.deltamax = delta
            if spec["kind"] == "pair":
                d0, d1 = pair_split(c, p2, p1, delta)
                p2.add_surface_motion(c.sides[0], d0)
                p1.add_surface_motion(c.sides[1], d1)
                F0, a0 = side_force(mat, c.sides[0], p2, d0)
                F1, a1 = side_force(mat, c.sides[1], p1, d1)
                Fel = 0.5 * (F0 + F1)                                        # (M4)
                eta = mat.damp * math.sqrt(meff * 2.0 * mat.Es * (a0 + a1))  # (M38)
            else:
                p1.add_surface_motion(c.sides[0], delta)
                F0, a0 = side_force(mat, c.sides[0], p1, delta)
                wfm = math.exp(10.7 * c.sides[0].deltao / p1.Ro - 10.0) + 1.0  # (M39)
                Fel = F0 * wfm
                eta = mat.damp * math.sqrt(meff * mat.Es * 0.5 * a0)
            F = Fel + eta * v_app
        elif delta <= 0.0:
            c.reset()
        rows.append((step, u, delta, p1.R, F, p1.psi))
    return rows


def load_csv(path):
    rows = []
    with open(path) as f:
        for line in f:
            if line.startswith("#") or line.startswith("step"):
                continue
            rows.append([float(x) for x in line.split(",")])
    return rows


def compare(outdir):
    lines = []
    worst = 0.0
    worst_c = 0.0
    for case, spec in C.SINGLE.items():
        ref = run_case(case, spec)
        with open(os.path.join(outdir, f"reference_{case}.csv"), "w") as f:
            f.write(f"# MDR single contact, tools/peer_mdr/mdr_reference.py (docs/laws/mdr.md); case {case}\n"
                    "step,approach_m,overlap_m,radius_m,force_N,psi\n")
            for r in ref:
                f.write(",".join(repr(x) for x in r) + "\n")
        lam = load_csv(os.path.join(outdir, f"single_{case}.csv"))
        n = C.phase_steps(spec["path"])
        bounds = [0]
        for k in n:
            bounds.append(bounds[-1] + k)
        names = ["loading", "unloading", "reloading", "unloading out"]
        fmax = max(abs(r[5]) for r in lam)
        parts = []
        for k in range(4):
            d_f = 0.0
            d_r = 0.0
            for r in lam:
                step = int(r[0])
                if bounds[k] < step <= bounds[k + 1]:
                    q = ref[step]
                    d_f = max(d_f, abs(q[4] - r[5]) / fmax)
                    d_r = max(d_r, abs(q[3] - r[4]) / C.R)
            worst = max(worst, d_f)
            parts.append(f"{names[k]} {d_f:.2e}")
        fmin_l = min(r[5] for r in lam)
        fmin_r = min(q[4] for q in ref)
        rad = max(abs(ref[int(r[0])][3] - r[4]) for r in lam) / C.R
        dpsi = max(abs(ref[int(r[0])][5] - r[6]) for r in lam)
        psimin = min(r[6] for r in lam)
        tens = ""
        if spec["gamma"] > 0.0:
            # the tensile branch against its own scale: rows where either force is below 1 % of the peak
            d_t = max((abs(ref[int(r[0])][4] - r[5]) for r in lam
                       if min(r[5], ref[int(r[0])][4]) < -0.0 and abs(r[5]) < 0.01 * fmax), default=0.0)
            ntens = sum(1 for r in lam if r[5] < 0.0)
            tens = f"; tensile rows {ntens}, largest difference there {d_t / abs(fmin_l):.2e} of the pull-off"
        lines.append(f"{case:10s} peak {fmax:8.4f} N; largest |F_ref - F_lammps| / peak: " + ", ".join(parts)
                     + f"; radius {rad:.1e} R; psi down to {psimin:.3f}, {dpsi:.1e} apart"
                     + f"; least force LAMMPS {fmin_l:.6g} N, reference {fmin_r:.6g} N"
                     + tens)
        # the C law's core on the same path (dem-mdr-walk's c_<case>.csv, when run.sh made it)
        cpath = os.path.join(outdir, f"c_{case}.csv")
        if os.path.exists(cpath):
            cf = {int(r[0]): r[1] for r in load_csv(cpath)}
            cparts = []
            for k in range(4):
                d_c = max((abs(cf[int(r[0])] - r[5]) / fmax for r in lam if bounds[k] < int(r[0]) <= bounds[k + 1]),
                          default=0.0)
                worst_c = max(worst_c, d_c)
                cparts.append(f"{names[k]} {d_c:.2e}")
            d_cr = max(abs(cf[int(r[0])] - ref[int(r[0])][4]) for r in lam) / fmax
            lines.append(f"{'  C law':10s} largest |F_C - F_lammps| / peak: " + ", ".join(cparts)
                         + f"; |F_C - F_ref| / peak {d_cr:.1e}")
    text = "\n".join(lines)
    print(text)
    with open(os.path.join(outdir, "comparison.txt"), "w") as f:
        f.write(text + "\n")
    ok = worst <= TOL
    print(f"mdr_reference: largest difference {worst:.2e} of the peak force (tolerance {TOL:g}): "
          + ("agree" if ok else "DISAGREE"))
    if worst_c > 0.0:
        ok_c = worst_c <= TOL
        print(f"mdr_reference: the C law's core, largest difference {worst_c:.2e} of the peak force: "
              + ("agree" if ok_c else "DISAGREE"))
        ok = ok and ok_c
    return 0 if ok else 1


def walk_all():
    """--walk: each case's inputs and the reference's walk, for the C law's test (tests/test_mdr.c)"""
    for case, spec in C.SINGLE.items():
        mat = Material(*C.material_of(spec))
        rows = run_case(case, spec)
        R2 = spec.get("R2", C.R)
        m1 = C.RHO * 4.0 / 3.0 * math.pi * C.R ** 3
        m2 = C.RHO * 4.0 / 3.0 * math.pi * R2 ** 3
        head = [C.R, R2, m1, m2, C.DT, mat.Es, mat.G, mat.kappa, mat.nu, mat.Y, mat.gamma, mat.psi_b, mat.damp]
        print("case", case, spec["kind"], len(rows) - 1, " ".join(repr(x) for x in head))
        for r in rows:  # (step, u, delta, R, F, psi)
            print(repr(r[1]), repr(r[2]), repr(r[3]), repr(r[5]), repr(r[4]))
    return 0


if __name__ == "__main__":
    if len(sys.argv) == 2 and sys.argv[1] == "--walk":
        sys.exit(walk_all())
    if len(sys.argv) == 2 and sys.argv[1] == "--selftest":
        sys.exit(fixed_count.main())
    sys.exit(compare(sys.argv[1]))
