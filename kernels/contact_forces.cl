/* contact_forces.cl - Hertz-Mindlin particle and wall contacts (with the MC-stress / MC-strain normal law when on) summed per particle (common/contact_forces.h):
 * contact_pairs evaluates each pair once, contact_forces sums them per particle and adds the walls.
 * Twin: reference/contact_forces.c */
#include "contact_forces.h"

__kernel void contact_pairs(int n, int maxn, int nmat, real dt, __global const real *x, __global const real *v,
                            __global const real *w, __global const real *radius, __global const real *invmass,
                            __global const int *mat, __global const real *pairmat, __global const int *nbr_count,
                            __global const int *nbr_list, __global const int *nbr_mirror, __global real *hist,
                            __global unsigned char *touch, __global const int *in_start, __global real *pair,
                            __global real *force, __global real *torque, __global const real *trace,
                            __global const real *invvol, __global const real *mc_disp, __global real *mc_fn)
{
    int i = get_global_id(0);
    if (i < n)
        contact_pairs_item(DEM_EFFECTS, i, maxn, x, v, w, radius, invmass, mat, pairmat, nmat, nbr_count, nbr_list, nbr_mirror, hist,
                           touch, dt, in_start, pair, force, torque, trace, invvol, mc_disp, mc_fn);
}

__kernel void contact_forces(int n, int maxn, int nmat, real dt, __global const real *x, __global const real *v,
                             __global const real *w, __global const real *radius, __global const real *invmass,
                             __global const int *mat, __global const real *pairmat, __global const int *nbr_count,
                             __global const int *nbr_list, __global const int *nbr_mirror,
                             __global const unsigned char *touch, __global const int *in_start,
                             __global const real *pair, __global real *force,
                             __global real *torque, int nwalls, __global const int *wall_int,
                             __global const real *wall_real, __global real *wall_hist, __global real *wall_pf,
                             __global unsigned *wall_mask, __global const real *trace,
                             __global const real *invvol, __global const real *mc_wall_disp,
                             __global real *mc_wall_fn)
{
    int i = get_global_id(0);
    if (i < n)
        contact_forces_item(DEM_EFFECTS, i, maxn, x, v, w, radius, invmass, mat, pairmat, nmat, nbr_count, nbr_list, nbr_mirror,
                            touch, in_start, pair, dt, force, torque, n, nwalls, wall_int, wall_real,
                            wall_hist, wall_pf, wall_mask, trace, invvol, mc_wall_disp, mc_wall_fn);
}
