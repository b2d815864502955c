/* integrate.cl - velocity Verlet half steps (common/integrate.h). Twin: reference/integrate.c */
#include "integrate.h"

__kernel void integrate_kick_drift(int n, real dt, real gx, real gy, real gz, real half_skin2, __global real *x,
                                   __global real *v, __global real *w, __global const real *force,
                                   __global const real *torque, __global const real *invmass,
                                   __global const real *invinertia, __global const real *x_build,
                                   __global int *flags)
{
    int i = get_global_id(0);
    if (i < n)
        integrate_kick_drift_item(DEM_EFFECTS, i, dt, v3(gx, gy, gz), half_skin2, x, v, w, force, torque, invmass, invinertia,
                                  x_build, flags);
}

__kernel void integrate_kick(int n, real dt, real gx, real gy, real gz, __global real *v, __global real *w,
                             __global const real *force, __global const real *torque,
                             __global const real *invmass, __global const real *invinertia)
{
    int i = get_global_id(0);
    if (i < n)
        integrate_kick_item(DEM_EFFECTS, i, dt, v3(gx, gy, gz), v, w, force, torque, invmass, invinertia);
}
