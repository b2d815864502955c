/* wall_forces.h - particle-wall contacts (planes of any orientation, flat or a concave punch's face, the inside of a
 * cylinder, a finite die: contact_geometry.h) and the canonical reduction of the force each wall receives.
 *
 * A wall is a rigid body of infinite mass and radius: r* = r_i, m* = m_i (also on a die's bore and in a punch's cup,
 * which are curved: taken locally flat, as LIGGGHTS takes its walls; docs/tableting.md), the contact point lies on the wall
 * surface (lever arm r_i - d). The same law as between particles (laws/laws.h: law_force) is used with the wall's own
 * material. Walls are visited in index order after all particle contacts (contact_forces.h), which fixes
 * the summation order of every particle's force. The force each wall receives is summed exactly (exact_sum.h) over
 * blocks of particles, the blocks merged by a tree of work items (wall_reduce_*) and rounded once: the correctly
 * rounded sum of the particles' terms, whatever their order, the blocks' cut or the device (docs/design.md "Sums that
 * do not depend on the decomposition"). The terms come after contact_forces from the forces it kept
 * (DEM_KEEP_WALL_FORCES), or before it from evaluating the same contacts (wall_reduce_block).
 */
#ifndef DEM_WALL_FORCES_H
#define DEM_WALL_FORCES_H
#include "dem_kernels.h"
#include "laws/laws.h"
#include "contact_geometry.h"
#include "particle_stress.h"
#include "mc_strain.h"
#include "rolling.h"
#include "exact_sum.h"

/* a real into an exact sum, and the sum rounded once to a real */
#if DEM_REAL_SIZE == 8
#define exact_add_real exact_add_double
#define exact_to_real exact_to_double
#else
#define exact_add_real exact_add_float
#define exact_to_real exact_to_float
#endif

/* Particle i against wall k: the law's result when they touch (active). old_touch: whether they touched in the
 * previous step (wall_mask), i.e. whether a tangential history is stored. A pure function of the state before the
 * step's contacts are committed, so that wall_reduce_block, run before contact_forces, computes exactly the forces
 * contact_forces then applies (the reduction keeps no per-particle copy of them). */
typedef struct {
    int active;
    vec3 n;     /* unit normal from the wall to the particle centre */
    real delta; /* overlap [m] */
    real arm;   /* lever arm of the contact point, r_i - delta [m] */
    law_result r;
} wall_contact;

/* The law's context of particle i's contact in wall slot `slot` (i * nwalls + k): the traces (MC-stress) and the
 * displacement induced at the slot (MC-strain; the wall has none) */
DEM_INLINE law_ctx wall_law_ctx(unsigned fx, int i, int slot, DEM_CONST_GLOBAL real *trace,
                                DEM_CONST_GLOBAL real *invvol, DEM_CONST_GLOBAL real *mc_wall_disp,
                                DEM_CONST_GLOBAL real *mdr_part)
{
    law_ctx ctx;
    ctx.trace = trace, ctx.invvol = invvol, ctx.mdr_part = mdr_part;
    ctx.disp_a = (fx & DEM_EFFECT_MC_STRAIN) ? mc_wall_disp[slot] : (real)0;
    ctx.disp_b = (real)0;
    return ctx;
}

