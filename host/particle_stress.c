/* particle_stress.c - host driver of kernels/particle_stress.cl: the stress trace each step (MC-stress) and the
 * stress tensor when FIELD_STRESS is read. */
#include "cl_backend.h"

/* arguments 0-12 are the same for both kernels */
static int stress_args(dem_backend *b, cl_kernel k)
{
    int s = b->cur;
    return clb_arg_int(b, k, 0, b->n) || clb_arg_int(b, k, 1, b->maxn[s]) || clb_arg_int(b, k, 2, b->nmat) ||
           clb_arg_mem(b, k, 3, b->x) || clb_arg_mem(b, k, 4, b->radius) || clb_arg_mem(b, k, 5, b->invvol) ||
           clb_arg_mem(b, k, 6, b->mat) || clb_arg_mem(b, k, 7, b->pairmat) || clb_arg_mem(b, k, 8, b->count[s]) ||
           clb_arg_mem(b, k, 9, b->list[s]) || clb_arg_int(b, k, 10, b->nwalls) ||
           clb_arg_mem(b, k, 11, b->wall_int) || clb_arg_mem(b, k, 12, b->wall_real);
}

int clb_stress_trace(dem_backend *b)
{
    cl_kernel k = b->k[K_STRESS_TRACE];
    return stress_args(b, k) || clb_arg_mem(b, k, 13, b->trace) || clb_launch(b, K_STRESS_TRACE, (size_t)b->n);
}

int clb_stress_tensor(dem_backend *b)
{
    int fail = 0;
    if (!b->stress && !(b->stress = clb_buffer(b, (size_t)ST_STRIDE * b->n * b->rs, NULL, &fail)))
        return 1;
    cl_kernel k = b->k[K_STRESS_TENSOR];
    return stress_args(b, k) || clb_arg_mem(b, k, 13, b->stress) || clb_launch(b, K_STRESS_TENSOR, (size_t)b->n);
}
