/* thornton_ning.h - the elastic-perfectly plastic normal law of Thornton and Ning (C. Thornton, Z. Ning, "A
 * theoretical model for the stick/bounce behaviour of adhesive, elastic-plastic spheres", Powder Technology 99
 * (1998) 154-162; its non-adhesive part, as in C. Thornton, J. Appl. Mech. 64 (1997) 383), a law unit (law.h; listed
 * in laws.h with DEM_EFFECT_THORNTON_NING), with Hertz-Mindlin's damping and tangential part.
 *
 * The contact is Hertzian until the largest contact pressure reaches the limiting pressure p_y, then the pressure
 * over the yielded zone stays at p_y:
 *   yield at       delta_y = (pi p_y / (2 E*))^2 r*,   F_y = 4/3 E* sqrt(r*) delta_y^(3/2)
 *   loading        F = 4/3 E* sqrt(r*) delta^(3/2)                        (delta <= delta_y)
 *                  F = F_y + pi p_y r* (delta - delta_y)                   (delta > delta_y)
 *   unloading      from the largest overlap delta_m (force F_m) along a Hertz curve of the flattened radius r_p:
 *   and reloading  F = 4/3 E* sqrt(r_p) (delta - delta_p)^(3/2), 0 once delta <= delta_p, where
 *                  a_p^2 = (2 F_m + F_y) / (2 pi p_y)   (the contact radius at delta_m),
 *                  r_p = 4 E* a_p^3 / (3 F_m),   delta_m - delta_p = a_p^2 / r_p = 3 F_m / (4 E* a_p)
 *                  (Thornton-Ning's Eq. for R_p; the second form is the Hertz relation delta = a^2 / r at a_p).
 *                  Reloading follows the same curve back to delta_m, then the loading line again.
 * Written with a_p and the elastic part delta_m - delta_p, every branch is + - * / sqrt: no power 2/3 is needed, and
 * the law is bitwise the same on every device (docs/design.md "Laws with memory"). Both branches meet at delta_m
 * (F = F_m) and at delta_y (a_p = the Hertz radius sqrt(r* delta_y)); tests/test_thornton_ning.c checks them against
 * these closed forms, typed in there.
 * The state kept per contact (law.h) is the largest overlap delta_m (negated while the contact has no bond, below); a
 * contact that ends (the spheres part) forgets it. Between delta_p and 0 the spheres still overlap geometrically but
 * carry no force (the dent is deeper than the overlap) - or a bond's tension (below).
 * Contact radius a (the elastic branches' sqrt(r* delta), on the plastic line a_p, unloading sqrt(r_p (delta -
 * delta_p))): the tangential stiffness k_t = 8 G* a and the damping's stiffness S_n = 2 E* a, as Hertz-Mindlin's with
 * a = sqrt(r* delta) (hm_contact_fel). The damping calibrated from the restitution then acts on top of the plastic
 * loss; a material that should lose energy by yield alone is given restitution 1.
 *
 * Pair-table columns (dem_layout.h): Hertz-Mindlin's and PM_TN_PIPY = pi p_y, PM_TN_DY = delta_y / r*,
 * PM_TN_FY = F_y / r*^2 (host/core/sim_setup.c, in double from p_y, the smaller yield stress of the two materials
 * that yield). A pair of which neither yields (all three 0) is Hertzian.
 * Bonds (PM_TN_SIGB = pi sigma_b, dem_material.bond_strength): a yielded contact has formed a solid bridge over its
 * plastic contact area pi a_p^2 (bonding area x bonding strength, the picture behind Rumpf's tensile strength of an
 * agglomerate). Unloaded past its dent (delta < delta_p) it is a flat circular contact of radius a_p pulled apart:
 *   F = 2 E* a_p (delta - delta_p) (< 0),  while -F <= F_b = sigma_b pi a_p^2,
 * and it breaks the first time the tension would pass F_b. While the bond holds, the normal force (with its
 * damping) may go down to -F_b and the Coulomb limit is mu (f_n + F_b), also in compression (as JKR-type laws let
 * adhesion raise the load friction resists); a bonded contact that slides (its tangential force meets that limit)
 * breaks its bond too, at the end of the step: the bridge's shear strength is mu (f_n + F_b), as bonded-particle
 * models give a bond a normal and a shear strength (Potyondy and Cundall 2004). A broken contact carries no tension
 * until it yields further (loads past its largest overlap on the plastic line), which forms a new bond over the new
 * plastic area: in a compact under compaction the contacts that slide while the powder rearranges bond again as the
 * pressure flattens them. Rolling resistance (rolling.h) acts with the compressive normal force only. The force is
 * continuous at delta_p, its slope is not: the Hertz curve's goes to 0 there, the bond's is 2 E* a_p (and the
 * tangential stiffness and the damping, which follow the contact radius, jump from 0 to a_p's). The state is the
 * largest overlap, negated while the contact has no bond. A pair's bond may hold across a gap (contact_forces.h); a
 * wall's cannot (its geometry ends the contact at zero overlap, so a wall given a bond strength lets go there,
 * unbroken, where the dent is shallower than the bond's stretch F_b / (2 E* a_p)): bonds are meant for powder on
 * powder, tools' steel bonds to nothing.
 * JKR adhesion (DEM_EFFECT_ADHESION, PM_TN_K; docs/laws/thornton_ning.md): the pair's work of adhesion w acts as in
 * Johnson, Kendall and Roberts (1971): a contact of radius a sits k sqrt(a) below its non-adhesive overlap and pulls
 * with 2 E* k a sqrt(a) more, k = sqrt(2 pi w / E*) (JKR's delta = a^2/R - sqrt(2 pi w a / E*), F = 4 E* a^3 / (3 R)
 * - sqrt(8 pi w E* a^3)). Thornton and Ning's paper could not be read here; the reading taken, after their abstract's
 * picture (a yielded contact unloads as a JKR contact of the flattened radius R_p, so its pull-off force grows with
 * plastic deformation: F_cp = 3/2 pi w R_p), is that the adhesive terms act on top of the law above written in
 * the contact radius a:
 *   loading    delta = a^2 / r* - k sqrt(a)   (the non-adhesive law's a = sqrt(r* delta_H) on both of its
 *              branches; it yields when a reaches a_y = sqrt(r* delta_y), the Hertzian pressure p_y),
 *              F = F_H(a) - 2 E* k a sqrt(a), F_H = 4/3 E* a^3 / r* (a <= a_y), pi p_y a^2 - F_y / 2 (a > a_y: the
 *              plastic line F_y + pi p_y r* (delta_H - delta_y) in a);
 *   unloading  from the largest contact radius a_m (at the largest overlap delta_m): R_p = 4 E* a_m^3 / (3 F_H(a_m))
 *              (r* if it never yielded), delta_p = a_m^2 / r* - a_m^2 / R_p, and
 *              delta = delta_p + a^2 / R_p - k sqrt(a), F = 4/3 E* a^3 / R_p - 2 E* k a sqrt(a);
 *   it lets go where the stable branch ends (d delta / da = 0): at a_c, a_c^(3/2) = k rho / 4, delta - delta_p =
 *   -3/4 k sqrt(a_c) (rho = r* or R_p; JKR's -3 a_c^2 / rho with a_c^3 = pi w rho^2 / (8 E*), force -5/6 pi w rho);
 *   a new contact forms at zero overlap (at JKR's force there, -4/3 pi w r*: no jump-in from a gap).
 * Each branch is s^4 / rho - k s = delta' in s = sqrt(a): tn_jkr_root solves it for u = s - s_c by a fixed count of
 * Newton steps from a start above the root that depends on delta' (the function is convex in u, so every step stays
 * above it), the same in the reference and the kernels; s_c from laws/mdr_core.h's fixed-count cube root. One cube
 * root and one solve per evaluation, loading or unloading. The damping and tangential stiffness take the
 * contact radius a; the Coulomb limit is mu (F + 3 pi w rho) (fn_min = -2 F_c: Thornton and Yin's mu (P + 2 P_c), the
 * load friction resists raised by adhesion). A pair keeps its contact across a gap (contact_forces.h) down to the
 * release, and so does a wall's (wall_forces.h, wall_contact_eval: r* = r_i); so does its stress (particle_stress.h).
 * The state of an adhesive contact is its largest contact radius a_m (since 2026-12-06; before, the largest overlap,
 * from which each unloading step solved for a_m again: the checkpoints say which, app/checkpoint.h), from which the
 * largest overlap is a_m^2 / r* - k sqrt(a_m) on the loading curve; negated
 * once the contact has let go (a pair may not both adhere and bond, so the bond's sign is free: host/core/sim_setup.c):
 * a yielded contact lets go where its dent is still deeper than the overlap, and is kept with no force while the
 * spheres overlap, as the non-adhesive law keeps it below delta_p; it adheres again if its surfaces meet again
 * (delta >= delta_p, as a contact forming at zero overlap), and ends once the spheres part.
 */
