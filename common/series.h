/* series.h - a time-series row's terms, on the device in a sampled step: each particle's kinetic and
 * potential energy, the Hertz elastic energy of its contacts and its contact counts (dem_layout.h SE_*), written to
 * the particle's slot in one row of a ring of rows by the kernels that have them at hand - integrate_kick (the
 * velocities at the step's end; and at each block's first particle the walls' block partial sums), contact_forces
 * (the touching pairs it owns and its walls; with DEM_KEEP_PAIR_ENERGY each pair's energy comes from contact_pairs,
 * which has the pair's elastic force at hand). So a sampled step launches no kernel more than another step (with the
 * wall forces kept; without, the walls' block sums) and needs no synchronisation; the host reads the ring when it is full or the steps end and adds each row's terms in ascending
 * particle order in double, and finishes the walls' sums with the same tree (wall_reduce_mid, wall_reduce_final) (host/physics/energy.c): the same
 * bits on every backend.
 *
 * A pair's contact is counted by its lower id when the overlap the contact law computed (PR_DELTA) is positive, a wall
 * when the particle overlaps it (a rider never touches its wall); host/physics/energy.c counts the same from whole rows. A
 * fixed particle has neither kinetic nor potential energy, one that does not rotate no rotational energy (its inverse
 * mass or inertia is 0: host/core/sim_setup.c). The membrane's springs and patches are not counted: a run with them samples
 * on the host.
 */
#ifndef DEM_SERIES_H
#define DEM_SERIES_H
#include "vec3.h"
#include "dem_layout.h"
#include "laws/laws.h"
#include "wall_forces.h"

/* particle i's slot in row `row` of the ring */
DEM_INLINE DEM_GLOBAL real *series_slot(DEM_GLOBAL real *ring, int row, int n, int i)
{
    return ring + ((long)row * n + i) * SE_STRIDE;
}

/* Kinetic and potential energy of particle i at the end of the step (integrate_kick). */
DEM_INLINE void series_motion_terms(unsigned fx, vec3 xi, vec3 vi, vec3 wi, real invm, real invi, vec3 g,
                                    DEM_GLOBAL real *slot)
{
    real kin = (real)0, pot = (real)0;
    if (invm > (real)0) {
        real m = (real)1 / invm;
        kin = (real)0.5 * m * v3_dot(vi, vi);
        if (fx & DEM_EFFECT_GRAVITY)
            pot = -(m * v3_dot(g, xi));
    }
    if (invi > (real)0)
        kin += (real)0.5 / invi * v3_dot(wi, wi);
    slot[SE_KIN] = kin;
    slot[SE_POT] = pot;
}

/* Block b's partial sums for each wall (wall_part), into the row: from the forces contact_forces kept
 * (DEM_KEEP_WALL_FORCES, the same function as wall_reduce_block's), or, without them, the partial sums
 * wall_reduce_block computed in this step (the driver has them computed in a sampled step). The host finishes them
 * with the tree's upper levels (wall_reduce_mid, wall_reduce_final). */
DEM_INLINE void series_wall_blocks(unsigned fx, int b, int n, int nwalls, int nblocks, int row,
                                   DEM_CONST_GLOBAL unsigned *wall_mask, DEM_CONST_GLOBAL real *wall_pf,
                                   DEM_CONST_GLOBAL real *x, DEM_CONST_GLOBAL real *radius,
                                   DEM_CONST_GLOBAL int *wall_int, DEM_CONST_GLOBAL real *wall_real,
                                   DEM_CONST_GLOBAL unsigned *ride, DEM_CONST_GLOBAL real *partial,
                                   DEM_GLOBAL real *ring_wall, DEM_CONST_GLOBAL int *order)
{
    DEM_GLOBAL real *dst = ring_wall + (long)row * nwalls * nblocks * WP_STRIDE;
    if (!(fx & DEM_KEEP_WALL_FORCES)) {
        for (int k = 0; k < nwalls; k++)
            for (int q = 0; q < WP_STRIDE; q++)
                dst[(k * nblocks + b) * WP_STRIDE + q] = partial[(k * nblocks + b) * WP_STRIDE + q];
        return;
    }
    /* wall_block_kept's sums for every wall in one pass over the block: a particle that touches no wall (most of
     * them) costs one test, not one per wall; each wall's terms are still added in ascending stable id, the same
     * bits */
    wall_part p[DEM_WALL_MASK_BITS];
    for (int k = 0; k < nwalls; k++) {
        p[k].f = v3_zero();
        p[k].fn = (real)0;
    }
    int end = (b + 1) * DEM_REDUCE_BLOCK < n ? (b + 1) * DEM_REDUCE_BLOCK : n;
    for (int q = b * DEM_REDUCE_BLOCK; q < end; q++) { /* ascending stable id, as wall_block_kept */
        int j = order[q];
        unsigned m = wall_mask[j];
        for (int k = 0; m != 0u; k++, m >>= 1)
            if (m & 1u) {
                wall_geom g = wall_met(fx, wall_int, wall_real, ride, j, k, v3_load(x, j), radius[j]);
                wall_part_take(&p[k], v3_load(wall_pf, k * n + j), g.n);
            }
    }
    for (int k = 0; k < nwalls; k++)
        wall_part_store(dst, k * nblocks + b, p[k]);
}

/* The elastic energy of a touching pair of radii ra, rb and overlap delta, as its lower id counts it (pm: the pair's
 * row of the pair table; the run's law: laws/laws.h) */
DEM_INLINE real series_pair_energy(unsigned fx, DEM_CONST_GLOBAL real *pm, real ra, real rb, real delta)
{
    /* no law state here: a run with a law that has one always keeps its pairs' energies (DEM_KEEP_PAIR_ENERGY,
     * host/core/sim_setup.c), computed where the state is at hand (series_pair_energy_kept) */
    return law_energy(fx, pm, ra * rb / (ra + rb), delta, (real)0);
}
/* The same given the elastic force fel the law returned for the pair (law_energy_kept: Hertz's needs no root) */
DEM_INLINE real series_pair_energy_kept(unsigned fx, DEM_CONST_GLOBAL real *pm, real ra, real rb, real delta, real fel,
                                        real st)
{
    return law_energy_kept(fx, pm, ra * rb / (ra + rb), delta, fel, st);
}
#endif /* DEM_SERIES_H */
