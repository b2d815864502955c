/* neighbor.c - reference twin of kernels/neighbor.cl (serial loops over common/neighbor.h). */
#include "ref_kernels.h"
#include "neighbor.h"

void REF(ref_nbr_build)(int n, int maxn, real skin, int ncx, int ncy, int ncz, const real *x, const real *radius,
                        const int *cell_of, const int *cell_start, const int *cell_particles, int *nbr_count,
                        int *nbr_list, int *in_count, int *flags)
{
    for (int i = 0; i < n; i++)
        nbr_build_item(i, maxn, skin, ncx, ncy, ncz, x, radius, cell_of, cell_start, cell_particles, nbr_count,
                       nbr_list, in_count, flags);
}

void REF(ref_nbr_carry)(unsigned fx, int n, int maxn, int old_maxn, const int *nbr_count, const int *nbr_list, const int *old_count,
                        const int *old_list, const real *old_hist, const unsigned char *old_touch, real *hist,
                        unsigned char *touch, int *mirror, int *flags, const real *old_mc_fn, real *mc_fn)
{
    for (int i = 0; i < n; i++)
        nbr_carry_item(fx, i, maxn, old_maxn, nbr_count, nbr_list, old_count, old_list, old_hist, old_touch, hist, touch, mirror,
                       flags, old_mc_fn, mc_fn);
}
