/* mc_strain.c - host driver of kernels/mc_strain.cl: induced displacements, and one fixed-point update of the
 * MC-strain forces (the iteration loop itself is the driver's, host/sim.c). */
#include "cl_backend.h"

int clb_mc_strain_disp(dem_backend *b)
{
    int s = b->cur;
    cl_kernel k = b->k[K_MC_STRAIN_DISP];
    return clb_arg_int(b, k, 0, b->n) || clb_arg_int(b, k, 1, b->maxn[s]) || clb_arg_int(b, k, 2, b->nmat) ||
           clb_arg_mem(b, k, 3, b->x) || clb_arg_mem(b, k, 4, b->radius) || clb_arg_mem(b, k, 5, b->mat) ||
           clb_arg_mem(b, k, 6, b->pairmat) || clb_arg_mem(b, k, 7, b->count[s]) || clb_arg_mem(b, k, 8, b->list[s]) ||
           clb_arg_int(b, k, 9, b->nwalls) || clb_arg_mem(b, k, 10, b->wall_int) ||
           clb_arg_mem(b, k, 11, b->wall_real) || clb_arg_mem(b, k, 12, b->mc_fn[s]) ||
           clb_arg_mem(b, k, 13, b->mc_wall_fn) || clb_arg_mem(b, k, 14, b->mc_disp[s]) ||
           clb_arg_mem(b, k, 15, b->mc_wall_disp) || clb_launch(b, K_MC_STRAIN_DISP, (size_t)b->n);
}

int clb_mc_strain_update(dem_backend *b, double tol)
{
    int s = b->cur;
    cl_kernel k = b->k[K_MC_STRAIN_UPDATE];
    return clb_arg_int(b, k, 0, b->n) || clb_arg_int(b, k, 1, b->maxn[s]) || clb_arg_int(b, k, 2, b->nmat) ||
           clb_arg_real(b, k, 3, tol) || clb_arg_mem(b, k, 4, b->x) || clb_arg_mem(b, k, 5, b->radius) ||
           clb_arg_mem(b, k, 6, b->mat) || clb_arg_mem(b, k, 7, b->pairmat) || clb_arg_mem(b, k, 8, b->count[s]) ||
           clb_arg_mem(b, k, 9, b->list[s]) || clb_arg_mem(b, k, 10, b->mirror[s]) ||
           clb_arg_int(b, k, 11, b->nwalls) || clb_arg_mem(b, k, 12, b->wall_int) ||
           clb_arg_mem(b, k, 13, b->wall_real) || clb_arg_mem(b, k, 14, b->mc_disp[s]) ||
           clb_arg_mem(b, k, 15, b->mc_wall_disp) || clb_arg_mem(b, k, 16, b->mc_fn[s]) ||
           clb_arg_mem(b, k, 17, b->mc_wall_fn) || clb_arg_mem(b, k, 18, b->flags) ||
           clb_launch(b, K_MC_STRAIN_UPDATE, (size_t)b->n);
}
