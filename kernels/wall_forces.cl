/* wall_forces.cl - particle-wall contacts and the canonical per-wall force sum (common/wall_forces.h).
 * Twin: reference/wall_forces.c */
#include "wall_forces.h"

__kernel void wall_forces(int n, int nwalls, int nmat, real dt, __global const int *wall_int,
                          __global const real *wall_real, __global const real *x, __global const real *v,
                          __global const real *w, __global const real *radius, __global const real *invmass,
                          __global const int *mat, __global const real *pairmat, __global real *wall_hist,
                          __global real *force, __global real *torque, __global real *wall_pf,
                          __global unsigned *wall_mask)
{
    int i = get_global_id(0);
    if (i < n)
        wall_forces_item(i, n, nwalls, wall_int, wall_real, x, v, w, radius, invmass, mat, pairmat, nmat, wall_hist,
                         dt, force, torque, wall_pf, wall_mask);
}

/* global size >= nblocks * nwalls; item (b, k) = (gid % nblocks, gid / nblocks) */
__kernel void wall_reduce_block(int n, int nwalls, int nblocks, __global const real *wall_pf,
                                __global const unsigned *wall_mask, __global real *partial)
{
    int g = get_global_id(0);
    if (g < nblocks * nwalls)
        wall_reduce_block_item(g % nblocks, g / nblocks, n, nblocks, wall_pf, wall_mask, partial);
}

__kernel void wall_reduce_final(int nwalls, int nblocks, __global const real *partial, __global real *wall_force)
{
    int k = get_global_id(0);
    if (k < nwalls)
        wall_reduce_final_item(k, nblocks, partial, wall_force);
}
