#!/usr/bin/python3
"""Checks of docs/laws/mdr.md's section "Only + - * / sqrt, fixed counts": each transcendental or iterative
step of the MDR law written with + - * / sqrt (and the exact floor and power-of-two scaling), a fixed number of
terms or Newton steps from a fixed start, measured against 50-digit mpmath over the range a press visits.

Run by `mdr_reference.py --selftest` (and `make peer-mdr`); prints the worst errors in units of the last place
(ulp) or relative, and exits 1 if one of them is above its bound.
"""
import math
import os
import sys

try:  # the checks against 50 digits need it; the fixed-count forms themselves (mdr_reference.py's walk) do not
    import mpmath
except ImportError:
    mpmath = None

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cases as C  # noqa: E402

if mpmath:
    mpmath.mp.dps = 50
LN2_HI = 0.693145751953125            # ln 2 split so that n*LN2_HI is exact for |n| < 2^11
LN2_LO = 1.4286068203094172321e-06
INV_LN2 = 1.4426950408889634074


def exp_fixed(x):
    """(F1) exp(x): n = floor(x/ln2 + 1/2), r = x - n ln2 (two products, Cody-Waite), |r| <= 0.347;
    exp(r) by its Taylor series to r^13 (Horner, 13 multiply-adds); times 2^n (exact). No loop with a
    data-dependent count."""
    n = math.floor(x * INV_LN2 + 0.5)
    r = (x - n * LN2_HI) - n * LN2_LO
    p = 1.0 / 6227020800.0                 # 1/13!
    for k in range(12, 0, -1):
        p = p * r + 1.0 / math.factorial(k)
    p = p * r + 1.0
    return math.ldexp(p, int(n))


ATAN_TERMS = 13
# (phi - sin phi)/phi^3 = sum_k c_k phi^(2k), c_k = (-1)^k/(2k+3)!, k = 0..13
_HC = [(-1) ** k / math.factorial(2 * k + 3) for k in range(14)]


def h_fixed(u):
    """(F2) h(u) = acos(1-2u) - 2(1-2u) sqrt(u(1-u)) for u in [0, 1/2], without acos and without the cancellation
    of that form at small u: t = tan(theta/2) = sqrt(u/(1-u)); two halvings t <- t/(1 + sqrt(1 + t^2)) bring
    t below tan(pi/16); theta = 8 atan(t) by the odd series to t^25 (13 terms); phi = 2 theta;
    h = (phi - sin phi)/2 = phi^3/2 * sum_k c_k phi^(2k) to phi^29 (14 terms)."""
    if u <= 0.0:
        return 0.0
    t = math.sqrt(u / (1.0 - u))
    t = t / (1.0 + math.sqrt(1.0 + t * t))
    t = t / (1.0 + math.sqrt(1.0 + t * t))
    t2 = t * t
    s = 1.0 / (2 * ATAN_TERMS - 1)
    for k in range(ATAN_TERMS - 2, -1, -1):
        s = s * (-t2) + 1.0 / (2 * k + 1)
    phi = 16.0 * t * s
    p2 = phi * phi
    q = _HC[-1]
    for c in reversed(_HC[:-1]):
        q = q * p2 + c
    return 0.5 * phi * p2 * q


def h_exact(u):
    u = mpmath.mpf(u)
    return mpmath.acos(1 - 2 * u) - 2 * (1 - 2 * u) * mpmath.sqrt(u * (1 - u))


def ulp_err(a, b):
    b = float(b) if not isinstance(b, float) else b
    if b == 0.0:
        return 0.0 if a == 0.0 else float("inf")
    return abs(a - b) / math.ulp(abs(b))


def rel_err(a, b):
    return float(abs(mpmath.mpf(a) - b) / abs(b)) if b != 0 else abs(a)


# ---- the adhesive contact radius (M25) and the critical radius (M26) ----

