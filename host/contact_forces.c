/* contact_forces.c - host driver of kernels/contact_forces.cl: contact_pairs (each pair once), then contact_forces
 * (per-particle sums in canonical order, walls). */
#include "cl_backend.h"

/* arguments 0-12 are the same for both kernels */
static int common_args(dem_backend *b, cl_kernel k)
{
    int s = b->cur;
    return clb_arg_int(b, k, 0, b->n) || clb_arg_int(b, k, 1, b->maxn[s]) || clb_arg_int(b, k, 2, b->nmat) ||
           clb_arg_real(b, k, 3, b->dt) || clb_arg_mem(b, k, 4, b->x) || clb_arg_mem(b, k, 5, b->v) ||
           clb_arg_mem(b, k, 6, b->w) || clb_arg_mem(b, k, 7, b->radius) || clb_arg_mem(b, k, 8, b->invm) ||
           clb_arg_mem(b, k, 9, b->mat) || clb_arg_mem(b, k, 10, b->pairmat) || clb_arg_mem(b, k, 11, b->count[s]) ||
           clb_arg_mem(b, k, 12, b->list[s]);
}

int clb_contact_forces(dem_backend *b)
{
    int s = b->cur;
    cl_kernel k = b->k[K_CONTACT_PAIRS];
    if (common_args(b, k) || clb_arg_mem(b, k, 13, b->mirror[s]) || clb_arg_mem(b, k, 14, b->hist[s]) ||
        clb_arg_mem(b, k, 15, b->touch[s]) || clb_arg_mem(b, k, 16, b->in_start) || clb_arg_mem(b, k, 17, b->pair) ||
        clb_arg_mem(b, k, 18, b->f) || clb_arg_mem(b, k, 19, b->t) || clb_arg_mem(b, k, 20, b->trace) ||
        clb_arg_mem(b, k, 21, b->invvol) || clb_arg_mem(b, k, 22, b->mc_disp[s]) || clb_arg_mem(b, k, 23, b->mc_fn[s]) ||
        clb_launch(b, K_CONTACT_PAIRS, (size_t)b->n))
        return 1;
    k = b->k[K_CONTACT_FORCES];
    return common_args(b, k) || clb_arg_mem(b, k, 13, b->mirror[s]) || clb_arg_mem(b, k, 14, b->touch[s]) ||
           clb_arg_mem(b, k, 15, b->in_start) || clb_arg_mem(b, k, 16, b->pair) || clb_arg_mem(b, k, 17, b->f) ||
           clb_arg_mem(b, k, 18, b->t) || clb_arg_int(b, k, 19, b->nwalls) || clb_arg_mem(b, k, 20, b->wall_int) ||
           clb_arg_mem(b, k, 21, b->wall_real) || clb_arg_mem(b, k, 22, b->wall_hist) ||
           clb_arg_mem(b, k, 23, b->wall_pf) || clb_arg_mem(b, k, 24, b->wall_mask) ||
           clb_arg_mem(b, k, 25, b->trace) || clb_arg_mem(b, k, 26, b->invvol) ||
           clb_arg_mem(b, k, 27, b->mc_wall_disp) || clb_arg_mem(b, k, 28, b->mc_wall_fn) ||
           clb_launch(b, K_CONTACT_FORCES, (size_t)b->n);
}
