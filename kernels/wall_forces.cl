/* wall_forces.cl - the canonical per-wall force sum (common/wall_forces.h); the wall contacts themselves are
 * evaluated per particle inside kernels/contact_forces.cl.
 * Twin: reference/wall_forces.c */
#include "wall_forces.h"

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