DEM_INLINE wall_contact wall_contact_eval(unsigned fx, int i, int k, int nwalls, DEM_CONST_GLOBAL int *wall_int,
                                          DEM_CONST_GLOBAL real *wall_real, vec3 xi, vec3 vi, vec3 wi, real ri,
                                          real invm, int mi, DEM_CONST_GLOBAL real *pairmat, int nmat,
                                          DEM_CONST_GLOBAL real *wall_hist, DEM_CONST_GLOBAL real *wall_law, real dt,
                                          int old_touch, law_ctx ctx, DEM_CONST_GLOBAL unsigned *ride,
                                          DEM_GLOBAL real *law_out, real *sums, int energy)
{
    wall_contact c;
    DEM_CONST_GLOBAL real *wr = wall_real + k * W_STRIDE;
    int slot = i * nwalls + k;
    DEM_CONST_GLOBAL real *pm = pairmat + PM_STRIDE * (mi * nmat + wall_int[k * WI_STRIDE + WI_MATERIAL]);
    /* a JKR contact (DEM_EFFECT_ADHESION) that touched in the previous step and has not let go (state > 0) holds across
     * a gap until the law releases it, as a pair's does (contact_geometry.h: wall_met_held) */
    wall_geom g = wall_met_held(fx, wall_met(fx, wall_int, wall_real, ride, i, k, xi, ri), wall_int, wall_real, ride, i,
                                k, xi, ri, old_touch, wall_law + slot * DEM_LAW_WALL_W(fx), pm);
    c.active = g.active;
    c.n = g.n;
    c.delta = g.delta;
    c.arm = ri - g.delta;
    if (!g.active)
        return c;
    law_in lc;
    lc.site = LAW_AT_WALL;
    lc.a = lc.b = i, lc.ra = lc.rb = ri;
    lc.n = g.n, lc.delta = g.delta, lc.rstar = ri, lc.dt = dt;
    lc.mstar = law_effective_mass(invm, (real)0);
    vec3 vc = vi, h = v3_zero();
    if (fx & DEM_EFFECT_FRICTION) {
        vc = v3_add(vi, v3_cross(wi, v3_scale(g.n, -c.arm)));
        if (old_touch)
            h = v3_load(wall_hist, slot);
    }
    lc.vrel = v3_sub(vc, v3(wr[W_VX], wr[W_VY], wr[W_VZ]));
    lc.hist = h;
    /* the law's state (laws/law.h): a real, or a row read from wall_law and written to law_out (0: not kept) */
    lc.st = ((fx & DEM_LAW_STATE_BITS) && old_touch) ? wall_law[slot * DEM_LAW_WALL_W(fx)] : (real)0;
    lc.row_in = ((fx & DEM_EFFECT_MDR) && old_touch) ? wall_law + slot * DEM_LAW_WALL_W(fx) : 0;
    lc.row_out = ((fx & DEM_EFFECT_MDR) && law_out) ? law_out + slot * DEM_LAW_WALL_W(fx) : 0;
    lc.sums = sums;
    lc.energy = energy;
    lc.pm = pm;
    lc.pmi = pairmat + PM_STRIDE * (mi * nmat + mi);
    c.r = law_force(fx, lc, ctx);
    if (!c.r.active) /* a JKR contact across a gap that let go (laws/thornton_ning.h); every law is active at an overlap */
        c.active = 0;
    return c;
}

/* One particle against every wall, added to its force and torque after all its particle contacts (called by
 * contact_forces_item, so the particle's data are read and its sums written once per step). Keeps each wall's
 * tangential history and the law's state; wall_mask[i] gets bit k set when particle i touches wall k (the history of wall k is only
 * touched when bit k is set now or was set in the previous step). With DEM_KEEP_WALL_FORCES (a run that reads the
 * contact network) the force from each touching wall is also stored, at wall_pf[k * n + i]. In a sampled step (ela
 * not null) the Hertz energy and count of the touching walls are added to *ela and *wcon (series.h). */
