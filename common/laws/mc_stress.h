/* mc_stress.h - the stress-based multi-contact law (seed 000 Eq. 10 with the appendix's two passes): Hertz-Mindlin
 * (hertz_mindlin.h) whose elastic normal force gets the extra term
 *   f_extra = beta nu A_ij P_ij,  A_ij = pi r* d,  P_ij = -(T_i + T_j) / K
 * at a particle pair, and at a particle-wall contact the same with the particle's own trace for both (the wall has
 * none): f_extra = beta_i nu_i pi r_i d (-(T_i + T_i) / K). T is a particle's stress trace (Eq. 9), summed by pass 1
 * (particle_stress.h, stress_trace) and read here through law_ctx. Sign: the trace is negative in compression while
 * the correction must stiffen, so P is minus a trace. beta nu = 0 makes f_extra an exact zero (classical DEM bit for
 * bit). At a patch the law is Hertz-Mindlin's (no trace is kept for a patch's triangle).
 * The convention bits of dem_effects.h (compiled in with the effects) choose the reading of seed 000:
 *   T    = tr (DEM_MCS_OWN_IN) or tr - t_c (contact c's own term out: then one contact gives tr - t = 0 exactly and a
 *          two-sphere collision is bit-identical to classical DEM);
 *   t_c  = -(lever f_H) / V_p with lever = d = r_i + r_j - delta, a wall 2 (r - delta) (DEM_MCS_LEVER_CENTRES), or the
 *          contact point's r - delta/2, a wall r - delta (the tensor output always uses the contact point: Eq. 9);
 *   K    = 2 (DEM_MCS_SCALE_TRACE, Eq. 11), 3 (DEM_MCS_SCALE_TEXT, Eq. 10's text) or 6 (the appendix's 1/6).
 * The decisions and their measurements are in docs/multicontact.md; tests in tests/test_multicontact.c and
 * tests/test_mc_validation.c (Eq. 11 on the octahedron).
 * Energy and stiffness: Hertz-Mindlin's at the geometric overlap (the extra term's work is not counted; the stability
 * estimate takes the stiffness as Hertz's, host/physics/stability.c).
 *
 * Pair-table columns (dem_layout.h): Hertz-Mindlin's and PM_MC_STRESS (pi beta nu).
 */
#ifndef DEM_LAW_MC_STRESS_H
#define DEM_LAW_MC_STRESS_H
#include "hertz_mindlin.h"

#define LAW_COLUMNS_mc_stress(C) LAW_COLUMNS_hertz_mindlin(C) C(PM_MC_STRESS)

/* One contact's term of a stress trace (Eq. 9): arm = r_p - a_c, fh the elastic force, invvol = 1/V_p. */
DEM_INLINE real stress_term(real arm, real fh, real invvol) { return -(arm * fh) * invvol; }

/* The lever of a pair's term in the MC-stress trace of the particle of radius ra (partner rb), and of a wall's. */
DEM_INLINE real mcs_lever_pair(unsigned fx, real ra, real rb, real delta)
{
    return (fx & DEM_MCS_LEVER_CENTRES) ? (ra + rb) - delta : ra - (real)0.5 * delta;
}
DEM_INLINE real mcs_lever_wall(unsigned fx, real ri, real delta)
{
    return (fx & DEM_MCS_LEVER_CENTRES) ? (real)2 * (ri - delta) : ri - delta;
}

/* K of P = -(T_i + T_j) / K */
DEM_INLINE real mcs_divisor(unsigned fx)
{
    return (fx & DEM_MCS_SCALE_TRACE) ? (real)2 : (fx & DEM_MCS_SCALE_TEXT) ? (real)3 : (real)6;
}

/* MC-stress extra normal force of a pair (a, b) with overlap delta, effective radius rstar, elastic force fh. */
DEM_INLINE real mc_stress_pair(unsigned fx, DEM_CONST_GLOBAL real *pm, DEM_CONST_GLOBAL real *trace,
                               DEM_CONST_GLOBAL real *invvol, int a, int b, real ra, real rb, real delta, real rstar,
                               real fh)
{
    real ta = trace[a], tb = trace[b];
    if (!(fx & DEM_MCS_OWN_IN)) {
        ta = ta - stress_term(mcs_lever_pair(fx, ra, rb, delta), fh, invvol[a]);
        tb = tb - stress_term(mcs_lever_pair(fx, rb, ra, delta), fh, invvol[b]);
    }
    return -(pm[PM_MC_STRESS] * rstar * delta) * ((ta + tb) / mcs_divisor(fx));
}

/* MC-stress extra normal force of particle i on a wall (pmi: the pair-table row of i's own material). */
DEM_INLINE real mc_stress_wall(unsigned fx, DEM_CONST_GLOBAL real *pmi, DEM_CONST_GLOBAL real *trace,
                               DEM_CONST_GLOBAL real *invvol, int i, real ri, real delta, real fh)
{
    real ti = trace[i];
    if (!(fx & DEM_MCS_OWN_IN))
        ti = ti - stress_term(mcs_lever_wall(fx, ri, delta), fh, invvol[i]);
    return -(pmi[PM_MC_STRESS] * ri * delta) * ((ti + ti) / mcs_divisor(fx));
}

/* ---- the law unit (law.h) ---- */
DEM_INLINE law_result mc_stress_force(unsigned fx, law_in c, law_ctx ctx)
{
    if (c.site == LAW_AT_PATCH)
        return hertz_mindlin_force(fx, c, ctx);
    real srd = dem_sqrt(c.rstar * c.delta), fh = hm_elastic_srd(c.pm[PM_ESTAR], srd, c.delta);
    real extra = c.site == LAW_AT_WALL
                     ? mc_stress_wall(fx, c.pmi, ctx.trace, ctx.invvol, c.a, c.ra, c.delta, fh)
                     : mc_stress_pair(fx, c.pm, ctx.trace, ctx.invvol, c.a, c.b, c.ra, c.rb, c.delta, c.rstar, fh);
    return hm_contact(fx, c.n, c.delta, srd, c.mstar, c.vrel, c.pm, c.dt, c.hist, extra);
}
DEM_INLINE real mc_stress_elastic(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real st)
{
    return hertz_mindlin_elastic(pm, rstar, delta, st);
}
DEM_INLINE real mc_stress_energy(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real st)
{
    return hertz_mindlin_energy(pm, rstar, delta, st);
}
DEM_INLINE real mc_stress_energy_kept(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real fel, real st)
{
    return hertz_mindlin_energy_kept(pm, rstar, delta, fel, st);
}
DEM_INLINE void mc_stress_stiffness(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real *kn, real *kt)
{
    hertz_mindlin_stiffness(pm, rstar, delta, kn, kt);
}
#endif /* DEM_LAW_MC_STRESS_H */
