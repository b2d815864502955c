/* bending.h - hinges between pairs of triangles: the membrane's resistance to bending (seed 001 Eq. 8-16, after
 * Bridson, Marino and Fedkiw, SCA 2003).
 *
 * Hinge h: vertices 1, 2, 3, 4 = hinge_int[4h..4h+3]; triangles (1, 3, 4) and (2, 4, 3) share the edge from 3 to 4,
 *     E = x4 - x3,   N1 = (x1 - x3) x (x1 - x4)   (Eq. 8),   N2 = (x2 - x4) x (x2 - x3)   (Eq. 9).
 * Angle. Eq. 10 writes cos(theta) = n1 . n2 with the unnormalised normals; we normalise, and sign the angle so that a
 * fold either way is told apart: cos(theta) = N1.N2 / (|N1||N2|), sin(theta) = (N2 x N1).E / (|N1||N2||E|), and
 *     s(theta) = sin(theta / 2) = sgn(sin theta) |n1 - n2| / 2   (n = N / |N|; |n1 - n2|^2 = 2 - 2 cos theta),
 * only + - * / sqrt. (sqrt((1 - cos theta) / 2) is the same in exact arithmetic but loses half the digits near a flat
 * hinge: in fp32 it put the period of a 0.01 rad fold 0.14 % off; |n1 - n2| / 2 puts it 6e-6 off, as in fp64.)
 * theta grows when x1 moves along N1 or x2 along N2 (the wings fold towards their normals); a flat hinge has theta 0.
 * (The first draft took (N1 x N2).E, and tests/test_bending.c's finite differences caught u_i = -d theta/d x_i: the
 * hinge then pushed away from its rest angle.)
 * Gradient. With this sign, the angle's gradient with respect to the vertices is (Bridson et al., Sec. 4)
 *     u1 = |E| N1 / |N1|^2,   u2 = |E| N2 / |N2|^2,
 *     u3 = (x1 - x4).E/|E| N1/|N1|^2 + (x2 - x4).E/|E| N2/|N2|^2,
 *     u4 = -(x1 - x3).E/|E| N1/|N1|^2 - (x2 - x3).E/|E| N2/|N2|^2,
 * i.e. u_i = d theta / d x_i, so that d theta / dt = sum_i u_i . v_i and u1 + u2 + u3 + u4 = 0 (no net force; no net
 * torque either, the angle being invariant under rotations). Seed 001 prints Eq. 16 (u4) without the minus signs; with
 * them the four sum to zero, without them the hinge would push the membrane as a whole: the minus signs are taken.
 * tests/test_bending.c checks u_i against finite differences of theta computed independently.
 * Forces. Seed 001 Eq. 11 and 12 give the elastic and the dissipative force along u_i with opposite signs; a restoring
 * force must point down the gradient of the bending energy, so both are read as restoring:
 *     F_i = -[ k_el |E|^2 / (|N1| + |N2|) (s(theta) - s(theta0)) + k_diss |E| d theta/dt ] u_i.
 * Units. With u_i as Eq. 13-16 print them (|u_1| = |E| / |N1|, one over the wing's height: 1/m), k_el is in N m and
 * k_diss in N s. Seed 001 gives k_el = 1e-3 N/m and k_diss = 1e-4 N s/m, units no reading of its equations yields
 * (unit vectors u_i would make k_diss N s/m but k_el N). Decision: the printed equations rule, and the printed
 * numbers are taken in N m and N s. The damping is then strong - on 1.33 mm edges it bounds the time step at
 * 1.64e-7 s (host/core/sim_setup.c) - but the paper's triaxial sets no time step to hold it against.
 * A degenerate hinge (an edge or a triangle of zero size) exerts nothing. The four forces go to the contribution
 * channel (springs.h) at chan_slot[2 nsprings + 3 ntriangles + 4h + k].
 */
#ifndef DEM_BENDING_H
#define DEM_BENDING_H
#include "dem_kernels.h"
#include "vec3.h"
#include "dem_layout.h"

/* s(theta) of a hinge, and its pieces (the item and the host's rest angle use the same expressions) */
typedef struct {
    vec3 e, n1, n2;
    real le, n1s, n2s, l1, l2, shalf; /* |E|, |N1|^2, |N2|^2, |N1|, |N2|, s(theta) */
    int ok;
} hinge_geom;

