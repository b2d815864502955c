/* particle_stress.h - per-particle stress tensor and its trace (seed 000 Eq. 9), and the MC-stress correction
 * (Eq. 10) that uses the trace.
 *
 *   sigma_p = (1/V_p) sum_c l_c (x) f_c,   l_c = -(r_p - a_c) n_c,  f_c = f_H,c n_c
 * n_c is the unit normal pointing into particle p at contact c (from the partner, or from the wall), l_c the branch
 * vector from the centre to the contact point (a_c = d/2 for a particle pair, d for a wall: the same contact points
 * as the torques of contact_forces.h), and f_H the elastic Hertz force of the overlap (hm_elastic, Eq. 3: the
 * appendix's "ForcesLocal = Forces(Overlap)"). Damping is left out: the stress is that of the elastic state, and
 * tangential forces have no trace (l_c is parallel to n_c). The tensor is therefore symmetric,
 *   sigma_p = -(1/V_p) sum_c (r_p - a_c) f_H,c n_c (x) n_c,
 * negative (compressive) under load; its trace is -(1/V_p) sum_c (r_p - a_c) f_H,c.
 *
 * Canonical order: partners in ascending id (the whole sorted neighbour row), then walls in index order. Each term
 * is rounded as t_c = -((r_p - a_c) f_H,c) * (1/V_p) and added in that order, so every device gets the same bits.
 *
 * MC-stress (Eq. 10 with the appendix's two passes): pass 1 (stress_trace) sums each particle's trace; pass 2 (the
 * contact kernels) adds to the elastic normal force of a pair
 *   f_extra = beta nu A_ij P_ij,  A_ij = pi r* d,  P_ij = -(T_i + T_j) / K
 * and to a particle-wall contact the same with the particle's own trace for both (the wall has none):
 * f_extra = beta_i nu_i pi r_i d (-(T_i + T_i) / K). Sign: the trace is negative in compression while the correction
 * must stiffen, so P is minus a trace. beta nu = 0 makes f_extra an exact zero (classical DEM bit for bit).
 * The convention bits of dem_effects.h (compiled in with the effects) choose the reading of seed 000:
 *   T    = tr (DEM_MCS_OWN_IN) or tr - t_c (contact c's own term out: then one contact gives tr - t = 0 exactly and a
 *          two-sphere collision is bit-identical to classical DEM);
 *   t_c  = -(lever f_H) / V_p with lever = d = r_i + r_j - delta, a wall 2 (r - delta) (DEM_MCS_LEVER_CENTRES), or the
 *          contact point's r - delta/2, a wall r - delta (the tensor output always uses the contact point: Eq. 9);
 *   K    = 2 (DEM_MCS_SCALE_TRACE, Eq. 11), 3 (DEM_MCS_SCALE_TEXT, Eq. 10's text) or 6 (the appendix's 1/6).
 * The decisions and their measurements are in docs/multicontact.md; tests in tests/test_multicontact.c and
 * tests/test_mc_validation.c (Eq. 11 on the octahedron).
 */
#ifndef DEM_PARTICLE_STRESS_H
#define DEM_PARTICLE_STRESS_H
#include "dem_kernels.h"
#include "contacts.h"
#include "contact_geometry.h"
#include "hertz_mindlin.h"

/* One contact's trace term: arm = r_p - a_c, fh the elastic force, invvol = 1/V_p. */
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

/* Adds one contact to a tensor sum: c * n (x) n with c = stress_term(...). */
DEM_INLINE void stress_add(real *st, real c, vec3 n)
{
    st[ST_XX] = st[ST_XX] + c * n.x * n.x;
    st[ST_YY] = st[ST_YY] + c * n.y * n.y;
    st[ST_ZZ] = st[ST_ZZ] + c * n.z * n.z;
    st[ST_XY] = st[ST_XY] + c * n.x * n.y;
    st[ST_XZ] = st[ST_XZ] + c * n.x * n.z;
    st[ST_YZ] = st[ST_YZ] + c * n.y * n.z;
}

/* Particle i's stress, one work item per particle: tensor = 0 writes the trace into out[i] (MC-stress pass 1, every
 * step), tensor = 1 the six components into out[6i...] (output, when DEM_FIELD_STRESS is read). The kernels pass a
 * constant, so each compiles only its own sums. Same terms, same order either way. */
DEM_INLINE void stress_at(unsigned fx, int tensor, int i, DEM_CONST_GLOBAL int *nbr_start, DEM_CONST_GLOBAL real *x,
                            DEM_CONST_GLOBAL real *radius, DEM_CONST_GLOBAL real *invvol, DEM_CONST_GLOBAL int *mat,
                            DEM_CONST_GLOBAL real *pairmat, int nmat, DEM_CONST_GLOBAL int *nbr_count,
                            DEM_CONST_GLOBAL int *nbr_lower, DEM_CONST_GLOBAL int *nbr_list, int nwalls,
                            DEM_CONST_GLOBAL int *wall_int,
                            DEM_CONST_GLOBAL real *wall_real, DEM_CONST_GLOBAL unsigned *ride, DEM_GLOBAL real *out)
{
    vec3 xi = v3_load(x, i);
    real ri = radius[i], iv = invvol[i], tr = (real)0;
    real st[ST_STRIDE];
    for (int c = 0; c < ST_STRIDE; c++)
        st[c] = (real)0;
    int mi = mat[i], cnt = nbr_count[i], lower = row_lower(nbr_lower[i]), nw = (fx & DEM_EFFECT_WALLS) ? nwalls : 0;
    int row0 = nbr_start[i];
    for (int k = 0; k < contact_count(cnt, nw); k++) { /* the canonical order (contacts.h): the row, then the walls */
        contact_ref r = contact_at(i, k, cnt, lower, row0, nwalls, nbr_list);
        real delta, rstar, arm;
        vec3 n;
        int other;
        if (r.kind != CONTACT_WALL) {
            int j = r.partner;
            pair_geom g = pair_geometry(xi, ri, v3_load(x, j), radius[j]);
            if (!g.active)
                continue;
            delta = g.delta, rstar = g.rstar, n = g.n, other = mat[j];
            arm = tensor ? ri - (real)0.5 * g.delta : mcs_lever_pair(fx, ri, radius[j], g.delta);
        } else {
            int w = r.partner;
            wall_geom g = wall_met(fx, wall_int, wall_real, ride, i, w, xi, ri);
            if (!g.active)
                continue;
            delta = g.delta, rstar = ri, n = g.n, other = wall_int[w * WI_STRIDE + WI_MATERIAL];
            arm = tensor ? ri - g.delta : mcs_lever_wall(fx, ri, g.delta);
        }
        real c = stress_term(arm, hm_elastic(pairmat[PM_STRIDE * (mi * nmat + other) + PM_ESTAR], rstar, delta), iv);
        if (tensor)
            stress_add(st, c, n);
        else
            tr = tr + c;
    }
    if (tensor)
        for (int c = 0; c < ST_STRIDE; c++)
            out[ST_STRIDE * i + c] = st[c];
    else
        out[i] = tr;
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
DEM_ITEM(stress_trace)
{
    stress_at(fx, 0, i, nbr_start, x, radius, invvol, mat, pairmat, nmat, nbr_count, nbr_lower, nbr_list, nwalls, wall_int,
              wall_real, ride, trace);
}

DEM_ITEM(stress_tensor)
{
    stress_at(fx, 1, i, nbr_start, x, radius, invvol, mat, pairmat, nmat, nbr_count, nbr_lower, nbr_list, nwalls, wall_int,
              wall_real, ride, stress);
}
#endif /* DEM_PARTICLE_STRESS_H */
