/* contact_forces.h - particle-particle contact forces (one work item = one pair) and their per-particle accumulation
 * (one work item = one particle).
 *
 * Two passes, no atomics. Pass 1 evaluates each listed pair once, for its particle a of lower stable id (sid:
 * neighbor.h), in canonical orientation (n from b to a), and leaves the result in the pair's record. Pass 2 has every
 * particle add the records of the pairs it owns, then subtract those owned by particles of lower stable id (the exact
 * negation of what they computed), then add its walls. The canonical order of every particle's sum is therefore:
 * partners of higher stable id ascending, then partners of lower stable id ascending, then walls by index (below,
 * "j > i" and "lower id" say stable ids); f_ji = -f_ij bit for bit. Where the particles are stored does not enter.
 * A listed pair that does not touch adds nothing at all (not even +0), which keeps results independent of the skin.
 * touch[p] says whether pair p touches (one byte per pair, like its history); the 24-byte history is read only when
 * it touched in the previous step and is zero otherwise, so a step reads one byte, not one history, per listed pair
 * that does not touch.
 *
 * Walls (wall_forces.h) follow the particle contacts, in wall index order.
 *
 * Effects: without friction no history, torque, n x f_t or lever arm is read or written (the torque array is left
 * as it is: zero); walls are visited only with DEM_EFFECT_WALLS. The force is the run's law's (laws/laws.h): the
 * context it gets holds both particles' stress traces (read by MC-stress, laws/mc_stress.h) and both particles'
 * induced displacements of this contact's slots (MC-strain, laws/mc_strain.h, which also has the resulting elastic
 * force stored once per pair: mc_strain.h).
 *
 * Torque: the contact point lies a distance (r - d/2) from each centre along the line of centres, so the torque on
 * either particle g is -(r_g - d/2) (n x f_t) with n from b to a (seed 000, Eq. 1 branch vector).
 */
#ifndef DEM_CONTACT_FORCES_H
#define DEM_CONTACT_FORCES_H
#include "dem_kernels.h"
#include "contacts.h"
#include "laws/laws.h"
#include "wall_forces.h"
#include "particle_stress.h"
#include "mc_strain.h"
#include "series.h"
#include "rolling.h"

typedef struct {
    int active;  /* 1 when the spheres overlap */
    real delta;  /* overlap [m] */
    real fel;    /* elastic normal force (MC-strain keeps it for the next evaluation) [N] */
    vec3 force;  /* force on a (the smaller id) [N] */
    vec3 c;      /* n x f_t [N] */
    vec3 hist;   /* new tangential history */
    real st;     /* new law state (a law with memory: laws/law.h) */
    real ela;    /* the contact's elastic energy when asked (a law that returns it: laws/law.h) [J] */
    vec3 roll;   /* rolling torque on a (rolling.h) [N m] */
    vec3 rspring; /* new rolling spring (DEM_EFFECT_ROLLING_SPRING, rolling.h) [N m] */
} pair_contact;

