/* series.h - a time-series row's terms, on the device in a sampled step: each particle's kinetic and
 * potential energy, the Hertz elastic energy of its contacts and its contact counts (dem_layout.h SE_*), written to
 * the particle's slot in one row of a ring of rows by the kernels that have them at hand - integrate_kick (the
 * velocities at the step's end; and, at item 0, the walls' sums of the step), contact_forces (the touching pairs it
 * owns and its walls; with DEM_KEEP_PAIR_ENERGY each pair's energy comes from contact_pairs, which has the pair's
 * elastic force at hand). A sampled step runs the walls' sums (wall_reduce_*), as the last step of a call does, and
 * needs no synchronisation; the host reads the ring when it is full or the steps end and adds each row's terms
 * exactly (common/exact_sum.h), rounded once to double (host/physics/energy.c): the same bits on every backend and
 * in any particle order.
 *
 * A pair's contact is counted by its lower id when the overlap the contact law computed (PR_DELTA) is positive, or in a
 * run with DEM_EFFECT_THORNTON_NING whenever it touches (a bond or a JKR contact holds across a gap:
 * laws/thornton_ning.h, contact_geometry.h pair_geometry_held), a wall when the particle overlaps it or, with
 * DEM_EFFECT_ADHESION, touches it across a gap (a rider never touches its wall); host/physics/energy.c counts the
 * same from whole rows. A
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

/* The walls' sums of the step (wall_reduce_final: the driver has them made in a sampled step) into the row */
DEM_INLINE void series_wall_row(int nwalls, int row, DEM_CONST_GLOBAL real *wall_force,
                                DEM_CONST_GLOBAL real *wall_nforce, DEM_GLOBAL real *ring_wall)
{
    DEM_GLOBAL real *dst = ring_wall + (long)row * nwalls * WP_STRIDE;
    for (int k = 0; k < nwalls; k++) {
        dst[k * WP_STRIDE + WP_FX] = wall_force[3 * k];
        dst[k * WP_STRIDE + WP_FY] = wall_force[3 * k + 1];
        dst[k * WP_STRIDE + WP_FZ] = wall_force[3 * k + 2];
        dst[k * WP_STRIDE + WP_FN] = wall_nforce[k];
    }
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
