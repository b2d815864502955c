/* mc_strain.h - the strain-based multi-contact law of Brodu et al. (seed 000 section 3.1, Eq. 8): Hertz-Mindlin
 * (hertz_mindlin.h) at the overlap d_eff = max(0, d_c + D_a,c + D_b,c), the geometric overlap plus the normal
 * displacements the other contacts of both particles induce at this one (a wall contact: D_a,c alone). The field D
 * (Eq. 7) is computed by the kernels of common/mc_strain.h and reaches the law through law_ctx (disp_a, disp_b).
 * Damping and the tangential stiffness follow d_eff; lever arms keep the geometric overlap (the callers'). With
 * DEM_MC_REACH a pair may be listed with a gap (delta <= 0): it touches only while d_eff > 0 (else the result is
 * inactive). At a patch the law is Hertz-Mindlin's (no displacement is kept for a patch contact).
 * Energy and stiffness: Hertz-Mindlin's at the geometric overlap (the host's energy and stability estimate, and the
 * series rows, count the contact as if it were Hertz's: series.h, host/physics/stability.c).
 *
 * Pair-table columns (dem_layout.h): Hertz-Mindlin's; the field's PM_MCS_K, PM_MCS_C1, PM_MCS_C2 and PM_MC_REACH are
 * read by common/mc_strain.h.
 */
#ifndef DEM_LAW_MC_STRAIN_H
#define DEM_LAW_MC_STRAIN_H
#include "hertz_mindlin.h"

#define LAW_COLUMNS_mc_strain(C) LAW_COLUMNS_hertz_mindlin(C) C(PM_MCS_K) C(PM_MCS_C1) C(PM_MCS_C2) C(PM_MC_REACH)

/* The overlap the Hertz law sees (Eq. 8), never negative. */
DEM_INLINE real mc_strain_overlap(real delta, real da, real db)
{
    real d = delta + da + db;
    return d > (real)0 ? d : (real)0;
}

/* ---- the law unit (law.h) ---- */
DEM_INLINE law_result mc_strain_force(unsigned fx, law_in c, law_ctx ctx)
{
    if (c.site == LAW_AT_PATCH)
        return hertz_mindlin_force(fx, c, ctx);
    real law_delta = mc_strain_overlap(c.delta, ctx.disp_a, c.site == LAW_AT_WALL ? (real)0 : ctx.disp_b);
    if (c.site == LAW_AT_PAIR && (fx & DEM_MC_REACH) && !(c.delta > (real)0) && !(law_delta > (real)0)) {
        law_result r; /* a neighbour within the contact distance whose induced overlap does not close the gap */
        r.active = 0;
        r.fel = r.st = (real)0;
        r.force = r.ft = r.hist = v3_zero();
        return r;
    }
    return hm_contact(fx, c.n, law_delta, dem_sqrt(c.rstar * law_delta), c.mstar, c.vrel, c.pm, c.dt, c.hist, (real)0);
}
DEM_INLINE real mc_strain_elastic(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real st)
{
    return hertz_mindlin_elastic(pm, rstar, delta, st);
}
DEM_INLINE real mc_strain_energy(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real st)
{
    return hertz_mindlin_energy(pm, rstar, delta, st);
}
DEM_INLINE real mc_strain_energy_kept(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real fel, real st)
{
    return hertz_mindlin_energy(pm, rstar, delta, st); /* fel is at the induced overlap */
}
DEM_INLINE void mc_strain_stiffness(DEM_CONST_GLOBAL real *pm, real rstar, real delta, real *kn, real *kt)
{
    hertz_mindlin_stiffness(pm, rstar, delta, kn, kt);
}
#endif /* DEM_LAW_MC_STRAIN_H */
