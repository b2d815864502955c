/* integrate.c - reference twin of kernels/integrate.cl (serial loops over common/integrate.h). */
#include "ref_kernels.h"
#include "integrate.h"

void REF(ref_integrate_kick_drift)(unsigned fx, int n, real dt, vec3 g, real half_skin2, real *x, real *v, real *w,
                                   const real *force, const real *torque, const real *invmass,
                                   const real *invinertia, const real *x_build, int *flags)
{
    for (int i = 0; i < n; i++)
        integrate_kick_drift_item(fx, i, dt, g, half_skin2, x, v, w, force, torque, invmass, invinertia, x_build, flags);
}

void REF(ref_integrate_kick)(unsigned fx, int n, real dt, vec3 g, real *v, real *w, const real *force, const real *torque,
                             const real *invmass, const real *invinertia)
{
    for (int i = 0; i < n; i++)
        integrate_kick_item(fx, i, dt, g, v, w, force, torque, invmass, invinertia);
}
