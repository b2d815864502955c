/* mc_strain.c - reference twin of kernels/mc_strain.cl (serial loops over common/mc_strain.h). */
#include "ref_kernels.h"
#include "mc_strain.h"

void REF(ref_mc_strain_disp)(unsigned fx, int n, int maxn, int nmat, const real *x, const real *radius, const int *mat,
                             const real *pairmat, const int *nbr_count, const int *nbr_list, int nwalls,
                             const int *wall_int, const real *wall_real, const real *fn, const real *wall_fn,
                             real *disp, real *wall_disp)
{
    for (int i = 0; i < n; i++)
        mc_strain_disp_item(fx, i, maxn, x, radius, mat, pairmat, nmat, nbr_count, nbr_list, nwalls, wall_int,
                            wall_real, fn, wall_fn, disp, wall_disp);
}

void REF(ref_mc_strain_update)(unsigned fx, int n, int maxn, int nmat, real tol, const real *x, const real *radius,
                               const int *mat, const real *pairmat, const int *nbr_count, const int *nbr_list,
                               const int *nbr_mirror, int nwalls, const int *wall_int, const real *wall_real,
                               const real *disp, const real *wall_disp, real *fn, real *wall_fn, int *flags)
{
    for (int i = 0; i < n; i++)
        mc_strain_update_item(fx, i, maxn, tol, x, radius, mat, pairmat, nmat, nbr_count, nbr_list, nbr_mirror,
                              nwalls, wall_int, wall_real, disp, wall_disp, fn, wall_fn, flags);
}
