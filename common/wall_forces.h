/* wall_forces.h - particle-wall contacts (planes of any orientation, the inside of a cylinder) and the canonical
 * reduction of the force each wall receives.
 *
 * A wall is a rigid body of infinite mass and radius: r* = r_i, m* = m_i, the contact point lies on the wall
 * surface (lever arm r_i - d). The same Hertz-Mindlin law as between particles (hertz_mindlin.h) is used with the
 * wall's own material. Walls are visited in index order after all particle contacts (contact_forces.h), which fixes
 * the summation order of every particle's force. The force each wall receives is then summed over particles in
 * fixed blocks (wall_reduce_*), the same way on every device.
 */
#ifndef DEM_WALL_FORCES_H
#define DEM_WALL_FORCES_H
#include "dem_kernels.h"
#include "hertz_mindlin.h"
#include "contact_geometry.h"
#include "particle_stress.h"
#include "mc_strain.h"

/* One particle against every wall, added to its force and torque after all its particle contacts (called by
 * contact_forces_item, so the particle's data are read and its sums written once per step). Keeps each wall's
 * tangential history and stores the force on the particle from each touching wall for the reduction.
 * wall_mask[i] has bit k set when particle i touches wall k: only those entries of wall_pf are written and read,
 * and the history of wall k is only touched when bit k is set now or was set in the previous step. */
DEM_INLINE void wall_contacts_add(unsigned fx, int i, int n, int nwalls, DEM_CONST_GLOBAL int *wall_int,
                                  DEM_CONST_GLOBAL real *wall_real, vec3 xi, vec3 vi, vec3 wi, real ri, real invm,
                                  int mi, DEM_CONST_GLOBAL real *pairmat, int nmat, DEM_GLOBAL real *wall_hist,
                                  real dt, DEM_GLOBAL real *wall_pf, DEM_GLOBAL unsigned *wall_mask,
                                  DEM_CONST_GLOBAL real *trace, DEM_CONST_GLOBAL real *invvol,
                                  DEM_CONST_GLOBAL real *mc_wall_disp, DEM_GLOBAL real *mc_wall_fn,
                                  DEM_CONST_GLOBAL unsigned *ride, vec3 *fi, vec3 *ti)
{
    unsigned old_mask = wall_mask[i], mask = 0;
    for (int k = 0; k < nwalls; k++) {
        DEM_CONST_GLOBAL real *wr = wall_real + k * W_STRIDE;
        int slot = i * nwalls + k;
        wall_geom g = wall_met(fx, wall_int, wall_real, ride, i, k, xi, ri);
        if (g.active) {
            real arm = ri - g.delta;
            real mstar = hm_effective_mass(invm, (real)0);
            vec3 vc = vi, h = v3_zero();
            if (fx & DEM_EFFECT_FRICTION) {
                vc = v3_add(vi, v3_cross(wi, v3_scale(g.n, -arm)));
                if ((old_mask >> k) & 1u)
                    h = v3_load(wall_hist, slot);
            }
            vec3 vrel = v3_sub(vc, v3(wr[W_VX], wr[W_VY], wr[W_VZ]));
            DEM_CONST_GLOBAL real *pm = pairmat + PM_STRIDE * (mi * nmat + wall_int[k * WI_STRIDE + WI_MATERIAL]);
            real extra = (real)0, law_delta = g.delta;
            if (fx & DEM_EFFECT_MC_STRAIN)
                law_delta = mc_strain_overlap(g.delta, mc_wall_disp[slot], (real)0);
            real srd = dem_sqrt(ri * law_delta);
            if (fx & DEM_EFFECT_MC_STRESS) /* (mc_strain is off: law_delta is g.delta) */
                extra = mc_stress_wall(fx, pairmat + PM_STRIDE * (mi * nmat + mi), trace, invvol, i, ri, g.delta,
                                       hm_elastic_srd(pm[PM_ESTAR], srd, g.delta));
            hm_result r = hm_contact(fx, g.n, law_delta, srd, mstar, vrel, pm, dt, h, extra);
            if (fx & DEM_EFFECT_MC_STRAIN)
                mc_wall_fn[slot] = r.fel;
            v3_store(wall_pf, k * n + i, r.force);
            *fi = v3_add(*fi, r.force);
            if (fx & DEM_EFFECT_FRICTION) {
                v3_store(wall_hist, slot, r.hist);
                *ti = v3_sub(*ti, v3_scale(v3_cross(g.n, r.ft), arm));
            }
            mask |= 1u << k;
        } else {
            if ((fx & DEM_EFFECT_FRICTION) && ((old_mask >> k) & 1u))
                v3_store(wall_hist, slot, v3_zero());
            if (fx & DEM_EFFECT_MC_STRAIN)
                mc_wall_fn[slot] = (real)0;
        }
    }
    wall_mask[i] = mask;
}

/* Partial sum of the force that particles [b*B, (b+1)*B) exert on wall k, ascending id (B = DEM_REDUCE_BLOCK). */
DEM_INLINE void wall_reduce_block_at(int b, int k, int n, int nblocks, DEM_CONST_GLOBAL real *wall_pf,
                                     DEM_CONST_GLOBAL unsigned *wall_mask, DEM_GLOBAL real *partial)
{
    vec3 s = v3_zero();
    int end = (b + 1) * DEM_REDUCE_BLOCK < n ? (b + 1) * DEM_REDUCE_BLOCK : n;
    for (int j = b * DEM_REDUCE_BLOCK; j < end; j++)
        if ((wall_mask[j] >> k) & 1u) /* the wall receives minus the force on the particle */
            s = v3_sub(s, v3_load(wall_pf, k * n + j));
    v3_store(partial, k * nblocks + b, s);
}

/* item i = block i % nblocks of wall i / nblocks */
DEM_ITEM(wall_reduce_block) { wall_reduce_block_at(i % nblocks, i / nblocks, n, nblocks, wall_pf, wall_mask, partial); }

DEM_ITEM(wall_reduce_final)
{
    int k = i;
    vec3 s = v3_zero();
    for (int b = 0; b < nblocks; b++)
        s = v3_add(s, v3_load(partial, k * nblocks + b));
    v3_store(wall_force, k, s);
}
#endif /* DEM_WALL_FORCES_H */