def cbrt_fixed(y):
    """(F5) y^(1/3) for y > 0: y = m 2^e (frexp, exact), e = 3q + r with r in {0, 1, 2}, m' = m 2^r in [1/2, 4);
    start x0 = 0.6362 + 0.3934 m' - 0.04042 m'^2 (within 3.7 % of m'^(1/3) there); 5 Newton steps
    x <- x - (x^3 - m')/(3 x^2); times 2^q (exact)."""
    m, e = math.frexp(y)
    q = e // 3
    r = e - 3 * q
    m = math.ldexp(m, r)
    x = 0.6362 + m * (0.3934 - 0.04042 * m)
    for _ in range(5):
        x = x - (x * x * x - m) / (3.0 * x * x)
    return math.ldexp(x, q)


def crit_newton(A, B, Es, gamma, steps):
    """(F3) the critical radius a_c, root of P(a) = 2E*A^2 a^3 + pi gamma B^2 a^2 - pi gamma B^4/4, as
    a_c = (B/2) z with kappa z^3 + z^2 - 1 = 0, kappa = E* A^2/(pi gamma B): Newton from
    z0 = min(1, cbrt(1/kappa)), an upper bound of z (kappa z^3 <= 1 and z^2 <= 1); the cubic is convex and
    increasing for z > 0, so the iterates fall monotonically onto z from above."""
    kappa = Es * A * A / (math.pi * gamma * B)
    z = min(1.0, cbrt_fixed(1.0 / kappa))
    for _ in range(steps):
        z = z - ((kappa * z + 1.0) * z * z - 1.0) / ((3.0 * kappa * z + 2.0) * z)
    return 0.5 * B * z


def crit_exact(A, B, Es, gamma):
    A, B, Es, gamma = (mpmath.mpf(x) for x in (A, B, Es, gamma))
    k3 = 2 * Es * A * A
    k2 = mpmath.pi * gamma * B * B
    k0 = mpmath.pi * gamma * B ** 4 / 4
    return _bisect(lambda a: (k3 * a + k2) * a * a - k0, mpmath.mpf(0), B / 2)


def _bisect(f, lo, hi):
    for _ in range(180):
        m = (lo + hi) / 2
        if f(m) < 0:
            lo = m
        else:
            hi = m
    return (lo + hi) / 2


def adh_newton(d, A, B, Es, gamma, a0, steps, a_c):
    """(F4) the root of f(a) = d - g(a) + sqrt(c a), c = 2 pi gamma / E*, between a_c and a0 (f(a0) < 0 is the
    tensile case's condition, f(a_c) > 0 that a root exists; otherwise the contact lets go and this is not
    called). f is concave, so one Newton step from any point of its decreasing branch (a > a_c) lands at or
    above the root and the steps after it fall monotonically onto the root. Start: the root of f's quadratic
    model at the fold, a_c + sqrt(2 f(a_c) / -f''(a_c)), but not above a0. Near the fold (the pull-off) a start
    from a0 would converge only linearly (the root is nearly double there); from the model's root it converges
    quadratically."""
    c = 2.0 * math.pi * gamma / Es

    def parts(a):
        w = math.sqrt(0.25 * B * B - a * a)
        sq = math.sqrt(c * a)
        return w, sq, d - 0.5 * A + A / B * w + sq

    w, sq, fc = parts(a_c)
    f2 = -(A / B) * 0.25 * B * B / (w * w * w) - 0.25 * sq / (a_c * a_c)
    a = min(a_c + math.sqrt(2.0 * fc / -f2), a0)
    for _ in range(steps):
        w, sq, f = parts(a)
        df = -A * a / (B * w) + 0.5 * c / sq
        a = a - f / df
    return a


def adh_newton_prev(d, A, B, Es, gamma, a0, steps):
    """For comparison: Newton from the previous radius a0 (LAMMPS's start), without the fold's model."""
    c = 2.0 * math.pi * gamma / Es
    a = a0
    for _ in range(steps):
        w = math.sqrt(0.25 * B * B - a * a)
        sq = math.sqrt(c * a)
        f = d - 0.5 * A + A / B * w + sq
        df = -A * a / (B * w) + 0.5 * c / sq
        if df >= 0.0:
            break
        a = a - f / df
    return a