#ifndef DEM_LAW_THORNTON_NING_H
#define DEM_LAW_THORNTON_NING_H
#include "law.h"
#include "hertz_mindlin.h"
#include "mdr_core.h" /* mdr_cbrt, the fixed-count cube root */

#define LAW_COLUMNS_thornton_ning(C)                                                                                 \
    C(PM_ESTAR) C(PM_GSTAR) C(PM_MU) C(PM_DAMP_N) C(PM_DAMP_T) C(PM_TN_PIPY) C(PM_TN_DY) C(PM_TN_FY) C(PM_TN_SIGB)   \
    C(PM_TN_K)

/* A point of the law: the elastic normal force, the contact radius, and the lowest normal force the contact may carry
 * at this point (-F_b while a bond holds, else 0) */
typedef struct {
    real f;    /* [N] */
    real a;    /* [m] */
    real fmin; /* [N] */
    int broke; /* 1: the bond broke at this point (its tension passed F_b) */
} tn_point;

/* The bond a contact of plastic contact radius a_p holds: F_b = sigma_b pi a_p^2 (0 without bonds) */
DEM_INLINE real tn_bond_force(DEM_CONST_GLOBAL real *pm, real ap)
{
    return pm[PM_TN_SIGB] * ap * ap;
}

/* On the loading curve at overlap delta (the largest so far); bonded: 1 while the contact's bond is whole */
DEM_INLINE tn_point tn_loading(DEM_CONST_GLOBAL real *pm, real rstar, real delta, int bonded)
{
    tn_point p;
    real dy = pm[PM_TN_DY] * rstar;
    p.fmin = (real)0;
    p.broke = 0;
    if (!(pm[PM_TN_PIPY] > (real)0) || delta <= dy) {
        p.a = dem_sqrt(rstar * delta);
        p.f = hm_elastic_srd(pm[PM_ESTAR], p.a, delta);
        return p;
    }
    real fy = pm[PM_TN_FY] * rstar * rstar;
    p.f = fy + pm[PM_TN_PIPY] * rstar * (delta - dy);
    p.a = dem_sqrt(((real)2 * p.f + fy) / ((real)2 * pm[PM_TN_PIPY]));
    if (bonded && pm[PM_TN_SIGB] > (real)0) /* (not -0: a run without bonds keeps its clamp at +0) */
        p.fmin = -tn_bond_force(pm, p.a);
    return p;
}

