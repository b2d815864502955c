/* bending.c - the host's fp64 helpers for hinges, from the item's own geometry (common/bending.h; declared in
 * ref_kernels.h): the rest angle, the fold period and the damping rate of the time-step bound. The loop
 * ref_hinge_forces is in loops.c. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include "ref_kernels.h"
#include "bending.h"

#if DEM_REAL_SIZE == 8
/* sin(theta0 / 2) of a hinge at the positions x (fp64), for the host's rest angle of a hinge added with theta0 NAN:
 * the item's own expressions (host/core/sim_setup.c, pack_channel) */
double dem_hinge_rest_shalf(const double *x, const int *p)
{
    return hinge_geometry(v3_load(x, p[0]), v3_load(x, p[1]), v3_load(x, p[2]), v3_load(x, p[3])).shalf;
}
#endif

#if DEM_REAL_SIZE == 8
/* The period 2 pi / omega of hinge p[0..3]'s fold at the positions x, linearised about its rest angle: the angle's
 * stiffness k_el |E|^2 / (|N1| + |N2|) / 2 (d s / d theta = cos(theta / 2) / 2 <= 1/2) over its mass
 * 1 / sum_i |u_i|^2 / m_i, so omega^2 = stiffness / 2 * sum_i |u_i|^2 / m_i. INFINITY for k_el 0 or a degenerate
 * hinge. (host/core/sim_setup.c: the time-step bound.) */
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

/* The largest decay rate lambda of the hinges' dissipative term, M^-1 C with C = sum_h k_diss |E| u u^T (force
 * -k_diss |E| theta' u_i on vertex i, bending.h): velocity Verlet needs lambda dt < 2. lambda is the largest eigenvalue
 * of the symmetric A = M^-1/2 C M^-1/2 (sqrt_im: sqrt of each vertex's inverse mass, 0 for a fixed one), found by
 * power iteration from a fixed start until the Rayleigh quotient changes by less than 1e-4 (at most 2000 products),
 * then raised by 5 % (the quotient approaches lambda from below). A vertex shares twelve hinges, so one hinge's own
 * rate is not enough (a fine membrane passing that blew up), and the Gershgorin bound over the rows - the first
 * version - was 2.4 times too high on seed 001's MSS_particle triaxial (6.8e-8 s against 1.64e-7 s). tests/
 * test_bending.c checks it against a dense eigenvalue bracket and against runs at and beyond it. 0 when no hinge
 * damps, -1 when memory runs out. */
double dem_hinge_damping_rate(const double *x, const int *hinge, const double *hinge_k, int nh, const double *sqrt_im,
                              int n)
{
    double *u = malloc(sizeof(double) * 13 * (size_t)(nh > 0 ? nh : 1)); /* per hinge: sqrt(im_k) u_k, then c */
    double *v = calloc(3 * (size_t)n, sizeof(double)), *w = calloc(3 * (size_t)n, sizeof(double)), lambda = 0;
    int any = 0;
    if (!u || !v || !w) {
        free(u), free(v), free(w);
        return -1;
    }
    for (int h = 0; h < nh; h++) {
        const int *p = hinge + 4 * h;
        vec3 x1 = v3_load(x, p[0]), x2 = v3_load(x, p[1]), x3 = v3_load(x, p[2]), x4 = v3_load(x, p[3]), g4[4];
        hinge_geom g = hinge_geometry(x1, x2, x3, x4);
        double *r = u + 13 * h;
        r[12] = g.ok && hinge_k[3 * h + 1] > 0 ? hinge_k[3 * h + 1] * g.le : 0;
        if (r[12] > 0)
            hinge_gradient(g, x1, x2, x3, x4, g4);
        for (int k = 0; k < 4; k++) {
            double f = r[12] > 0 ? sqrt_im[p[k]] : 0;
            if (f > 0)
                r[3 * k] = f * g4[k].x, r[3 * k + 1] = f * g4[k].y, r[3 * k + 2] = f * g4[k].z, any = 1;
            else /* a fixed vertex, or a hinge that does not damp (its gradient is not computed) */
                r[3 * k] = r[3 * k + 1] = r[3 * k + 2] = 0;
        }
    }
    if (any) {
        uint32_t seed = 12345u; /* a fixed pseudo-random start: no mode is left out by symmetry */
        double norm = 0;
        for (size_t i = 0; i < 3 * (size_t)n; i++) {
            seed = seed * 1664525u + 1013904223u;
            v[i] = (double)(seed >> 8) / 16777216.0 - 0.5;
            norm += v[i] * v[i];
        }
        for (int it = 0; it < 2000; it++) {
            for (size_t i = 0; i < 3 * (size_t)n; i++)
                v[i] /= sqrt(norm), w[i] = 0;
            for (int h = 0; h < nh; h++) { /* w += c (a . v) a, a = M^-1/2 u */
                const double *r = u + 13 * h;
                const int *p = hinge + 4 * h;
                double d = 0;
                for (int k = 0; k < 4; k++)
                    d += r[3 * k] * v[3 * p[k]] + r[3 * k + 1] * v[3 * p[k] + 1] + r[3 * k + 2] * v[3 * p[k] + 2];
                for (int k = 0; k < 4; k++)
                    for (int c = 0; c < 3; c++)
                        w[3 * p[k] + c] += r[12] * d * r[3 * k + c];
            }
            double q = 0;
            norm = 0;
            for (size_t i = 0; i < 3 * (size_t)n; i++)
                q += v[i] * w[i], norm += w[i] * w[i], v[i] = w[i];
            int done = it > 10 && fabs(q - lambda) <= 1e-4 * q;
            lambda = q;
            if (done || !(norm > 0))
                break;
        }
    }
    free(u), free(v), free(w);
    return 1.05 * lambda;
}
#endif
