/* particle_stress.cl - per-particle stress trace (online, MC-stress pass 1) and full stress tensor (output), one work
 * item per particle (common/particle_stress.h). Twin: reference/particle_stress.c */
#include "particle_stress.h"

__kernel void stress_trace(int n, int maxn, int nmat, __global const real *x, __global const real *radius,
                           __global const real *invvol, __global const int *mat, __global const real *pairmat,
                           __global const int *nbr_count, __global const int *nbr_list, int nwalls,
                           __global const int *wall_int, __global const real *wall_real, __global real *trace)
{
    int i = get_global_id(0);
    if (i < n)
        stress_item(DEM_EFFECTS, 0, i, maxn, x, radius, invvol, mat, pairmat, nmat, nbr_count, nbr_list, nwalls, wall_int,
                    wall_real, trace);
}

__kernel void stress_tensor(int n, int maxn, int nmat, __global const real *x, __global const real *radius,
                            __global const real *invvol, __global const int *mat, __global const real *pairmat,
                            __global const int *nbr_count, __global const int *nbr_list, int nwalls,
                            __global const int *wall_int, __global const real *wall_real, __global real *stress)
{
    int i = get_global_id(0);
    if (i < n)
        stress_item(DEM_EFFECTS, 1, i, maxn, x, radius, invvol, mat, pairmat, nmat, nbr_count, nbr_list, nwalls, wall_int,
                    wall_real, stress);
}
