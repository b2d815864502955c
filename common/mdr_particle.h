/* mdr_particle.h - MDR's per-particle steps (Part II of Zunker and Kamrin; docs/laws/mdr.md (M31)-(M36)): the two
 * kernels a run with DEM_EFFECT_MDR adds to every step around the contact passes (laws/mdr.h), in (M36)'s order:
 *
 *   mdr_begin    (after the drift, before the rebuild test) each particle's volumes, free-surface fraction and
 *                apparent radius from the sums its contacts left in the last step (M31, M34); the sums restart. The
 *                radius is written to RADIUS, which every contact reads, and its growth since the last build uses up
 *                skin as a displacement does: the rebuild flag is raised when |x - x_build| + (r - r_build) passes
 *                half the skin. Not at dem_start (there are no sums before the first contact pass).
 *   mdr_surface  (a force stage, before the contacts) each particle's mean surface displacement increment (M33) from
 *                its contacts that touched in the last step and still overlap, in the canonical order
 *                (contacts.h: the row, then the walls), with the pair's share of (M3) computed as the force will;
 *                and the penalty (M40) of each pair it owns (the pair's lower stable id: one writer per row) that
 *                overlaps now, into the pair's row: for every third sphere k of its row that overlaps both, when the
 *                pair's centres are the farthest apart of the three, 1/(1 + exp(-50 (alpha/pi - 1/2))) with alpha
 *                the angle at k. A tie of distances goes to the pair whose central sphere has the higher stable id, so
 *                that each triplet weighs exactly one pair (LAMMPS gives it to the pair its loop meets first).
 *                Overlap here is the contacts' own, delta > 0 (LAMMPS counts delta = 0 too).
 *
 * A particle's row (MDR_PART, dem_layout.h MDR_P_*) is written by these two and by contact_forces (the sums), one
 * writer per row; contact_pairs and the walls' sums read it.
 */
#ifndef DEM_MDR_PARTICLE_H
#define DEM_MDR_PARTICLE_H
#include "dem_kernels.h"
#include "contacts.h"
#include "contact_geometry.h"
#include "laws/mdr.h"

DEM_ITEM(mdr_begin)
{
    DEM_GLOBAL real *row = mdr_part + MDR_P_STRIDE * i;
    mdr_particle p = mdr_particle_load(row);
    mdr_material m = mdr_material_from(pairmat + PM_STRIDE * (mat[i] * nmat + mat[i]) + PM_MDR);
    if (mdr_particle_begin(&p, &m)) /* the radius held at its cap: the host says where (step_loop.c) */
        DEM_ATOMIC_MIN(&flags[FLAG_MDR_CAPPED], i);
    mdr_particle_store(row, &p);
    radius[i] = p.r;
    real grown = p.r - r_build[i];
    if (grown > (real)0) {
        vec3 d = v3_sub(v3_load(x, i), v3_load(x_build, i));
        real reach = dem_sqrt(v3_dot(d, d)) + grown;
        if (!(reach * reach <= half_skin2))
            DEM_ATOMIC_MAX(&flags[FLAG_REBUILD], 1);
    }
}

/* (M40) the penalty of pair pn of particles a (the lower stable id, owner of the pair) and b, over a's row: the sum over
 * the third spheres k that overlap both when the pair's centres are the farthest apart of the three (ties: see
 * above); 0 when a and b do not overlap. Written to the pair's row. */
DEM_INLINE void mdr_pair_penalty(int a, int b, int pn, int cnt, int row0, vec3 xa, real ra,
                                 DEM_CONST_GLOBAL real *x, DEM_CONST_GLOBAL real *radius, DEM_CONST_GLOBAL int *sid,
                                 DEM_CONST_GLOBAL int *nbr_list, DEM_GLOBAL real *law_st)
{
    vec3 xb = v3_load(x, b);
    real rb = radius[b], p = (real)0;
    /* overlap as pair_geometry tests it (contact_geometry.h): |x_a - x_b|^2 < (r_a + r_b)^2 */
    vec3 dab = v3_sub(xa, xb);
    real sab = ra + rb, qab = v3_dot(dab, dab);
    if (qab < sab * sab) {
        real lab = dem_sqrt(qab);
        for (int c = 0; c < cnt; c++) {
            int k = nbr_list[row0 + c];
            if (k == b)
                continue;
            vec3 xk = v3_load(x, k), dak = v3_sub(xa, xk), dbk = v3_sub(xb, xk);
            real rk = radius[k], sak = ra + rk, sbk = rb + rk, qak = v3_dot(dak, dak), qbk = v3_dot(dbk, dbk);
            if (!(qak < sak * sak) || !(qbk < sbk * sbk))
                continue;
            real lak = dem_sqrt(qak), lbk = dem_sqrt(qbk);
            /* (a, b) against (a, k), whose central sphere is b, and (b, k), whose central sphere is a */
            int sk = sid[k];
            if (!(lab > lak || (lab == lak && sk > sid[b])) || !(lab > lbk || (lab == lbk && sk > sid[a])))
                continue;
            p += mdr_penalty(v3_dot(dak, dbk) / (lak * lbk)); /* cos of the angle at k */
        }
    }
    law_st[MDR_PAIR_STRIDE * pn + MDR_PEN] = p;
}

DEM_ITEM(mdr_surface)
{
    DEM_GLOBAL real *row = mdr_part + MDR_P_STRIDE * i;
    mdr_particle p = mdr_particle_load(row);
    p.ddelta_bar = (real)0;
    vec3 xi = v3_load(x, i);
    real ri = radius[i];
    int cnt = nbr_count[i], lower = row_lower(nbr_lower[i]), row0 = nbr_start[i], h = 0;
    int nw = (fx & DEM_EFFECT_WALLS) ? nwalls : 0;
    for (int c = 0; c < contact_count(cnt, nw); c++) {
        contact_ref r = contact_at(i, c, cnt, lower, row0, nwalls, nbr_list);
        if (r.kind != CONTACT_WALL) {
            int j = r.partner, hk = h;
            h += j > i;
            int pn = row_pair(i, j, c, hk, own_start[i], in_start[i], in_pair);
            if (r.kind == CONTACT_OWNED) /* this step's penalty (a new contact's too) */
                mdr_pair_penalty(i, j, pn, cnt, row0, xi, ri, x, radius, sid, nbr_list, law_st);
            if (!touch[pn])
                continue;
            pair_geom g = pair_geometry(xi, ri, v3_load(x, j), radius[j]);
            if (!g.active)
                continue;
            /* side 0 is the sphere of higher stable id: i's partner in an owned pair, i in a mirrored one */
            int k = r.kind == CONTACT_OWNED ? 1 : 0;
            real r0 = k ? radius[j] : ri, r1 = k ? ri : radius[j];
            DEM_CONST_GLOBAL real *pr = law_st + MDR_PAIR_STRIDE * pn;
            real share = mdr_pair_side_share(k, g.delta, pr, r0, r1);
            mdr_side s = mdr_side_load(pr + MDR_S0 + MDR_SIDE * k);
            mdr_surface_motion(&p, &s, share);
        } else {
            if (!((wall_mask[i] >> r.partner) & 1u))
                continue;
            wall_geom g = wall_met(fx, wall_int, wall_real, ride, i, r.partner, xi, ri);
            if (!g.active)
                continue;
            mdr_side s = mdr_side_load(wall_law + MDR_WALL_STRIDE * r.slot + MDR_S0);
            mdr_surface_motion(&p, &s, g.delta);
        }
    }
    row[13] = p.ddelta_bar;
}
#endif /* DEM_MDR_PARTICLE_H */