/* At overlap delta given the largest overlap dmax >= delta: on the unloading (reloading) curve from dmax; *de gets
 * the elastic part of the overlap, delta - delta_p (<= 0: no force, or a bond's tension) */
DEM_INLINE tn_point tn_unloading(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real dmax, int bonded, real *de)
{
    tn_point p;
    p.fmin = (real)0;
    p.broke = 0;
    if (!(pm[PM_TN_PIPY] > (real)0) || dmax <= pm[PM_TN_DY] * rstar) { /* it never yielded: Hertz */
        *de = delta;
        if (delta < (real)0) { /* across a gap (contact_forces.h): no bond, no force */
            p.f = p.a = (real)0;
            return p;
        }
        p.a = dem_sqrt(rstar * delta);
        p.f = hm_elastic_srd(pm[PM_ESTAR], p.a, delta);
        return p;
    }
    tn_point m = tn_loading(pm, rstar, dmax, bonded);
    real dem = (real)3 * m.f / ((real)4 * pm[PM_ESTAR] * m.a); /* delta_m - delta_p */
    real d = delta - (dmax - dem);
    *de = d;
    if (!(d > (real)0)) {
        p.f = p.a = (real)0;
        if (m.fmin < (real)0) { /* a bond: a flat contact of radius a_p pulled, stiffness 2 E* a_p, up to F_b */
            real ften = (real)2 * pm[PM_ESTAR] * m.a * d;
            if (ften < m.fmin) {
                p.broke = 1;
            } else {
                p.f = ften;
                p.a = m.a;
                p.fmin = m.fmin;
            }
        }
        return p;
    }
    real rp = m.a * m.a / dem;
    p.a = dem_sqrt(rp * d);
    p.f = hm_elastic_srd(pm[PM_ESTAR], p.a, d);
    p.fmin = m.fmin;
    return p;
}

