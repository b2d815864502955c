/* neighbor.cl - Verlet rows from cells, history carried across rebuilds (common/neighbor.h). Twin: reference/neighbor.c */
#include "neighbor.h"

__kernel void nbr_build(int n, int maxn, real skin, int ncx, int ncy, int ncz, __global const real *x,
                        __global const real *radius, __global const int *cell_of, __global const int *cell_start,
                        __global const int *cell_particles, __global int *nbr_count, __global int *nbr_list,
                        __global int *in_count, __global int *flags)
{
    int i = get_global_id(0);
    if (i < n)
        nbr_build_item(i, maxn, skin, ncx, ncy, ncz, x, radius, cell_of, cell_start, cell_particles, nbr_count,
                       nbr_list, in_count, flags);
}

__kernel void nbr_carry(int n, int maxn, int old_maxn, __global const int *nbr_count, __global const int *nbr_list,
                        __global const int *old_count, __global const int *old_list, __global const real *old_hist,
                        __global const unsigned char *old_touch, __global real *hist, __global unsigned char *touch,
                        __global int *mirror, __global int *flags, __global const real *old_mc_fn,
                        __global real *mc_fn)
{
    int i = get_global_id(0);
    if (i < n)
        nbr_carry_item(DEM_EFFECTS, i, maxn, old_maxn, nbr_count, nbr_list, old_count, old_list, old_hist, old_touch, hist, touch, mirror,
                       flags, old_mc_fn, mc_fn);
}
