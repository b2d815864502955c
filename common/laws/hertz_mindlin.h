/* hertz_mindlin.h - the Hertz-Mindlin contact law of seed 000 section 2 (Eq. 2-6), written once: a law unit
 * (law.h; listed in laws.h with DEM_EFFECT_HERTZ, the law every run has unless another law of the list is on).
 *
 * Normal (Eq. 3):   f_n = 4/3 E* sqrt(r*) d^(3/2) - c sqrt(S_n m*) v_n,   S_n = 2 E* sqrt(r* d)
 *                   d^(3/2) sqrt(r*) is evaluated as sqrt(r* d) * d (only + - * / sqrt, see dem_real.h).
 *                   The total normal force is clamped at zero: a contact never pulls.
 * Tangential (Eq. 4-6, Tsuji): the elastic tangential force is kept as history and grows incrementally,
 *                   f_t,el(t+dt) = R[f_t,el(t)] - k_t v_t dt,   k_t = 8 G* sqrt(r* d),
 *                   where R rotates the stored force into the current tangent plane keeping its length;
 *                   damping -c sqrt(k_t m*) v_t; Coulomb limit |f_t| <= mu f_n. When sliding, the force is
 *                   scaled onto the cone and the stored spring force is set to it (spring rescaled).
 * Damping: the form is LIGGGHTS' (c = 2 sqrt(5/6) beta). The coefficient c is NOT beta = ln e/sqrt(ln^2 e + pi^2)
 *          (that is exact only for a linear spring); the host solves the dimensionless Hertz collision for the c
 *          that gives the requested restitution e (host/physics/restitution.c). c depends on e alone, so e is velocity
 *          independent. Since S_n = 2 E* sqrt(r* d) and k_t = 8 G* sqrt(r* d), both damping terms share
 *          q = sqrt(sqrt(r* d) m*); the pair table holds c sqrt(2 E*) and c sqrt(8 G*) (host-computed), so one
 *          square root serves both and no transcendental function is evaluated on the device.
 *
 * Multi-contact laws (mc_stress.h, mc_strain.h) are Hertz-Mindlin with another normal force and reach hm_contact
 *          through two arguments: `delta` is the overlap the law sees (MC-strain passes the geometric overlap plus
 *          the displacements induced by the other contacts, Eq. 8) and `fn_extra` is added to the elastic normal
 *          force before damping and the clamp (MC-stress, Eq. 10; only with DEM_EFFECT_MC_STRESS, so other runs
 *          compile exactly the classical law).
 *
 * Pair-table columns (dem_layout.h): E*, G*, mu and the two damping factors.
 *
 * Effects (dem_effects.h): without DEM_EFFECT_DAMPING the damping terms and their square root are left out; without
 *          DEM_EFFECT_FRICTION the whole tangential part is (no history, no torque).
 *
 * Conventions: body a and body b; n is the unit vector from b to a; d > 0 the overlap; vrel the velocity of a's
 * contact point relative to b's. Returned forces act on a (b receives the negative).
 */
#ifndef DEM_HERTZ_MINDLIN_H
#define DEM_HERTZ_MINDLIN_H
#include "law.h"

#define LAW_COLUMNS_hertz_mindlin(C) C(PM_ESTAR) C(PM_GSTAR) C(PM_MU) C(PM_DAMP_N) C(PM_DAMP_T)

/* Rotate the stored tangential force into the plane normal to n, keeping its magnitude. */
DEM_INLINE vec3 hm_rotate_history(vec3 h, vec3 n)
{
    real hn = v3_dot(h, n);
    vec3 hp = v3_sub(h, v3_scale(n, hn));
    real h2 = v3_dot(h, h);
    real hp2 = v3_dot(hp, hp);
    if (hp2 > (real)0 && hp2 != h2)
        hp = v3_scale(hp, dem_sqrt(h2 / hp2));
    return hp;
}

/* Elastic Hertz normal force (Eq. 3) given sqrt(r* d): the one expression every caller shares, so the stress
 * trace (particle_stress.h) sees the very bits the force law computes. */
DEM_INLINE real hm_elastic_srd(real estar, real srd, real delta)
{
    const real four_thirds = (real)4 / (real)3;
    return four_thirds * estar * srd * delta;
}
DEM_INLINE real hm_elastic(real estar, real rstar, real delta)
{
    return hm_elastic_srd(estar, dem_sqrt(rstar * delta), delta);
}

/* The elastic energy stored in a Hertz contact: the work of hm_elastic from 0 to delta, 2/5 F delta
 * = 8/15 E* sqrt(r*) delta^(5/2) [J]. The host's energies in double (host/physics/energy.c) and the series rows
 * (series.h) reach it through law_energy; hertz_energy_of_force is the same from the elastic force at delta, for a
 * caller that has it (contact_pairs in a sampled step). */
DEM_INLINE real hertz_energy_of_force(real fel, real delta)
{
    return (real)2 / (real)5 * fel * delta;
}
DEM_INLINE real hertz_energy(real estar, real rstar, real delta)
{
    return hertz_energy_of_force(hm_elastic(estar, rstar, delta), delta);
}

/* The law's stiffnesses at an overlap, given srd = sqrt(r* delta): normal dF/d(delta) = 2 E* sqrt(r* d) (S_n of Eq. 3's
 * damping) and tangential k_t = 8 G* sqrt(r* d) (Eq. 4). hm_contact uses the tangential one; the host's stability
 * estimate (host/physics/stability.c) both, through law_stiffness. */
