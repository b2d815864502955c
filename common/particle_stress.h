/* particle_stress.h - per-particle stress tensor and its trace (seed 000 Eq. 9); the trace is what the MC-stress law
 * (laws/mc_stress.h, Eq. 10) reads.
 *
 *   sigma_p = (1/V_p) sum_c l_c (x) f_c,   l_c = -(r_p - a_c) n_c,  f_c = f_H,c n_c
 * n_c is the unit normal pointing into particle p at contact c (from the partner, or from the wall), l_c the branch
 * vector from the centre to the contact point (a_c = d/2 for a particle pair, d for a wall: the same contact points
 * as the torques of contact_forces.h), and f_H the elastic normal force of the overlap (the run's law: law_elastic,
 * laws/laws.h; Hertz's Eq. 3 for Hertz-Mindlin and the multi-contact laws: the appendix's "ForcesLocal =
 * Forces(Overlap)"). Damping is left out: the stress is that of the elastic state, and
 * tangential forces have no trace (l_c is parallel to n_c). The tensor is therefore symmetric,
 *   sigma_p = -(1/V_p) sum_c (r_p - a_c) f_H,c n_c (x) n_c,
 * negative (compressive) under load; its trace is -(1/V_p) sum_c (r_p - a_c) f_H,c.
 *
 * Contacts that hold across a gap (a bond's or JKR adhesion's, laws/thornton_ning.h: contact_geometry.h's
 * pair_geometry_held and wall_met_held) are summed with their overlap delta < 0 and their tension (f_H < 0), as the
 * forces took them; before 2026-12-06 the stress left them out.
 *
 * Canonical order: partners in ascending id (the whole sorted neighbour row), then walls in index order. Each term
 * is rounded as t_c = -((r_p - a_c) f_H,c) * (1/V_p) and added in that order, so every device gets the same bits.
 *
 * MC-stress (Eq. 10 with the appendix's two passes): pass 1 (stress_trace) sums each particle's trace with the
 * lever its convention bits choose (laws/mc_stress.h: mcs_lever_*); pass 2 is the law's force (laws/mc_stress.h).
 */
#ifndef DEM_PARTICLE_STRESS_H
#define DEM_PARTICLE_STRESS_H
#include "dem_kernels.h"
#include "contacts.h"
#include "contact_geometry.h"
#include "laws/laws.h"

/* stress_term, the MC-stress levers and divisor: laws/mc_stress.h */

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
                            DEM_CONST_GLOBAL real *wall_real, DEM_CONST_GLOBAL unsigned *ride,
                            DEM_CONST_GLOBAL int *own_start, DEM_CONST_GLOBAL int *in_start,
                            DEM_CONST_GLOBAL int *in_pair, DEM_CONST_GLOBAL dem_byte *touch,
                            DEM_CONST_GLOBAL real *law_st, DEM_CONST_GLOBAL unsigned *wall_mask,
                            DEM_CONST_GLOBAL real *wall_law, DEM_GLOBAL real *out)
{
    vec3 xi = v3_load(x, i);
    real ri = radius[i], iv = invvol[i], tr = (real)0;
    real st[ST_STRIDE];
    for (int c = 0; c < ST_STRIDE; c++)
        st[c] = (real)0;
    int mi = mat[i], cnt = nbr_count[i], lower = row_lower(nbr_lower[i]), nw = (fx & DEM_EFFECT_WALLS) ? nwalls : 0;
    int row0 = nbr_start[i], h = 0; /* h: the row's slots so far whose partner is stored after i (contacts.h row_pair) */
    for (int k = 0; k < contact_count(cnt, nw); k++) { /* the canonical order (contacts.h): the row, then the walls */
        contact_ref r = contact_at(i, k, cnt, lower, row0, nwalls, nbr_list);
        real delta, rstar, arm, lst = (real)0; /* lst: the law's state of a contact that touched (laws/law.h) */
        vec3 n;
        int other;
        if (r.kind != CONTACT_WALL) {
            int j = r.partner, hk = h;
            if (fx & DEM_LAW_STATE_BITS) /* only a law's states need the pair number */
                h += j > i;
            other = mat[j];
            pair_geom g = pair_geometry(xi, ri, v3_load(x, j), radius[j]);
            /* the pair's state: a touching pair's, and under Thornton-Ning any pair's (it may hold across a gap) */
            if ((fx & DEM_LAW_STATE_BITS) && (g.active || (fx & DEM_EFFECT_THORNTON_NING))) {
                int p = row_pair(i, j, k, hk, own_start[i], in_start[i], in_pair), t = touch[p];
                DEM_CONST_GLOBAL real *ps = law_st + p * DEM_LAW_PAIR_W(fx);
                /* a bond or a JKR contact that holds across a gap (contact_geometry.h), as the forces saw it */
                g = pair_geometry_held(fx, g, xi, ri, v3_load(x, j), radius[j], t, ps, pairmat, mat, nmat, i, j);
                lst = t ? ps[DEM_LAW_PAIR_ELASTIC(fx)] : (real)0;
            }
            if (!g.active)
                continue;
            delta = g.delta, rstar = g.rstar, n = g.n;
            arm = tensor ? ri - (real)0.5 * g.delta : mcs_lever_pair(fx, ri, radius[j], g.delta);
        } else {
            int w = r.partner, t = (wall_mask[i] >> w) & 1u;
            other = wall_int[w * WI_STRIDE + WI_MATERIAL];
            wall_geom g = wall_met(fx, wall_int, wall_real, ride, i, w, xi, ri);
            if (fx & DEM_LAW_STATE_BITS) {
                DEM_CONST_GLOBAL real *ws = wall_law + r.slot * DEM_LAW_WALL_W(fx);
                g = wall_met_held(fx, g, wall_int, wall_real, ride, i, w, xi, ri, t, ws,
                                  pairmat + PM_STRIDE * (mi * nmat + other)); /* (JKR adhesion across a gap) */
                lst = t ? ws[DEM_LAW_WALL_ELASTIC(fx)] : (real)0;
            }
            if (!g.active)
                continue;
            delta = g.delta, rstar = ri, n = g.n;
            arm = tensor ? ri - g.delta : mcs_lever_wall(fx, ri, g.delta);
        }
        real c = stress_term(arm, law_elastic(fx, pairmat + PM_STRIDE * (mi * nmat + other), rstar, delta, lst), iv);
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

DEM_ITEM(stress_trace)
{
    stress_at(fx, 0, i, nbr_start, x, radius, invvol, mat, pairmat, nmat, nbr_count, nbr_lower, nbr_list, nwalls, wall_int,
              wall_real, ride, own_start, in_start, in_pair, touch, law_st, wall_mask, wall_law, trace);
}

DEM_ITEM(stress_tensor)
{
    stress_at(fx, 1, i, nbr_start, x, radius, invvol, mat, pairmat, nmat, nbr_count, nbr_lower, nbr_list, nwalls, wall_int,
              wall_real, ride, own_start, in_start, in_pair, touch, law_st, wall_mask, wall_law, stress);
}
#endif /* DEM_PARTICLE_STRESS_H */
