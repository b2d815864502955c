/* integrate.c - host driver of kernels/integrate.cl (velocity Verlet half steps). */
#include "cl_backend.h"

int clb_integrate_kick_drift(dem_backend *b)
{
    cl_kernel k = b->k[K_KICK_DRIFT];
    int e = clb_arg_int(b, k, 0, b->n) || clb_arg_real(b, k, 1, b->dt) || clb_arg_real(b, k, 2, b->g[0]) ||
            clb_arg_real(b, k, 3, b->g[1]) || clb_arg_real(b, k, 4, b->g[2]) ||
            clb_arg_real(b, k, 5, b->half_skin2) || clb_arg_mem(b, k, 6, b->x) || clb_arg_mem(b, k, 7, b->v) ||
            clb_arg_mem(b, k, 8, b->w) || clb_arg_mem(b, k, 9, b->f) || clb_arg_mem(b, k, 10, b->t) ||
            clb_arg_mem(b, k, 11, b->invm) || clb_arg_mem(b, k, 12, b->invi) || clb_arg_mem(b, k, 13, b->x_build) ||
            clb_arg_mem(b, k, 14, b->flags);
    return e || clb_launch(b, K_KICK_DRIFT, (size_t)b->n);
}

int clb_integrate_kick(dem_backend *b)
{
    cl_kernel k = b->k[K_KICK];
    int e = clb_arg_int(b, k, 0, b->n) || clb_arg_real(b, k, 1, b->dt) || clb_arg_real(b, k, 2, b->g[0]) ||
            clb_arg_real(b, k, 3, b->g[1]) || clb_arg_real(b, k, 4, b->g[2]) || clb_arg_mem(b, k, 5, b->v) ||
            clb_arg_mem(b, k, 6, b->w) || clb_arg_mem(b, k, 7, b->f) || clb_arg_mem(b, k, 8, b->t) ||
            clb_arg_mem(b, k, 9, b->invm) || clb_arg_mem(b, k, 10, b->invi);
    return e || clb_launch(b, K_KICK, (size_t)b->n);
}