DEM_INLINE real hm_normal_stiffness(real estar, real srd)
{
    return (real)2 * estar * srd;
}
DEM_INLINE real hm_tangential_stiffness(real gstar, real srd)
{
    return (real)8 * gstar * srd;
}

/* The contact given its elastic normal force fel and its contact radius srd (Hertz: sqrt(r* delta)), which sets the
 * damping's stiffness S_n = 2 E* srd and the tangential k_t = 8 G* srd: Hertz-Mindlin's, and that of a law with
 * another elastic force and the same Mindlin tangential part (thornton_ning.h) */
DEM_INLINE law_result hm_contact_core(unsigned fx, vec3 n, real fel, real srd, real mstar, vec3 vrel,
                                     DEM_CONST_GLOBAL real *pm, real dt, vec3 hist, real fn_extra, real fn_min,
                                     int *slid)
{
    law_result r;
    real q = (real)0;                   /* sqrt(sqrt(r* d) m*), shared by both damping terms */
    real vn = v3_dot(vrel, n);          /* < 0 while approaching: d' = -vn */

    r.active = 1;
    r.st = (real)0;
    /* normal */
    r.fel = fel;
    real fn = r.fel;
    if (fx & DEM_EFFECT_MC_STRESS)
        fn = fn + fn_extra;
    if (fx & DEM_EFFECT_DAMPING) {
        q = dem_sqrt(srd * mstar);
        fn = fn - pm[PM_DAMP_N] * q * vn;
    }
    if (fn < fn_min)
        fn = fn_min;

    /* tangential */
    *slid = 0;
    if (!(fx & DEM_EFFECT_FRICTION)) {
        r.ft = v3_zero();
        r.hist = v3_zero();
        r.force = v3_scale(n, fn);
        return r;
    }
    const real gstar = pm[PM_GSTAR], mu = pm[PM_MU];
    vec3 vt = v3_sub(vrel, v3_scale(n, vn));
    real kt = hm_tangential_stiffness(gstar, srd);
    vec3 ft_el = v3_sub(hm_rotate_history(hist, n), v3_scale(vt, kt * dt));
    vec3 ft = ft_el;
    if (fx & DEM_EFFECT_DAMPING)
        ft = v3_sub(ft_el, v3_scale(vt, pm[PM_DAMP_T] * q));
    real fmax = mu * (fn - fn_min); /* a bond's strength adds to the load friction resists (0 without) */
    real ft2 = v3_dot(ft, ft);
    if (ft2 > fmax * fmax) {
        ft = v3_scale(ft, fmax / dem_sqrt(ft2));
        r.hist = ft;
        *slid = 1;
    } else {
        r.hist = ft_el;
    }
    r.ft = ft;
    r.force = v3_add(v3_scale(n, fn), ft);
    return r;
}

/* fn_extra: MC-stress's added normal force; fn_min: the lowest normal force the contact carries (0: it only pushes;
 * -F_b: a bond's tension, thornton_ning.h); *slid: 1 when the tangential force met the Coulomb limit */
DEM_INLINE law_result hm_contact_fel(unsigned fx, vec3 n, real fel, real srd, real mstar, vec3 vrel,
                                    DEM_CONST_GLOBAL real *pm, real dt, vec3 hist, real fn_extra)
{
    int slid;
    return hm_contact_core(fx, n, fel, srd, mstar, vrel, pm, dt, hist, fn_extra, (real)0, &slid);
}
DEM_INLINE law_result hm_contact_bond(unsigned fx, vec3 n, real fel, real srd, real mstar, vec3 vrel,
                                     DEM_CONST_GLOBAL real *pm, real dt, vec3 hist, real fn_min, int *slid)
{
    return hm_contact_core(fx, n, fel, srd, mstar, vrel, pm, dt, hist, (real)0, fn_min, slid);
}

/* srd = sqrt(r* delta), computed by the caller (it may need it for its own terms: one square root, not two). */
DEM_INLINE law_result hm_contact(unsigned fx, vec3 n, real delta, real srd, real mstar, vec3 vrel,
                                DEM_CONST_GLOBAL real *pm, real dt, vec3 hist, real fn_extra)
{
    return hm_contact_fel(fx, n, hm_elastic_srd(pm[PM_ESTAR], srd, delta), srd, mstar, vrel, pm, dt, hist, fn_extra);
}

/* ---- the law unit (law.h) ---- */
DEM_INLINE law_result hertz_mindlin_force(unsigned fx, law_in c, law_ctx ctx)
{
    return hm_contact(fx, c.n, c.delta, dem_sqrt(c.rstar * c.delta), c.mstar, c.vrel, c.pm, c.dt, c.hist, (real)0);
}
DEM_INLINE real hertz_mindlin_elastic(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real st)
{
    return hm_elastic(pm[PM_ESTAR], rstar, delta);
}
DEM_INLINE real hertz_mindlin_energy(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real st)
{
    return hertz_energy(pm[PM_ESTAR], rstar, delta);
}
DEM_INLINE real hertz_mindlin_energy_kept(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real fel, real st)
{
    return hertz_energy_of_force(fel, delta);
}
DEM_INLINE void hertz_mindlin_stiffness(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real *kn, real *kt)
{
    real srd = dem_sqrt(rstar * delta);
    *kn = hm_normal_stiffness(pm[PM_ESTAR], srd);
    *kt = hm_tangential_stiffness(pm[PM_GSTAR], srd);
}
#endif /* DEM_HERTZ_MINDLIN_H */