/* Pair (a, b) through the run's law (laws.h: law_force); ctx: what the law reads beyond the two particles. */
DEM_INLINE pair_contact pair_contact_eval(unsigned fx, int a, int b, DEM_CONST_GLOBAL real *x, DEM_CONST_GLOBAL real *v,
                                          DEM_CONST_GLOBAL real *w, DEM_CONST_GLOBAL real *radius,
                                          DEM_CONST_GLOBAL real *invmass, DEM_CONST_GLOBAL int *mat,
                                          DEM_CONST_GLOBAL real *pairmat, int nmat, real dt,
                                          DEM_CONST_GLOBAL real *hist, DEM_GLOBAL real *law_st, int hp,
                                          int touching, law_ctx ctx, DEM_CONST_GLOBAL real *roll_inertia,
                                          DEM_CONST_GLOBAL real *rspring, real *sums, int energy)
{
    pair_contact pc;
    real ra = radius[a], rb = radius[b];
    pair_geom g = mc_pair_geometry(fx, v3_load(x, a), ra, v3_load(x, b), rb, pairmat);
    /* a bond whose dent is shallower than its stretch, or a JKR contact before its release, holds across a gap
     * (thornton_ning.h): a pair that touched with state > 0 goes to the law, which ends it unless it still pulls */
    g = pair_geometry_held(fx, g, v3_load(x, a), ra, v3_load(x, b), rb, touching, law_st + hp * DEM_LAW_PAIR_W(fx),
                           pairmat, mat, nmat, a, b);
    pc.active = g.active;
    pc.delta = (real)0;
    pc.fel = (real)0;
    pc.force = v3_zero();
    pc.c = v3_zero();
    pc.hist = v3_zero();
    pc.st = (real)0;
    pc.ela = (real)0;
    pc.roll = v3_zero();
    pc.rspring = v3_zero();
    if (!g.active)
        return pc;
    vec3 n = g.n;
    real delta = g.delta;
    law_in c;
    c.site = LAW_AT_PAIR;
    c.a = a, c.b = b, c.ra = ra, c.rb = rb;
    c.n = n, c.delta = delta, c.rstar = g.rstar, c.dt = dt;
    c.pm = c.pmi = pairmat + PM_STRIDE * (mat[a] * nmat + mat[b]);
    c.mstar = law_effective_mass(invmass[a], invmass[b]);
    real arm_a = ra - (real)0.5 * delta, arm_b = rb - (real)0.5 * delta;
    /* contact-point velocities: v + w x l with l_a = -arm_a n, l_b = +arm_b n (no rotation without friction) */
    vec3 vca = v3_load(v, a), vcb = v3_load(v, b), h = v3_zero();
    if (fx & DEM_EFFECT_FRICTION) {
        vca = v3_add(vca, v3_cross(v3_load(w, a), v3_scale(n, -arm_a)));
        vcb = v3_add(vcb, v3_cross(v3_load(w, b), v3_scale(n, arm_b)));
        /* the stored history is read only for a pair that touched in the previous step (otherwise it is zero) */
        if (touching)
            h = v3_load(hist, hp);
    }
    c.vrel = v3_sub(vca, vcb);
    c.hist = h;
    /* the law's state, like the history, only for a pair that touched in the previous step; a law whose state is a
     * row (MDR) reads and writes the pair's row and leaves its sides' sums (laws/law.h) */
    c.st = ((fx & DEM_LAW_STATE_BITS) && touching) ? law_st[hp * DEM_LAW_PAIR_W(fx)] : (real)0;
    c.row_in = ((fx & DEM_EFFECT_MDR) && touching) ? law_st + hp * DEM_LAW_PAIR_W(fx) : 0;
    c.row_out = (fx & DEM_EFFECT_MDR) ? law_st + hp * DEM_LAW_PAIR_W(fx) : 0;
    c.sums = sums;
    c.energy = energy;
    law_result r = law_force(fx, c, ctx);
    if (!r.active) {
        pc.active = 0;
        return pc;
    }
    pc.delta = delta;
    pc.fel = r.fel;
    pc.st = r.st;
    pc.ela = r.ela;
    pc.force = r.force;
    if (fx & DEM_EFFECT_FRICTION) {
        pc.c = v3_cross(n, r.ft);
        pc.hist = r.hist;
    }
    if ((fx & DEM_EFFECT_ROLLING) && !(fx & DEM_EFFECT_ROLLING_SPRING)) /* against the relative spin, model A */
        pc.roll = rolling_torque(n, v3_dot(r.force, n), v3_sub(v3_load(w, a), v3_load(w, b)), g.rstar, c.pm);
    if (fx & DEM_EFFECT_ROLLING_SPRING) /* model C: the pair's spring, stored only for a pair that touched */
        pc.rspring = rolling_spring_torque(n, delta, v3_dot(r.force, n), v3_sub(v3_load(w, a), v3_load(w, b)),
                                           touching ? v3_load(rspring, hp) : v3_zero(), g.rstar,
                                           roll_inertia[a] + roll_inertia[b], dt, c.pm, &pc.roll);
    return pc;
}

