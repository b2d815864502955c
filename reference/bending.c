/* bending.c - reference twin of kernels/bending.cl: the same items in one serial loop (common/bending.h; arguments:
 * common/dem_kernels.h). */
#include "ref_kernels.h"
#include "bending.h"

DEM_REF_LOOP(hinge_forces)

#if DEM_REAL_SIZE == 8
/* sin(theta0 / 2) of a hinge at the positions x (fp64), for the host's rest angle of a hinge added with theta0 NAN:
 * the item's own expressions (host/sim_setup.c, pack_channel) */
double dem_hinge_rest_shalf(const double *x, const int *p)
{
    return hinge_geometry(v3_load(x, p[0]), v3_load(x, p[1]), v3_load(x, p[2]), v3_load(x, p[3])).shalf;
}
#endif

#if DEM_REAL_SIZE == 8
/* The period 2 pi / omega of hinge p[0..3]'s fold at the positions x, linearised about its rest angle: the angle's
 * stiffness k_el |E|^2 / (|N1| + |N2|) / 2 (d s / d theta = cos(theta / 2) / 2 <= 1/2) over its mass
 * 1 / sum_i |u_i|^2 / m_i, so omega^2 = stiffness / 2 * sum_i |u_i|^2 / m_i. INFINITY for k_el 0 or a degenerate
 * hinge. (host/sim_setup.c: the time-step bound.) */
double dem_hinge_period(const double *x, const int *p, double kel, const double *mass)
{
    vec3 x1 = v3_load(x, p[0]), x2 = v3_load(x, p[1]), x3 = v3_load(x, p[2]), x4 = v3_load(x, p[3]), u[4];
    hinge_geom g = hinge_geometry(x1, x2, x3, x4);
    if (!g.ok || !(kel > 0))
        return INFINITY;
    hinge_gradient(g, x1, x2, x3, x4, u);
    double w2 = 0;
    for (int k = 0; k < 4; k++)
        w2 += v3_dot(u[k], u[k]) / mass[k];
    w2 *= hinge_stiffness(g, kel) / 2;
    return 2 * M_PI / sqrt(w2);
}
#endif
