/* wall_forces.c - reference twin of kernels/wall_forces.cl (serial loops over common/wall_forces.h). */
#include "ref_kernels.h"
#include "wall_forces.h"

void REF(ref_wall_forces)(int n, int nwalls, int nmat, real dt, const int *wall_int, const real *wall_real,
                          const real *x, const real *v, const real *w, const real *radius, const real *invmass,
                          const int *mat, const real *pairmat, real *wall_hist, real *force, real *torque,
                          real *wall_pf, unsigned *wall_mask)
{
    for (int i = 0; i < n; i++)
        wall_forces_item(i, n, nwalls, wall_int, wall_real, x, v, w, radius, invmass, mat, pairmat, nmat, wall_hist,
                         dt, force, torque, wall_pf, wall_mask);
}

void REF(ref_wall_reduce)(int n, int nwalls, int nblocks, const real *wall_pf, const unsigned *wall_mask,
                          real *partial, real *wall_force)
{
    for (int g = 0; g < nblocks * nwalls; g++)
        wall_reduce_block_item(g % nblocks, g / nblocks, n, nblocks, wall_pf, wall_mask, partial);
    for (int k = 0; k < nwalls; k++)
        wall_reduce_final_item(k, nblocks, partial, wall_force);
}