/* The magnitude of a stored state st: the largest overlap (negated while the contact has no bond), or with JKR
 * adhesion the largest contact radius (negated once it let go) */
DEM_INLINE real tn_dmax(real st)
{
    return st < (real)0 ? -st : st;
}

/* The point at delta given the stored state st: the largest overlap, negated while the contact has no bond (0: a new
 * contact) */
DEM_INLINE tn_point tn_at(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real st, real *de)
{
    int bonded = !(st < (real)0);
    real dmax = tn_dmax(st);
    if (delta >= dmax) {
        *de = delta; /* not used on loading */
        return tn_loading(pm, rstar, delta, bonded);
    }
    return tn_unloading(pm, rstar, delta, dmax, bonded, de);
}

/* ---- JKR adhesion (DEM_EFFECT_ADHESION) ---- */
/* Newton steps of tn_jkr_root. Its start is within 23 % above the root and the error then falls quadratically: 6 steps
 * reach rounding in fp64 everywhere on the branch, the release included (tests/test_tn_adhesion.c checks the force at
 * every step against a bisection) */
#define TN_JKR_STEPS 6

/* s = sqrt(a) >= s_c on the stable branch of s^4 / rho - k s = d (s_c^3 = k rho / 4, d >= -3/4 k s_c, the release).
 * Solved for u = s - s_c, about the release, where the slope of s^4 / rho - k s vanishes: with D = rho (d + 3/4 k s_c)
 * (>= 0 on the branch) the equation is F(u) = u^2 (u^2 + 4 s_c u + 6 s_c^2) - D = 0, convex for u >= 0. Since
 * u^2 + 4 s_c u + 6 s_c^2 >= (u + 2 s_c)^2, u0 = sqrt(D) / (sqrt(s_c^2 + sqrt(D)) + s_c) (the root of u (u + 2 s_c) =
 * sqrt(D), written without cancellation) lies above the root, at most sqrt(6)/2 times it (near the release, where F ~ 6 s_c^2
 * u^2); Newton from above stays above it. Near the release the root in s is double, and Newton in s from a start far
 * above it only halved the error per step (12 steps until 2026-12-06, each waiting on the last); in u from u0 the
 * error falls quadratically there too. sc must be rho's own s_c (tn_jkr_sc(rho, k)): the expansion uses s_c^3 = k rho / 4.
 * "To rounding" is in u for the D it is given: next to the release D = rho (d - delta_c) itself carries the rounding of
 * d and of s_c, which moves the root there (7.7e-10 F_c in the force at 1e-14 |delta_c|: tests/test_tn_adhesion.c,
 * test_root). */
