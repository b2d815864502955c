/* wall_forces.c - host driver of kernels/wall_forces.cl: the fixed-block sum of the force each wall receives. */
#include "cl_backend.h"

int clb_wall_reduce(dem_backend *b)
{
    cl_kernel k = b->k[K_WALL_REDUCE_BLOCK];
    if (clb_arg_int(b, k, 0, b->n) || clb_arg_int(b, k, 1, b->nwalls) || clb_arg_int(b, k, 2, b->nblocks_red) ||
        clb_arg_mem(b, k, 3, b->wall_pf) || clb_arg_mem(b, k, 4, b->wall_mask) || clb_arg_mem(b, k, 5, b->partial) ||
        clb_launch(b, K_WALL_REDUCE_BLOCK, (size_t)b->nblocks_red * b->nwalls))
        return 1;
    k = b->k[K_WALL_REDUCE_FINAL];
    return clb_arg_int(b, k, 0, b->nwalls) || clb_arg_int(b, k, 1, b->nblocks_red) ||
           clb_arg_mem(b, k, 2, b->partial) || clb_arg_mem(b, k, 3, b->wall_force) ||
           clb_launch(b, K_WALL_REDUCE_FINAL, (size_t)b->nwalls);
}
