/* contact_rows.h - particle-particle contact forces in one pass (one work item = one particle): the two passes of
 * contact_forces.h (contact_pairs, then contact_forces) joined, for the steps on which nothing reads the pair records
 * (dem_config.one_pass; host/core/step_loop.c says which steps; docs/design.md "One pass over the rows").
 *
 * Particle i walks its row as contact_forces does - partners of higher stable id ascending, then those of lower id
 * ascending, then its walls - and evaluates each pair itself, always in the canonical orientation (for the pair's
 * lower id a, n from b to a: pair_contact_eval), so both ends of a pair compute the same force from the same inputs
 * and f_ji = -f_ij holds bit for bit, as in the two passes. Every term enters i's sums in the same order and with the
 * same operations as contact_forces adds a record, so force and torque have the two passes' bits; each pair's law is
 * evaluated twice (once by each end) instead of once, and no record is written or read.
 *
 * The pair's tangential history and touching flag are read from this step's (hist, touch) by both ends and written
 * by the lower id only, into the other copy (hist_next, touch_next), which the host then makes the current one (the
 * two swap: host/core/step_loop.c). So no end reads what the other wrote this step. Every listed pair's flag and
 * history is written each step (the history as zero where the pair does not touch, as the two passes leave it),
 * because the other copy holds what two steps ago left there, or nothing after a rebuild. The pair records are not
 * written: a record is read only under a set flag, and the last step of every call takes the two passes.
 *
 * Laws and effects: the force laws without a state per pair beyond the history (classical, MC-stress; with
 * friction, walls, rolling resistance of constant torque). MC-strain, Thornton-Ning (and its adhesion), MDR and the
 * rolling spring keep per-pair results that other kernels read, and the host does not set DEM_ONE_PASS for them.
 * A sampled step's energies and contact counts are contact_forces' (such a step takes the two passes).
 */
#ifndef DEM_CONTACT_ROWS_H
#define DEM_CONTACT_ROWS_H
#include "contact_forces.h"

/* pair p of particle i's row (partner j) evaluated for the pair's lower id; owner: i is that lower id (it writes the
 * pair's next flag and history and adds the force; the other end subtracts it) */
DEM_INLINE void contact_row_pair(unsigned fx, int i, int j, int p, int owner, real ri, DEM_CONST_GLOBAL real *x,
                                 DEM_CONST_GLOBAL real *v, DEM_CONST_GLOBAL real *w, DEM_CONST_GLOBAL real *radius,
                                 DEM_CONST_GLOBAL real *invmass, DEM_CONST_GLOBAL int *mat,
                                 DEM_CONST_GLOBAL real *pairmat, int nmat, real dt, DEM_CONST_GLOBAL real *hist,
                                 DEM_GLOBAL real *hist_next, DEM_CONST_GLOBAL dem_byte *touch,
                                 DEM_GLOBAL dem_byte *touch_next, DEM_CONST_GLOBAL real *trace,
                                 DEM_CONST_GLOBAL real *invvol, DEM_GLOBAL real *law_st,
                                 DEM_CONST_GLOBAL real *roll_inertia, DEM_CONST_GLOBAL real *rspring,
                                 DEM_CONST_GLOBAL real *mdr_part, vec3 *fi, vec3 *ti)
{
    int a = owner ? i : j, b = owner ? j : i, touching = touch[p];
    law_ctx ctx;
    ctx.trace = trace, ctx.invvol = invvol, ctx.disp_a = (real)0, ctx.disp_b = (real)0, ctx.mdr_part = mdr_part;
    real sums[2 * MDR_NSUM]; /* (MDR's; not a law of this kernel) */
    pair_contact pc = pair_contact_eval(fx, a, b, x, v, w, radius, invmass, mat, pairmat, nmat, dt, hist, law_st, p,
                                        touching, ctx, roll_inertia, rspring, sums, 0);
    if (owner) {
        touch_next[p] = (dem_byte)(pc.active ? 1 : 0);
        if (fx & DEM_EFFECT_FRICTION) /* zero where it does not touch, as contact_pairs leaves it */
            v3_store(hist_next, p, pc.active ? pc.hist : v3_zero());
    }
    if (!pc.active)
        return;
    /* contact_forces' terms of a record, in its order: the force, the torque of n x f_t at i's lever arm, the
     * rolling torque (a's; minus it on b) */
    *fi = owner ? v3_add(*fi, pc.force) : v3_sub(*fi, pc.force);
    if (fx & DEM_EFFECT_FRICTION)
        *ti = v3_sub(*ti, v3_scale(pc.c, ri - (real)0.5 * pc.delta));
    if (fx & DEM_EFFECT_ROLLING)
        *ti = owner ? v3_add(*ti, pc.roll) : v3_sub(*ti, pc.roll);
}

/* contact_rows: particle i's force and torque (the step's particle contacts and walls), with the rows found as
 * contact_forces finds them */
DEM_ITEM(contact_rows)
{
    if (!(fx & DEM_ONE_PASS)) /* never launched without it; a constant in a kernel, so the body is not compiled */
        return;
    vec3 fi = v3_zero(), ti = v3_zero();
    real ri = radius[i], wcon = (real)0;
    real macc[MDR_NSUM]; /* (MDR's sums; not a law of this kernel) */
    int cnt = nbr_count[i], lv = nbr_lower[i], lower = row_lower(lv), own = own_start[i], in = in_start[i];
    DEM_CONST_GLOBAL int *nrow = nbr_list + nbr_start[i];
    int h = row_walk_start(lv, lower, nrow, i);
    for (int k = lower; k < cnt; k++) { /* owned: partners of higher stable id */
        int p = row_walk_pair(lv, k, lower, i, nrow, own, in, in_pair, &h);
        contact_row_pair(fx, i, nrow[k], p, 1, ri, x, v, w, radius, invmass, mat, pairmat, nmat, dt, hist, hist_next,
                         touch, touch_next, trace, invvol, law_st, roll_inertia, rspring, mdr_part, &fi, &ti);
    }
    h = 0;
    for (int k = 0; k < lower; k++) { /* mirrored: partners of lower stable id */
        int p = row_walk_pair(lv, k, lower, i, nrow, own, in, in_pair, &h);
        contact_row_pair(fx, i, nrow[k], p, 0, ri, x, v, w, radius, invmass, mat, pairmat, nmat, dt, hist, hist_next,
                         touch, touch_next, trace, invvol, law_st, roll_inertia, rspring, mdr_part, &fi, &ti);
    }
    if ((fx & DEM_EFFECT_WALLS) && nwalls > 0)
        wall_contacts_add(fx, i, n, nwalls, wall_int, wall_real, v3_load(x, i), v3_load(v, i), v3_load(w, i), ri,
                          invmass[i], mat[i], pairmat, nmat, wall_hist, wall_law, dt, wall_pf, wall_mask, trace, invvol,
                          mc_wall_disp, mc_wall_fn, ride, &fi, &ti, 0, &wcon, (real)0, wall_rspring, mdr_part, macc);
    v3_store(force, i, fi);
    if (fx & DEM_EFFECT_FRICTION)
        v3_store(torque, i, ti);
}
#endif /* DEM_CONTACT_ROWS_H */
