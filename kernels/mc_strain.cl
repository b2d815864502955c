/* mc_strain.cl - MC-strain: displacements induced at each contact by the particle's other contacts, and one
 * fixed-point update of the contact forces (common/mc_strain.h). Twin: reference/mc_strain.c */
#include "mc_strain.h"

__kernel void mc_strain_disp(int n, int maxn, int nmat, __global const real *x, __global const real *radius,
                             __global const int *mat, __global const real *pairmat, __global const int *nbr_count,
                             __global const int *nbr_list, int nwalls, __global const int *wall_int,
                             __global const real *wall_real, __global const real *fn, __global const real *wall_fn,
                             __global real *disp, __global real *wall_disp)
{
    int i = get_global_id(0);
    if (i < n)
        mc_strain_disp_item(DEM_EFFECTS, i, maxn, x, radius, mat, pairmat, nmat, nbr_count, nbr_list, nwalls, wall_int,
                            wall_real, fn, wall_fn, disp, wall_disp);
}

__kernel void mc_strain_update(int n, int maxn, int nmat, real tol, __global const real *x,
                               __global const real *radius, __global const int *mat, __global const real *pairmat,
                               __global const int *nbr_count, __global const int *nbr_list,
                               __global const int *nbr_mirror, int nwalls, __global const int *wall_int,
                               __global const real *wall_real, __global const real *disp,
                               __global const real *wall_disp, __global real *fn, __global real *wall_fn,
                               __global int *flags)
{
    int i = get_global_id(0);
    if (i < n)
        mc_strain_update_item(DEM_EFFECTS, i, maxn, tol, x, radius, mat, pairmat, nmat, nbr_count, nbr_list,
                              nbr_mirror, nwalls, wall_int, wall_real, disp, wall_disp, fn, wall_fn, flags);
}