/* Pass 1, contact_pairs: one work item per listed pair p (the flat list of neighbor.h's pair_index: owned pairs in
 * the lower ids' row order), evaluated once by its lower-id particle i in canonical orientation. It keeps the pair's
 * history (hist[3 p]) and touching flag (touch[p]) and leaves force on i, n x f_t and the overlap in record p. Each
 * flag byte and record has exactly one writer. A work item per pair, not per particle, gives every item the same work: a compiler
 * for SIMD lanes (PoCL) can run neighbouring pairs side by side. */
DEM_ITEM(contact_pairs)
{
    int ph = pair_host[i], host_lower = ph >= 0, slot = -1; /* neighbor.h's pair_index */
    int h = host_lower ? ph : ~ph, g = pair_guest[i]; /* the pair's host (stored first) and its partner */
    int a = host_lower ? h : g, j = host_lower ? g : h; /* evaluated for the lower stable id, a */
    int touching = touch[i], m = -1;
    real da = (real)0, db = (real)0;
    if (fx & DEM_EFFECT_MC_STRAIN) {
        slot = pair_slot[i];
        m = pair_mirror[i];
        if (m < 0) /* cannot happen (rows are symmetric; pair_index reports it): never write out of bounds */
            return;
        da = mc_disp[host_lower ? slot : m]; /* D at a's slot of the pair, then at j's */
        db = mc_disp[host_lower ? m : slot];
    }
    law_ctx ctx;
    ctx.trace = trace, ctx.invvol = invvol, ctx.disp_a = da, ctx.disp_b = db, ctx.mdr_part = mdr_part;
    real sums[2 * MDR_NSUM]; /* MDR: each side's sums for its particle (laws/mdr.h) */
    pair_contact pc = pair_contact_eval(fx, a, j, x, v, w, radius, invmass, mat, pairmat, nmat, dt, hist, law_st, i,
                                        touching, ctx, roll_inertia, rspring, sums,
                                        (fx & DEM_EFFECT_MDR) && sample);
    /* per pair (both particles' mc_strain_disp read it). A pair that neither touched nor touches holds 0 already
     * (mc_strain_update zeroes what it set for a pair that does not touch now) */
    if ((fx & DEM_EFFECT_MC_STRAIN) && (pc.active || touching))
        mc_fn[i] = pc.fel;
    if (!pc.active) {
        if (touching) { /* the contact ended: so does its history */
            if (fx & DEM_EFFECT_FRICTION)
                v3_store(hist, i, v3_zero());
            for (int k = 0; (fx & DEM_LAW_STATE_BITS) && k < DEM_LAW_PAIR_W(fx); k++)
                law_st[i * DEM_LAW_PAIR_W(fx) + k] = (real)0;
            if (fx & DEM_EFFECT_ROLLING_SPRING)
                v3_store(rspring, i, v3_zero());
            touch[i] = 0;
        }
        return;
    }
    if (fx & DEM_EFFECT_FRICTION)
        v3_store(hist, i, pc.hist);
    if ((fx & DEM_LAW_STATE_BITS) && !(fx & DEM_EFFECT_MDR)) /* (MDR's law wrote its row) */
        law_st[i] = pc.st;
    for (int k = 0; (fx & DEM_EFFECT_MDR) && k < 2 * MDR_NSUM; k++) /* read by both particles' contact_forces */
        pair_mdr_sum[2 * MDR_NSUM * i + k] = sums[k];
    if (!touching)
        touch[i] = 1;
    DEM_GLOBAL real *pr = pair + i * PR_STRIDE;
    pr[PR_FX] = pc.force.x;
    pr[PR_FY] = pc.force.y;
    pr[PR_FZ] = pc.force.z;
    if (fx & DEM_EFFECT_FRICTION) {
        pr[PR_CX] = pc.c.x;
        pr[PR_CY] = pc.c.y;
        pr[PR_CZ] = pc.c.z;
    }
    pr[PR_DELTA] = pc.delta; /* the torque's lever arm, and a sampled step's elastic energy (series.h) */
    if (fx & DEM_EFFECT_ROLLING) /* read with the record, only for a touching pair */
        v3_store(pair_roll, i, pc.roll);
    if (fx & DEM_EFFECT_ROLLING_SPRING)
        v3_store(rspring, i, pc.rspring);
    /* read by contact_forces for this step's row (a bond's or a JKR contact's also across a gap: Thornton-Ning keeps a
     * contact there only while it holds; MC-strain's reach does not count) */
    if ((fx & DEM_KEEP_PAIR_ENERGY) && sample && (pc.delta > (real)0 || (fx & DEM_EFFECT_THORNTON_NING)))
        pair_ela[i] = (fx & DEM_EFFECT_MDR) ? pc.ela : series_pair_energy_kept(fx, pairmat + PM_STRIDE * (mat[a] * nmat + mat[j]), radius[a], radius[j],
                                              pc.delta, pc.fel, pc.st); /* series_pair_energy's bits */
}