DEM_INLINE real tn_jkr_root(real rho, real k, real d, real sc)
{
    real dd = rho * (d + (real)0.75 * k * sc);
    if (!(dd > (real)0)) /* at (or, rounded, past) the release */
        return sc;
    real rd = dem_sqrt(dd);
    real u = rd / (dem_sqrt(sc * sc + rd) + sc);
    real c4 = (real)4 * sc, c6 = (real)6 * sc * sc, c3 = (real)3 * sc, c3s = (real)3 * sc * sc;
    for (int it = 0; it < TN_JKR_STEPS; it++) {
        real u2 = u * u;
        real f = u2 * (u2 + c4 * u + c6) - dd;
        real fp = (real)4 * u * (u2 + c3 * u + c3s);
        real step = fp > (real)0 ? f / fp : (real)0;
        u = u - step;
        if (u < (real)0)
            u = (real)0;
    }
    return sc + u;
}

/* s_c = sqrt(a_c) of a branch of radius rho: s_c^3 = k rho / 4 */
DEM_INLINE real tn_jkr_sc(real rho, real k)
{
    return mdr_cbrt(k * rho / (real)4);
}

/* The non-adhesive law's force at contact radius a on loading (a^2 = r* delta_H): Hertz to a_y, then the plastic
 * line pi p_y a^2 - F_y / 2 */
DEM_INLINE real tn_hertzian_force(DEM_CONST_GLOBAL real *pm, real rstar, real a)
{
    if (pm[PM_TN_PIPY] > (real)0 && a * a > rstar * rstar * pm[PM_TN_DY])
        return pm[PM_TN_PIPY] * a * a - pm[PM_TN_FY] * rstar * rstar / (real)2;
    return (real)4 * pm[PM_ESTAR] * a * a * a / ((real)3 * rstar);
}

/* The unloading branch from the largest contact radius am (> 0): its radius rho (R_p, or r* if the contact never
 * yielded), its offset dp = delta_p and its s_c */
DEM_INLINE void tn_jkr_branch(DEM_CONST_GLOBAL real *pm, real rstar, real am, real *rho, real *dp, real *sc)
{
    *rho = rstar;
    *dp = (real)0;
    if (pm[PM_TN_PIPY] > (real)0 && am * am > rstar * rstar * pm[PM_TN_DY]) { /* it yielded */
        *rho = (real)4 * pm[PM_ESTAR] * am * am * am / ((real)3 * tn_hertzian_force(pm, rstar, am));
        *dp = am * am / rstar - am * am / *rho;
    }
    *sc = tn_jkr_sc(*rho, pm[PM_TN_K]);
}

/* The largest overlap of an adhesive contact whose state is st (its largest contact radius a_m, negated once it let
 * go; 0: a new contact): the loading curve's delta = a_m^2 / r* - k sqrt(a_m), 0 for a new contact */
DEM_INLINE real tn_jkr_dmax(DEM_CONST_GLOBAL real *pm, real rstar, real st)
{
    real am = tn_dmax(st);
    return am > (real)0 ? am * am / rstar - pm[PM_TN_K] * dem_sqrt(am) : (real)0;
}

