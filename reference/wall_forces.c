/* wall_forces.c - reference twin of kernels/wall_forces.cl: the per-wall force sum (common/wall_forces.h). */
#include "ref_kernels.h"
#include "wall_forces.h"

void REF(ref_wall_reduce)(int n, int nwalls, int nblocks, const real *wall_pf, const unsigned *wall_mask,
                          real *partial, real *wall_force)
{
    for (int g = 0; g < nblocks * nwalls; g++)
        wall_reduce_block_item(g % nblocks, g / nblocks, n, nblocks, wall_pf, wall_mask, partial);
    for (int k = 0; k < nwalls; k++)
        wall_reduce_final_item(k, nblocks, partial, wall_force);
}