def adh_exact(d, A, B, Es, gamma, a_c, a0):
    d, A, B, Es, gamma = (mpmath.mpf(x) for x in (d, A, B, Es, gamma))

    def f(a):
        return d - A / 2 + A / B * mpmath.sqrt(B * B / 4 - a * a) + mpmath.sqrt(2 * mpmath.pi * gamma * a / Es)
    lo, hi = mpmath.mpf(a_c), mpmath.mpf(a0)
    if f(lo) < 0:
        return None
    for _ in range(180):
        m = (lo + hi) / 2
        if f(m) >= 0:
            lo = m
        else:
            hi = m
    return (lo + hi) / 2


def collect_case3_states():
    """Every tensile-branch solve (M25) met along cases.py's single-contact paths, from the reference."""
    import mdr_reference as M
    states = []
    orig = M.solve_adhesive_radius

    def spy(d, A, B, mat, a_hi):
        states.append((d, A, B, mat.Es, mat.gamma, a_hi))
        return orig(d, A, B, mat, a_hi)
    M.solve_adhesive_radius = spy
    try:
        for case, spec in C.SINGLE.items():
            if spec["gamma"] > 0.0:
                M.run_case(case, spec)
    finally:
        M.solve_adhesive_radius = orig
    return states


def closed_forms():
    """(M6, M7) against their definitions: the force of the 1D ellipse F = 2 E* int_0^a (d - g(x)) dx by
    quadrature, and its Hertz limit 4/3 E* R^(1/2) d^(3/2) for A = 4R, B = 2R, small d. Returns the worst
    relative errors."""
    import mdr_reference as M
    w_q = 0.0
    for (A, B) in ((4.0, 2.0), (0.13, 1.0), (1.0, 0.05)):
        for u in (1e-6, 1e-3, 0.05, 0.2, 0.37, 0.5):
            d = u * A
            a = M.a_of_depth(d, A, B)
            q = 2 * mpmath.quad(lambda x: d - (A / 2 - A / B * mpmath.sqrt(B * B / 4 - x * x)), [0, a])
            w_q = max(w_q, rel_err(M.f_na(d, A, B, 1.0), q))
    w_h = 0.0
    R = 1.0
    for d in (1e-8, 1e-6, 1e-4):
        hertz = 4.0 / 3.0 * R ** 0.5 * d ** 1.5
        w_h = max(w_h, abs(M.f_na(d, 4 * R, 2 * R, 1.0) / hertz - 1) / (d / R))
    return w_q, w_h