/* Where an adhesive contact (state st: its largest contact radius, negated once it has let go) is at overlap delta:
 * its branch's radius *rho (r*, or R_p unloading from a yielded contact), that branch's *sc and s = sqrt(a) on it
 * (*s); *load whether that is the loading curve (delta at or past the largest overlap: the contact's largest radius
 * is then s^2). unload 0: the law's branch (loading at or past the largest overlap, else unloading from it); 1: the
 * unloading branch from max(delta, the largest overlap), along which the energy is counted. Returns 1, solving
 * nothing, where the contact has nothing to carry: below its release point, or released and its surfaces not met
 * again (delta - delta_p < 0; where they meet it adheres anew, as a contact forming at zero overlap does). Keeping
 * a_m, not the largest overlap, spares the solve for it: unloading takes one cube root (its branch's s_c) and one
 * solve, loading one of each (r*'s s_c) */
DEM_INLINE int tn_jkr_solve(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real st, int unload, real *rho, real *sc,
                            real *s, int *load)
{
    real k = pm[PM_TN_K], am = tn_dmax(st), dmax = tn_jkr_dmax(pm, rstar, st), dp = (real)0;
    int released = 0;
    *rho = rstar;
    *load = !(delta < dmax);
    if (*load) { /* on the loading curve (r*'s branch) */
        *sc = tn_jkr_sc(rstar, k);
        *s = tn_jkr_root(rstar, k, delta, *sc);
        if (!unload)
            return 0;
        am = *s * *s > am ? *s * *s : am; /* the energy: unloading from here */
    }
    tn_jkr_branch(pm, rstar, am, rho, &dp, sc);
    released = st < (real)0 && delta < dmax ? delta - dp < (real)0 : delta - dp < (real)-0.75 * k * *sc;
    if (!released)
        *s = tn_jkr_root(*rho, k, delta - dp, *sc);
    return released;
}

/* The adhesive law at overlap delta given the contact's state st: the elastic force and contact radius, fmin = -3 pi
 * w rho (the Coulomb limit's offset), *rel whether it is released after this point (f = a = fmin = 0), and *load
 * whether it is on the loading curve (its largest contact radius is then p.a) */
DEM_INLINE tn_point tn_jkr_at(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real st, int *rel, int *load)
{
    tn_point p;
    real es = pm[PM_ESTAR], k = pm[PM_TN_K], rho, sc, s;
    p.broke = 0;
    *rel = tn_jkr_solve(pm, rstar, delta, st, 0, &rho, &sc, &s, load);
    if (*rel) {
        p.f = p.a = p.fmin = (real)0;
        return p;
    }
    p.a = s * s;
    p.f = (*load ? tn_hertzian_force(pm, rstar, p.a) : (real)4 * es * p.a * p.a * p.a / ((real)3 * rho)) -
          (real)2 * es * k * p.a * s;
    p.fmin = (real)-1.5 * es * k * k * rho; /* -3 pi w rho = -2 F_c: pi w = E* k^2 / 2 */
    return p;
}

/* What an adhesive contact (state st) gives back if pulled from overlap delta along the unloading branch from
 * max(delta, its largest overlap) to its release: G(a) - G(a_c), G(a) = 8/15 E* a^5 / rho^2 - 4/3 E* k a^(7/2) / rho +
 * E* k^2 a^2 / 2 (the integral of F d delta along the branch), G(a_c) = 16/5 E* a_c^5 / rho^2; negative in the
 * adhesive well, 0 once let go or while released */
DEM_INLINE real tn_jkr_energy(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real st)
{
    real es = pm[PM_ESTAR], k = pm[PM_TN_K], rho, sc, s;
    int load;
    if (tn_jkr_solve(pm, rstar, delta, st, 1, &rho, &sc, &s, &load))
        return (real)0;
    real a = s * s, ac = sc * sc;
    real g = (real)8 / (real)15 * es * a * a * a * a * a / (rho * rho) - (real)4 / (real)3 * es * k * a * a * a * s / rho +
             es * k * k * a * a / (real)2;
    return g - (real)16 / (real)5 * es * ac * ac * ac * ac * ac / (rho * rho);
}