/* How contact_forces and contact_rows walk particle i's row (nrow; lower: its partners of lower stable id, the front;
 * lv: nbr_lower, below 0 when the row's storage split is not its id split, the particles stored anew since the
 * rebuild): the owned part (k = lower on, h from row_walk_start: the slots of the front whose partner is stored after
 * i), then the front (k = 0 on, h = 0). row_walk_pair gives slot k's pair number (contacts.h row_pair, h counted on),
 * reading the row only where the two splits differ. */
DEM_INLINE int row_walk_start(int lv, int lower, DEM_CONST_GLOBAL int *nrow, int i)
{
    int h = 0;
    for (int k = 0; lv < 0 && k < lower; k++) /* the records of the front come after the back's in the sum */
        h += nrow[k] > i;
    return h;
}
DEM_INLINE int row_walk_pair(int lv, int k, int lower, int i, DEM_CONST_GLOBAL int *nrow, int own, int in,
                             DEM_CONST_GLOBAL int *in_pair, int *h)
{
    if (lv >= 0) /* the front stored before i, the rest after it */
        return k >= lower ? own + k - lower : in_pair[in + k];
    int j = nrow[k], p = row_pair(i, j, k, *h, own, in, in_pair);
    *h += j > i;
    return p;
}

/* Pass 2, contact_forces: particle i adds its touching pairs in the canonical order - the pairs it owns (partners
 * of higher stable id, ascending: the back of its row), then those owned by partners of lower stable id (ascending:
 * the front of its row, nbr_lower[i] of them, subtracted), then its walls. The records are found by storage order
 * (row_walk_pair: a pair i hosts, its partner stored after i, is own + h, h counting the hosted slots before it; one
 * its partner hosts is in_pair[in + g], g counting the others) and added in the stable ids' order. */