DEM_INLINE void wall_contacts_add(unsigned fx, int i, int n, int nwalls, DEM_CONST_GLOBAL int *wall_int,
                                  DEM_CONST_GLOBAL real *wall_real, vec3 xi, vec3 vi, vec3 wi, real ri, real invm,
                                  int mi, DEM_CONST_GLOBAL real *pairmat, int nmat, DEM_GLOBAL real *wall_hist,
                                  DEM_GLOBAL real *wall_law, real dt, DEM_GLOBAL real *wall_pf, DEM_GLOBAL unsigned *wall_mask,
                                  DEM_CONST_GLOBAL real *trace, DEM_CONST_GLOBAL real *invvol,
                                  DEM_CONST_GLOBAL real *mc_wall_disp, DEM_GLOBAL real *mc_wall_fn,
                                  DEM_CONST_GLOBAL unsigned *ride, vec3 *fi, vec3 *ti, real *ela, real *wcon,
                                  real iroll, DEM_GLOBAL real *wall_rspring, DEM_CONST_GLOBAL real *mdr_part,
                                  real *macc)
{
    unsigned old_mask = wall_mask[i], mask = 0;
    for (int k = 0; k < nwalls; k++) {
        int slot = i * nwalls + k, old_touch = (old_mask >> k) & 1u;
        real sums[MDR_NSUM]; /* MDR: the side's sums, added to the particle's (macc) in wall order */
        wall_contact c = wall_contact_eval(fx, i, k, nwalls, wall_int, wall_real, xi, vi, wi, ri, invm, mi, pairmat,
                                           nmat, wall_hist, wall_law, dt, old_touch,
                                           wall_law_ctx(fx, i, slot, trace, invvol, mc_wall_disp, mdr_part), ride,
                                           wall_law, sums, (fx & DEM_EFFECT_MDR) && ela);
        if (c.active) {
            for (int q = 0; (fx & DEM_EFFECT_MDR) && q < MDR_NSUM; q++)
                macc[q] += sums[q];
            if (fx & DEM_EFFECT_MC_STRAIN)
                mc_wall_fn[slot] = c.r.fel;
            if (fx & DEM_KEEP_WALL_FORCES)
                v3_store(wall_pf, k * n + i, c.r.force);
            if (ela && (c.delta > (real)0 || (fx & DEM_EFFECT_ADHESION))) { /* a sampled step (series.h): the law's
                                                                             energy, from the force at hand (a JKR
                                                                             contact's also across a gap) */
                *ela += (fx & DEM_EFFECT_MDR)
                            ? c.r.ela
                            : law_energy_kept(fx, pairmat + PM_STRIDE * (mi * nmat + wall_int[k * WI_STRIDE + WI_MATERIAL]),
                                              ri, c.delta, c.r.fel, c.r.st);
                *wcon += (real)1;
            }
            *fi = v3_add(*fi, c.r.force);
            if ((fx & DEM_LAW_STATE_BITS) && !(fx & DEM_EFFECT_MDR)) /* (MDR's law wrote its row) */
                wall_law[slot] = c.r.st;
            if (fx & DEM_EFFECT_FRICTION) {
                v3_store(wall_hist, slot, c.r.hist);
                *ti = v3_sub(*ti, v3_scale(v3_cross(c.n, c.r.ft), c.arm));
            }
            DEM_CONST_GLOBAL real *pmw = pairmat + PM_STRIDE * (mi * nmat + wall_int[k * WI_STRIDE + WI_MATERIAL]);
            if ((fx & DEM_EFFECT_ROLLING) && !(fx & DEM_EFFECT_ROLLING_SPRING)) /* against the sphere's spin (the
                                                                                  wall's: none), r* = r_i */
                *ti = v3_add(*ti, rolling_torque(c.n, v3_dot(c.r.force, c.n), wi, ri, pmw));
            if (fx & DEM_EFFECT_ROLLING_SPRING) { /* model C: the slot's spring (the wall's term of 1/I_r: 0) */
                vec3 mr;
                v3_store(wall_rspring, slot,
                         rolling_spring_torque(c.n, c.delta, v3_dot(c.r.force, c.n), wi,
                                               old_touch ? v3_load(wall_rspring, slot) : v3_zero(), ri,
                                               iroll, dt, pmw, &mr));
                *ti = v3_add(*ti, mr);
            }
            mask |= 1u << k;
        } else {
            if ((fx & DEM_EFFECT_FRICTION) && old_touch)
                v3_store(wall_hist, slot, v3_zero());
            for (int q = 0; (fx & DEM_LAW_STATE_BITS) && old_touch && q < DEM_LAW_WALL_W(fx); q++)
                wall_law[slot * DEM_LAW_WALL_W(fx) + q] = (real)0;
            if ((fx & DEM_EFFECT_ROLLING_SPRING) && old_touch)
                v3_store(wall_rspring, slot, v3_zero());
            if (fx & DEM_EFFECT_MC_STRAIN)
                mc_wall_fn[slot] = (real)0;
        }
    }
    wall_mask[i] = mask;
}

/* A block's sums for one wall (dem_layout.h WP_*), exact: the force the wall received [N] and the sum of the
 * particles' normal force components [N] */
typedef struct {
    exact_acc s[WP_STRIDE];
} wall_part;

DEM_INLINE void wall_part_clear(wall_part *p)
{
    for (int q = 0; q < WP_STRIDE; q++)
        exact_clear(&p->s[q]);
}

/* A particle's force fj from a wall into the wall's sums (n: the contact normal): the wall receives -fj, and the normal
 * part is fj . n, the one expression of every term, so every path adds the same numbers */
DEM_INLINE void wall_part_take(wall_part *p, vec3 fj, vec3 n)
{
    exact_add_real(&p->s[WP_FX], -fj.x);
    exact_add_real(&p->s[WP_FY], -fj.y);
    exact_add_real(&p->s[WP_FZ], -fj.z);
    exact_add_real(&p->s[WP_FN], v3_dot(fj, n));
}

/* The sums of (wall, block) idx into the partial buffers: WP_STRIDE accumulators of EXACT_WORDS words each */
DEM_INLINE void wall_part_store(DEM_GLOBAL unsigned *p, long idx, const wall_part *w)
{
    for (int q = 0; q < WP_STRIDE; q++)
        exact_store(p + (idx * WP_STRIDE + q) * EXACT_WORDS, &w->s[q]);
}

/* Block b's sums for wall k from the forces contact_forces kept (DEM_KEEP_WALL_FORCES): the wall receives
 * minus the force on each particle that touches it; the normal part is that force along the contact normal
 * (wall_met: the geometry the force law saw, the state being the same). The block is the particles stored at
 * [b*B, (b+1)*B) (B = DEM_REDUCE_BLOCK): the sums are exact, so which particles share a block does not matter. */