def main():
    bad = 0
    w_q, w_h = closed_forms()
    print(f"M7 closed form of the ellipse's force against quadrature: worst relative error {w_q:.1e}; "
          f"elastic ellipse against Hertz: |F/F_Hertz - 1| <= {w_h:.2f} delta/R")
    bad += w_q > 1e-9 or w_h > 1.0
    # F1: exp over the ranges the law visits: pY (-4.4..0), wall magnifier (-10..1), confinement weight
    # (-60..8), penalty (-25..25)
    worst = 0.0
    n = 0
    for i in range(20001):
        x = -80.0 + 100.0 * i / 20000
        for xx in (x, x + 1e-3 * math.sin(i)):
            e = ulp_err(exp_fixed(xx), mpmath.exp(mpmath.mpf(xx)))
            worst = max(worst, e)
            n += 1
    print(f"F1 exp_fixed on [-80, 20], {n} points: worst {worst:.2f} ulp")
    bad += worst > 2.0
    # F2: h(u) on [0, 1/2], log-spaced near 0 (first touch) and uniform above
    worst_rel = 0.0
    worst_naive = 0.0
    pts = [10.0 ** (-12 + 11.0 * i / 3000) for i in range(3001)] + [0.5 * i / 5000 for i in range(1, 5001)]
    for u in pts:
        ex = h_exact(u)
        worst_rel = max(worst_rel, rel_err(h_fixed(u), ex))
        naive = math.acos(1.0 - 2.0 * u) - 2.0 * (1.0 - 2.0 * u) * math.sqrt(u * (1.0 - u))
        worst_naive = max(worst_naive, rel_err(naive, ex))
    print(f"F2 h_fixed on u in [1e-12, 1/2], {len(pts)} points: worst relative error {worst_rel:.2e} "
          f"(the acos form in doubles: {worst_naive:.2e}, its cancellation at small u)")
    bad += worst_rel > 1e-14
    # F3, F4 over the tensile-branch states the single-contact cases visit
    states = collect_case3_states()
    print(f"F3/F4: {len(states)} tensile-branch solves met along the single-contact paths")
    w = 0.0
    for i in range(20001):
        y = 10.0 ** (-30 + 60.0 * i / 20000)
        w = max(w, ulp_err(cbrt_fixed(y), mpmath.cbrt(mpmath.mpf(y))))
    print(f"F5 cbrt_fixed on [1e-30, 1e30]: worst {w:.2f} ulp")
    bad += w > 2.0
    for steps in (3, 4, 5, 6):
        w = 0.0
        for (d, A, B, Es, g, a0) in states:
            ac = crit_newton(A, B, Es, g, steps)
            w = max(w, rel_err(ac, crit_exact(A, B, Es, g)))
        # and over kappa in [1e-6, 1e12] (weak to strong adhesion against the ellipse's stiffness)
        for i in range(601):
            kap = 10.0 ** (-6 + 18.0 * i / 600)
            A_, B_, Es_ = 1.0, 1.0, kap * math.pi
            w = max(w, rel_err(crit_newton(A_, B_, Es_, 1.0, steps), crit_exact(A_, B_, Es_, 1.0)))
        print(f"F3 critical radius, {steps:2d} Newton steps from min(1, cbrt(1/kappa)): worst relative error "
              f"{w:.2e}")
        if steps == 5:
            bad += w > 4e-16
    ac_steps = 5
    # F4 over the states met, and over synthetic ones: each state's ellipse and previous radius a0 with the
    # depth d swept from where the root is a0 down to 1e-12 of that range above the fold (where the root meets
    # a_c and the contact lets go): one step from a0 to near the fold is the hardest start
    synth = []
    for (d, A, B, Es, g, a0) in states[::4]:
        ac = float(crit_exact(A, B, Es, g))
        c = 2.0 * math.pi * g / Es

        def gfun(a):
            return 0.5 * A - A / B * math.sqrt(0.25 * B * B - a * a)
        d_top = gfun(a0) - math.sqrt(c * a0)       # root at a0
        d_fold = gfun(ac) - math.sqrt(c * ac)      # root at a_c
        for k in range(13):
            frac = 10.0 ** (-k)
            synth.append((d_fold + frac * (d_top - d_fold), A, B, Es, g, a0))
    for label, group in (("met", states), ("swept", synth)):
        for steps in (2, 3, 4, 5, 8):
            w_a = 0.0
            w_p = 0.0
            for (d, A, B, Es, g, a0) in group:
                ac = crit_newton(A, B, Es, g, ac_steps)
                ex = adh_exact(d, A, B, Es, g, ac, a0)
                if ex is None:
                    continue
                w_a = max(w_a, rel_err(adh_newton(d, A, B, Es, g, a0, steps, ac), ex))
                w_p = max(w_p, rel_err(adh_newton_prev(d, A, B, Es, g, a0, steps), ex))
            print(f"F4 adhesive radius ({label}: {len(group)}), {steps} Newton steps from the fold model's root: "
                  f"worst relative error {w_a:.2e} (from the previous radius: {w_p:.2e})")
            if steps == 5:
                bad += w_a > (1e-12 if label == "met" else 1e-6)
    print("fixed_count: " + ("all within bounds" if bad == 0 else f"{bad} check(s) OUT OF BOUNDS"))
    return 0 if bad == 0 else 1


if __name__ == "__main__":
    sys.exit(main())