DEM_ITEM(contact_forces)
{
    vec3 fi = v3_zero(), ti = v3_zero();
    real ri = radius[i], ela = (real)0, con = (real)0, wcon = (real)0;
    real macc[MDR_NSUM]; /* MDR: the particle's sums from its contacts' sides, in the canonical order (laws/mdr.h) */
    for (int k = 0; (fx & DEM_EFFECT_MDR) && k < MDR_NSUM; k++)
        macc[k] = (real)0;
    int cnt = nbr_count[i], lv = nbr_lower[i], lower = row_lower(lv), own = own_start[i], in = in_start[i];
    DEM_CONST_GLOBAL int *nrow = nbr_list + nbr_start[i]; /* the row (row: the series' row) */
    int h = row_walk_start(lv, lower, nrow, i);
    for (int k = lower; k < cnt; k++) { /* owned: partners of higher stable id */
        int p = row_walk_pair(lv, k, lower, i, nrow, own, in, in_pair, &h);
        if (!touch[p])
            continue;
        DEM_CONST_GLOBAL real *pr = pair + p * PR_STRIDE;
        fi = v3_add(fi, v3(pr[PR_FX], pr[PR_FY], pr[PR_FZ]));
        if (fx & DEM_EFFECT_FRICTION)
            ti = v3_sub(ti, v3_scale(v3(pr[PR_CX], pr[PR_CY], pr[PR_CZ]), ri - (real)0.5 * pr[PR_DELTA]));
        for (int q = 0; (fx & DEM_EFFECT_MDR) && q < MDR_NSUM; q++) /* i is the pair's a: side 1 */
            macc[q] += pair_mdr_sum[2 * MDR_NSUM * p + MDR_NSUM + q];
        if (fx & DEM_EFFECT_ROLLING) /* i is the pair's a: its rolling torque */
            ti = v3_add(ti, v3_load(pair_roll, p));
        /* a sampled step: the pair's elastic energy, by its lower id (a Thornton-Ning contact also across a gap, where
         * it is kept only while a bond or JKR adhesion holds it: contact_pairs' test, series.h) */
        if (sample && (pr[PR_DELTA] > (real)0 || (fx & DEM_EFFECT_THORNTON_NING))) {
            if (fx & DEM_KEEP_PAIR_ENERGY) {
                ela += pair_ela[p];
            } else {
                int j = nrow[k];
                ela += series_pair_energy(fx, pairmat + PM_STRIDE * (mat[i] * nmat + mat[j]), ri, radius[j],
                                          pr[PR_DELTA]);
            }
            con += (real)1;
        }
    }
    h = 0;
    for (int k = 0; k < lower; k++) { /* mirrored: partners of lower stable id */
        int p = row_walk_pair(lv, k, lower, i, nrow, own, in, in_pair, &h);
        if (!touch[p])
            continue;
        DEM_CONST_GLOBAL real *pr = pair + p * PR_STRIDE;
        fi = v3_sub(fi, v3(pr[PR_FX], pr[PR_FY], pr[PR_FZ]));
        if (fx & DEM_EFFECT_FRICTION)
            ti = v3_sub(ti, v3_scale(v3(pr[PR_CX], pr[PR_CY], pr[PR_CZ]), ri - (real)0.5 * pr[PR_DELTA]));
        for (int q = 0; (fx & DEM_EFFECT_MDR) && q < MDR_NSUM; q++) /* i is the pair's b: side 0 */
            macc[q] += pair_mdr_sum[2 * MDR_NSUM * p + q];
        if (fx & DEM_EFFECT_ROLLING) /* i is the pair's b: minus a's rolling torque */
            ti = v3_sub(ti, v3_load(pair_roll, p));
    }
    if ((fx & DEM_EFFECT_WALLS) && nwalls > 0)
        wall_contacts_add(fx, i, n, nwalls, wall_int, wall_real, v3_load(x, i), v3_load(v, i), v3_load(w, i), ri,
                          invmass[i], mat[i], pairmat, nmat, wall_hist, wall_law, dt, wall_pf, wall_mask, trace, invvol,
                          mc_wall_disp, mc_wall_fn, ride, &fi, &ti, sample ? &ela : 0, &wcon,
                          (fx & DEM_EFFECT_ROLLING_SPRING) ? roll_inertia[i] : (real)0, wall_rspring, mdr_part,
                          macc);
    v3_store(force, i, fi);
    for (int k = 0; (fx & DEM_EFFECT_MDR) && k < MDR_NSUM; k++) /* the next step's mdr_begin reads them */
        mdr_part[MDR_P_STRIDE * i + MDR_P_SUMS + k] = macc[k];
    if (fx & DEM_EFFECT_FRICTION)
        v3_store(torque, i, ti);
    if (sample) { /* the particle's contact terms of the sampled step (series.h) */
        DEM_GLOBAL real *slot = series_slot(ring, row, n, i);
        slot[SE_ELA] = ela;
        slot[SE_CON] = con;
        slot[SE_WCON] = wcon;
    }
}
#endif /* DEM_CONTACT_FORCES_H */
