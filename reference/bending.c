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
void dem_hinge_damping_rows(const double *x, const int *p, double kdiss, double row[4]);
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

/* The dissipative term of hinge p[0..3] (force -k_diss |E| theta' u_i on vertex i, bending.h) as rows of the damping
 * matrix C = k_diss |E| u u^T: row[i] = k_diss |E| |u_i| sum_k,d |u_k,d|, a bound of the absolute row sums of
 * vertex i's three rows. The host adds them over a vertex's hinges and divides by its mass: a Gershgorin bound on the largest decay
 * rate lambda of M^-1 C, which velocity Verlet needs below 2 / dt (a vertex shares ~6 hinges: one hinge's own rate
 * is not enough - a fine membrane passed that and still blew up). Zeros for k_diss 0 or a degenerate hinge. */
void dem_hinge_damping_rows(const double *x, const int *p, double kdiss, double row[4])
{
    vec3 x1 = v3_load(x, p[0]), x2 = v3_load(x, p[1]), x3 = v3_load(x, p[2]), x4 = v3_load(x, p[3]), u[4];
    hinge_geom g = hinge_geometry(x1, x2, x3, x4);
    for (int k = 0; k < 4; k++)
        row[k] = 0;
    if (!g.ok || !(kdiss > 0))
        return;
    hinge_gradient(g, x1, x2, x3, x4, u);
    double sum = 0; /* sum over the 12 components of |u_k,d| */
    for (int k = 0; k < 4; k++)
        sum += fabs(u[k].x) + fabs(u[k].y) + fabs(u[k].z);
    for (int k = 0; k < 4; k++) /* a row (i, c) of C sums to |u_i,c| sum |u_k,d| <= |u_i| sum |u_k,d| */
        row[k] = kdiss * g.le * sqrt(v3_dot(u[k], u[k])) * sum;
}
#endif
