/* particle_stress.c - reference twin of kernels/particle_stress.cl (serial loops over common/particle_stress.h). */
#include "ref_kernels.h"
#include "particle_stress.h"

void REF(ref_stress_trace)(unsigned fx, int n, int maxn, int nmat, const real *x, const real *radius,
                           const real *invvol, const int *mat, const real *pairmat, const int *nbr_count,
                           const int *nbr_list, int nwalls, const int *wall_int, const real *wall_real, real *trace)
{
    for (int i = 0; i < n; i++)
        stress_item(fx, 0, i, maxn, x, radius, invvol, mat, pairmat, nmat, nbr_count, nbr_list, nwalls, wall_int,
                    wall_real, trace);
}

void REF(ref_stress_tensor)(unsigned fx, int n, int maxn, int nmat, const real *x, const real *radius,
                            const real *invvol, const int *mat, const real *pairmat, const int *nbr_count,
                            const int *nbr_list, int nwalls, const int *wall_int, const real *wall_real,
                            real *stress)
{
    for (int i = 0; i < n; i++)
        stress_item(fx, 1, i, maxn, x, radius, invvol, mat, pairmat, nmat, nbr_count, nbr_list, nwalls, wall_int,
                    wall_real, stress);
}
