/* wall_forces.c - host driver of kernels/wall_forces.cl: wall contacts, then the fixed-block force reduction. */
#include "cl_backend.h"

int clb_wall_forces(dem_backend *b)
{
    cl_kernel k = b->k[K_WALL_FORCES];
    if (clb_arg_int(b, k, 0, b->n) || clb_arg_int(b, k, 1, b->nwalls) || clb_arg_int(b, k, 2, b->nmat) ||
        clb_arg_real(b, k, 3, b->dt) || clb_arg_mem(b, k, 4, b->wall_int) || clb_arg_mem(b, k, 5, b->wall_real) ||
        clb_arg_mem(b, k, 6, b->x) || clb_arg_mem(b, k, 7, b->v) || clb_arg_mem(b, k, 8, b->w) ||
        clb_arg_mem(b, k, 9, b->radius) || clb_arg_mem(b, k, 10, b->invm) || clb_arg_mem(b, k, 11, b->mat) ||
        clb_arg_mem(b, k, 12, b->pairmat) || clb_arg_mem(b, k, 13, b->wall_hist) || clb_arg_mem(b, k, 14, b->f) ||
        clb_arg_mem(b, k, 15, b->t) || clb_arg_mem(b, k, 16, b->wall_pf) || clb_arg_mem(b, k, 17, b->wall_mask) ||
        clb_launch(b, K_WALL_FORCES, (size_t)b->n))
        return 1;
    k = b->k[K_WALL_REDUCE_BLOCK];
    if (clb_arg_int(b, k, 0, b->n) || clb_arg_int(b, k, 1, b->nwalls) || clb_arg_int(b, k, 2, b->nblocks_red) ||
        clb_arg_mem(b, k, 3, b->wall_pf) || clb_arg_mem(b, k, 4, b->wall_mask) || clb_arg_mem(b, k, 5, b->partial) ||
        clb_launch(b, K_WALL_REDUCE_BLOCK, (size_t)b->nblocks_red * b->nwalls))
        return 1;
    k = b->k[K_WALL_REDUCE_FINAL];
    return clb_arg_int(b, k, 0, b->nwalls) || clb_arg_int(b, k, 1, b->nblocks_red) ||
           clb_arg_mem(b, k, 2, b->partial) || clb_arg_mem(b, k, 3, b->wall_force) ||
           clb_launch(b, K_WALL_REDUCE_FINAL, (size_t)b->nwalls);
}