/* ---- the law unit (law.h) ---- */
DEM_INLINE law_result thornton_ning_force(unsigned fx, law_in c, law_ctx ctx)
{
    real de;
    int slid;
    if ((fx & DEM_EFFECT_ADHESION) && c.pm[PM_TN_K] > (real)0) { /* JKR adhesion; no bond on such a pair */
        real am = tn_dmax(c.st), st;
        int rel, load;
        tn_point q = tn_jkr_at(c.pm, c.rstar, c.delta, c.st, &rel, &load);
        law_result r = hm_contact_bond(fx, c.n, q.f, q.a, c.mstar, c.vrel, c.pm, c.dt, c.hist, q.fmin, &slid);
        st = load && q.a > am ? q.a : am; /* the largest contact radius (a loading contact is never released) */
        r.st = rel ? -st : st;
        /* a released contact is kept, with no force, while the spheres overlap (its dent is remembered, as without
         * adhesion); across a gap it ends */
        r.active = !rel || c.delta > (real)0;
        return r;
    }
    tn_point p = tn_at(c.pm, c.rstar, c.delta, c.st, &de);
    law_result r = hm_contact_bond(fx, c.n, p.f, p.a, c.mstar, c.vrel, c.pm, c.dt, c.hist, p.fmin, &slid);
    real dmax = tn_dmax(c.st);
    real st = c.delta > dmax ? c.delta : dmax;
    r.st = st;
    if (c.pm[PM_TN_SIGB] > (real)0) { /* the bond's fate (runs without bonds keep st >= 0) */
        /* a contact that yields further forms a bond (anew where one broke); one that slides or is pulled past F_b
         * has none after this step */
        int whole = !(c.st < (real)0) || (c.delta > dmax && c.delta > c.pm[PM_TN_DY] * c.rstar);
        if (!whole || p.broke || slid)
            r.st = -st;
    }
    if (c.delta < (real)0 && !(p.f < (real)0)) /* across a gap, only a whole bond holds (contact_forces.h) */
        r.active = 0;
    return r;
}
/* The elastic force at delta given the contact's state st (the stress output: particle_stress.h) */
DEM_INLINE real thornton_ning_elastic(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real st)
{
    real de;
    if (pm[PM_TN_K] > (real)0) { /* JKR adhesion (0 unless DEM_EFFECT_ADHESION: sim_setup.c) */
        int rel, load;
        return tn_jkr_at(pm, rstar, delta, st, &rel, &load).f;
    }
    return tn_at(pm, rstar, delta, st, &de).f;
}
/* What the contact gives back if unloaded from delta: 2/5 F (delta - delta_p), the Hertz energy of its elastic part
 * (a bond in tension: 1/2 F (delta - delta_p)) */
DEM_INLINE real thornton_ning_energy(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real st)
{
    real de;
    if (pm[PM_TN_K] > (real)0) /* JKR adhesion (0 unless DEM_EFFECT_ADHESION: sim_setup.c) */
        return tn_jkr_energy(pm, rstar, delta, st);
    real dmax = tn_dmax(st);
    tn_point p = tn_unloading(pm, rstar, delta, delta > dmax ? delta : dmax, !(st < (real)0), &de);
    if (p.f < (real)0) /* a bond's tension: a linear spring's */
        return (real)0.5 * p.f * de;
    return p.f > (real)0 ? hertz_energy_of_force(p.f, de) : (real)0;
}
DEM_INLINE real thornton_ning_energy_kept(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real fel, real st)
{
    return thornton_ning_energy(pm, rstar, delta, st);
}
/* At the stiffest: unloading from delta (k_n = 2 E* a_p >= the loading branch's slope) */
DEM_INLINE void thornton_ning_stiffness(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real *kn, real *kt)
{
    tn_point p = tn_loading(pm, rstar, delta, 0);
    *kn = hm_normal_stiffness(pm[PM_ESTAR], p.a);
    *kt = hm_tangential_stiffness(pm[PM_GSTAR], p.a);
}
#endif /* DEM_LAW_THORNTON_NING_H */