DEM_INLINE void wall_block_kept(unsigned fx, int b, int k, int n, DEM_CONST_GLOBAL unsigned *wall_mask,
                                DEM_CONST_GLOBAL real *wall_pf, DEM_CONST_GLOBAL real *x,
                                DEM_CONST_GLOBAL real *radius, DEM_CONST_GLOBAL int *wall_int,
                                DEM_CONST_GLOBAL real *wall_real, DEM_CONST_GLOBAL unsigned *ride,
                                DEM_CONST_GLOBAL unsigned *ghost, wall_part *p)
{
    int end = (b + 1) * DEM_REDUCE_BLOCK < n ? (b + 1) * DEM_REDUCE_BLOCK : n;
    for (int j = b * DEM_REDUCE_BLOCK; j < end; j++)
        if (((wall_mask[j] >> k) & 1u) && !((fx & DEM_HAS_GHOSTS) && ghost[j])) {
            wall_geom g = wall_met(fx, wall_int, wall_real, ride, j, k, v3_load(x, j), radius[j]);
            if (!g.active && (fx & DEM_EFFECT_ADHESION)) /* it touches across a gap: the normal the law saw */
                g = wall_met_gap(fx, wall_int, wall_real, ride, j, k, v3_load(x, j), radius[j], radius[j]);
            wall_part_take(p, v3_load(wall_pf, k * n + j), g.n);
        }
}

/* Exact sums of the force that the particles stored at [b*B, (b+1)*B) exert on wall k (B = DEM_REDUCE_BLOCK), and of
 * their normal parts. With DEM_KEEP_WALL_FORCES: the forces contact_forces kept (this kernel runs after it).
 * Without: each particle's force from the wall evaluated as contact_forces is about to (this kernel runs between
 * contact_pairs and contact_forces, on the same state), so nothing per particle and wall is stored. The same terms
 * either way, and the same bits. A run holding ghosts (DEM_HAS_GHOSTS) leaves them out: its sums are its own
 * particles', which the ranks merge (host/mpi). */
DEM_ITEM(wall_reduce_block)
{
    int b = i % nblocks, k = i / nblocks;
    wall_part p;
    wall_part_clear(&p);
    int end = (b + 1) * DEM_REDUCE_BLOCK < n ? (b + 1) * DEM_REDUCE_BLOCK : n;
    if (fx & DEM_KEEP_WALL_FORCES)
        wall_block_kept(fx, b, k, n, wall_mask, wall_pf, x, radius, wall_int, wall_real, ride, ghost, &p);
    else
        for (int j = b * DEM_REDUCE_BLOCK; j < end; j++) {
            if ((fx & DEM_HAS_GHOSTS) && ghost[j]) /* another rank's particle: its owner counts it */
                continue;
            wall_contact c = wall_contact_eval(fx, j, k, nwalls, wall_int, wall_real, v3_load(x, j), v3_load(v, j),
                                               v3_load(w, j), radius[j], invmass[j], mat[j], pairmat, nmat, wall_hist,
                                               wall_law, dt, (wall_mask[j] >> k) & 1u,
                                               wall_law_ctx(fx, j, j * nwalls + k, trace, invvol, mc_wall_disp, mdr_part),
                                               ride, 0, 0, 0);
            if (c.active)
                wall_part_take(&p, c.r.force, c.n);
        }
    wall_part_store(partial, k * nblocks + b, &p);
}

/* The middle level of the tree (dem_layout.h): group g of wall k merges its blocks g*FAN .. (g+1)*FAN-1, one sum at a
 * time (one accumulator in private memory). */
DEM_ITEM(wall_reduce_mid)
{
    int g = i % nmid, k = i / nmid;
    int end = (g + 1) * DEM_REDUCE_FAN < nblocks ? (g + 1) * DEM_REDUCE_FAN : nblocks;
    for (int q = 0; q < WP_STRIDE; q++) {
        exact_acc a;
        exact_sum_stored(&a, partial + ((long)(k * nblocks + g * DEM_REDUCE_FAN) * WP_STRIDE + q) * EXACT_WORDS,
                         end - g * DEM_REDUCE_FAN, WP_STRIDE * EXACT_WORDS);
        exact_store(mid + ((long)(k * nmid + g) * WP_STRIDE + q) * EXACT_WORDS, &a);
    }
}

/* Wall k's sums over its groups, each rounded once: its force and its normal force. */
DEM_ITEM(wall_reduce_final)
{
    int k = i;
    for (int q = 0; q < WP_STRIDE; q++) {
        exact_acc a;
        exact_sum_stored(&a, mid + ((long)k * nmid * WP_STRIDE + q) * EXACT_WORDS, nmid, WP_STRIDE * EXACT_WORDS);
        if (q == WP_FN)
            wall_nforce[k] = exact_to_real(&a);
        else
            wall_force[3 * k + q] = exact_to_real(&a);
    }
}
#endif /* DEM_WALL_FORCES_H */
