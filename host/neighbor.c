/* neighbor.c - host driver of kernels/neighbor.cl: build rows into the spare set, carry history into them. */
#include "cl_backend.h"

int clb_nbr_build(dem_backend *b)
{
    int s = 1 - b->cur;
    cl_kernel k = b->k[K_NBR_BUILD];
    return clb_arg_int(b, k, 0, b->n) || clb_arg_int(b, k, 1, b->maxn[s]) || clb_arg_real(b, k, 2, b->skin) ||
           clb_arg_int(b, k, 3, b->ncx) || clb_arg_int(b, k, 4, b->ncy) || clb_arg_int(b, k, 5, b->ncz) ||
           clb_arg_mem(b, k, 6, b->x) || clb_arg_mem(b, k, 7, b->radius) || clb_arg_mem(b, k, 8, b->cell_of) ||
           clb_arg_mem(b, k, 9, b->cell_start) || clb_arg_mem(b, k, 10, b->cell_particles) ||
           clb_arg_mem(b, k, 11, b->count[s]) || clb_arg_mem(b, k, 12, b->list[s]) ||
           clb_arg_mem(b, k, 13, b->in_count) || clb_arg_mem(b, k, 14, b->flags) ||
           clb_launch(b, K_NBR_BUILD, (size_t)b->n);
}

int clb_nbr_carry(dem_backend *b)
{
    int s = 1 - b->cur, o = b->cur;
    cl_kernel k = b->k[K_NBR_CARRY];
    return clb_arg_int(b, k, 0, b->n) || clb_arg_int(b, k, 1, b->maxn[s]) || clb_arg_int(b, k, 2, b->maxn[o]) ||
           clb_arg_mem(b, k, 3, b->count[s]) || clb_arg_mem(b, k, 4, b->list[s]) ||
           clb_arg_mem(b, k, 5, b->count[o]) || clb_arg_mem(b, k, 6, b->list[o]) ||
           clb_arg_mem(b, k, 7, b->hist[o]) || clb_arg_mem(b, k, 8, b->touch[o]) || clb_arg_mem(b, k, 9, b->hist[s]) ||
           clb_arg_mem(b, k, 10, b->touch[s]) || clb_arg_mem(b, k, 11, b->mirror[s]) || clb_arg_mem(b, k, 12, b->flags) ||
           clb_arg_mem(b, k, 13, b->mc_fn[o]) || clb_arg_mem(b, k, 14, b->mc_fn[s]) ||
           clb_launch(b, K_NBR_CARRY, (size_t)b->n);
}