DEM_INLINE hinge_geom hinge_geometry(vec3 x1, vec3 x2, vec3 x3, vec3 x4)
{
    hinge_geom g;
    g.e = v3_sub(x4, x3);
    g.n1 = v3_cross(v3_sub(x1, x3), v3_sub(x1, x4));
    g.n2 = v3_cross(v3_sub(x2, x4), v3_sub(x2, x3));
    g.le = dem_sqrt(v3_dot(g.e, g.e));
    g.n1s = v3_dot(g.n1, g.n1);
    g.n2s = v3_dot(g.n2, g.n2);
    g.l1 = dem_sqrt(g.n1s);
    g.l2 = dem_sqrt(g.n2s);
    g.ok = g.le > (real)0 && g.n1s > (real)0 && g.n2s > (real)0;
    g.shalf = (real)0;
    if (g.ok) {
        vec3 d = v3_sub(v3_scale(g.n1, (real)1 / g.l1), v3_scale(g.n2, (real)1 / g.l2));
        real h = dem_sqrt(v3_dot(d, d)) / (real)2, sn = v3_dot(v3_cross(g.n2, g.n1), g.e);
        g.shalf = sn < (real)0 ? -h : h;
    }
    return g;
}

/* u_i = d theta / d x_i of a hinge whose geometry g is ok */
DEM_INLINE void hinge_gradient(hinge_geom g, vec3 x1, vec3 x2, vec3 x3, vec3 x4, vec3 *u)
{
    vec3 m1 = v3_scale(g.n1, (real)1 / g.n1s), m2 = v3_scale(g.n2, (real)1 / g.n2s); /* N / |N|^2 */
    real inv_le = (real)1 / g.le;
    u[0] = v3_scale(m1, g.le);
    u[1] = v3_scale(m2, g.le);
    u[2] = v3_add(v3_scale(m1, v3_dot(v3_sub(x1, x4), g.e) * inv_le), v3_scale(m2, v3_dot(v3_sub(x2, x4), g.e) * inv_le));
    u[3] = v3_neg(v3_add(v3_scale(m1, v3_dot(v3_sub(x1, x3), g.e) * inv_le),
                         v3_scale(m2, v3_dot(v3_sub(x2, x3), g.e) * inv_le)));
}

/* the elastic prefactor k_el |E|^2 / (|N1| + |N2|) [N m]: the elastic force on vertex i is -it (s - s0) u_i */
DEM_INLINE real hinge_stiffness(hinge_geom g, real kel) { return kel * (g.le * g.le) / (g.l1 + g.l2); }

DEM_ITEM(hinge_forces)
{
    /* stable ids to places */
    int p1 = order[hinge_int[4 * i]], p2 = order[hinge_int[4 * i + 1]], p3 = order[hinge_int[4 * i + 2]],
        p4 = order[hinge_int[4 * i + 3]];
    vec3 x1 = v3_load(x, p1), x2 = v3_load(x, p2), x3 = v3_load(x, p3), x4 = v3_load(x, p4);
    hinge_geom g = hinge_geometry(x1, x2, x3, x4);
    vec3 u[4] = {v3_zero(), v3_zero(), v3_zero(), v3_zero()};
    real mag = (real)0;
    if (g.ok) {
        hinge_gradient(g, x1, x2, x3, x4, u);
        real rate = v3_dot(u[0], v3_load(v, p1)) + v3_dot(u[1], v3_load(v, p2)) + v3_dot(u[2], v3_load(v, p3)) +
                    v3_dot(u[3], v3_load(v, p4));
        DEM_CONST_GLOBAL real *hk = hinge_real + HG_STRIDE * i;
        mag = hinge_stiffness(g, hk[HG_KEL]) * (g.shalf - hk[HG_SIN0]) + hk[HG_KDISS] * g.le * rate;
    }
    int base = 2 * nsprings + 3 * ntriangles + 4 * i;
    for (int k = 0; k < 4; k++)
        v3_store(chan_rec, chan_slot[base + k], v3_scale(u[k], -mag));
}
#endif /* DEM_BENDING_H */
