/* contact_geometry.h - where two spheres touch: overlap, normal and effective radius, computed the same way by every
 * caller (the force law, the stress trace, MC-strain), so all of them see the same bits for the same pair.
 *
 * pair_geometry(xa, ra, xb, rb): n is the unit vector from b to a (seed 000 Eq. 2). Swapping a and b negates d
 * exactly, so dist2, delta and rstar have the same bits either way (IEEE + and * commute): particle j's view of a
 * contact equals particle i's.
 * wall_geometry(type, wall, x, r): a plane of any orientation (flat, or a concave punch's face with its cup), or the
 * inside of a cylinder (a finite die with its rims and faces) (dem_layout.h W_*); n points from the wall towards the
 * particle centre.
 */
#ifndef DEM_CONTACT_GEOMETRY_H
#define DEM_CONTACT_GEOMETRY_H
#include "vec3.h"
#include "dem_layout.h"
#include "../include/dem_effects.h"

typedef struct {
    int active;  /* 1 when the spheres overlap */
    real delta;  /* overlap r_a + r_b - |x_a - x_b| [m] */
    real rstar;  /* r_a r_b / (r_a + r_b) [m] */
    vec3 n;      /* unit vector from b to a */
} pair_geom;

/* reach >= 1: the pair is active when |x_a - x_b| < reach (r_a + r_b), so with reach > 1 delta is negative across a
 * gap (MC-strain's contact distance, mc_strain.h). pair_geometry is reach 1 (1 * x == x: the same bits). */
DEM_INLINE pair_geom pair_geometry_reach(vec3 xa, real ra, vec3 xb, real rb, real reach)
{
    pair_geom g;
    vec3 d = v3_sub(xa, xb);
    real rsum = ra + rb, cut = reach * rsum;
    real dist2 = v3_dot(d, d);
    g.active = 0;
    g.delta = (real)0;
    g.rstar = (real)0;
    g.n = v3((real)0, (real)0, (real)1);
    if (!(dist2 < cut * cut))
        return g;
    g.active = 1;
    real dist = dem_sqrt(dist2);
    /* Coincident centres: the direction is undefined; the defined policy is to push a along +z. */
    if (dist > (real)0)
        g.n = v3_scale(d, (real)1 / dist);
    g.delta = rsum - dist;
    g.rstar = ra * rb / rsum;
    return g;
}

DEM_INLINE pair_geom pair_geometry(vec3 xa, real ra, vec3 xb, real rb)
{
    return pair_geometry_reach(xa, ra, xb, rb, (real)1);
}
typedef struct {
    int active;
    real delta; /* overlap [m] */
    vec3 n;     /* unit normal from the wall towards the particle centre */
} wall_geom;

/* A circle about the wall's axis nw touched as an edge (a die's rim, a cup's rim): the centre lies q from it along the
 * outward radial radial / rho and a from it along the axis; n from the circle to the centre. reach = ri + gap (below). */
DEM_INLINE void wall_edge_contact(wall_geom *g, vec3 radial, real rho, vec3 nw, real q, real a, real ri, real reach)
{
    real dist2 = a * a + q * q;
    if (dist2 > (real)0 && dist2 < reach * reach) {
        real dist = dem_sqrt(dist2);
        g->delta = ri - dist;
        g->active = 1;
        g->n = v3_add(v3_scale(radial, q / (dist * rho)), v3_scale(nw, a / dist));
    }
}

/* gap >= 0: the contact is active while the overlap delta > -gap, so with gap > 0 delta is negative across a gap (a JKR
 * contact held to its release: wall_forces.h, wall_contact_eval). gap 0 is the plain contact (delta > -0 is delta > 0,
 * and ri + 0 is ri: the same bits). */
DEM_INLINE wall_geom wall_geometry_gap(int type, DEM_CONST_GLOBAL real *wr, vec3 xi, real ri, real gap)
{
    wall_geom g;
    real lo = -gap, reach = ri + gap;
    vec3 p = v3(wr[W_PX], wr[W_PY], wr[W_PZ]);
    vec3 nw = v3(wr[W_NX], wr[W_NY], wr[W_NZ]);
    vec3 d = v3_sub(xi, p);
    g.active = 0;
    g.delta = (real)0;
    g.n = nw;
    if (type == WALL_PLANE) {
        /* A centre behind the plane still gets pushed back out (d > r), rather than tunnelling silently. */
        g.delta = ri - v3_dot(d, nw);
        g.active = g.delta > lo;
    } else if (type == WALL_PLANE_CUP) {
        /* A concave punch: the plane (the land) with a spherical cup of radius rp at the face and depth c about the
         * normal through the point, recessed away from the particles; its sphere has radius rc = (rp^2 + c^2) / 2c and
         * its centre on that normal, rc - c above the land (c <= rp: at most a hemisphere). The nearest point of the
         * face to the centre: over the land (rho >= rp) the plane below it; within the cup's radius the sphere's
         * point on the line from its centre, when that point lies on the cup (at or below the land), else the rim
         * (the circle where the cup meets the land, an edge). A centre behind the face is pushed back out, as a
         * plane's. */
        real h = v3_dot(d, nw), rp = wr[W_RADIUS], c = wr[W_HEIGHT];
        vec3 radial = v3_sub(d, v3_scale(nw, h));
        real rho2 = v3_dot(radial, radial);
        if (!(rho2 < rp * rp)) { /* over the land */
            g.delta = ri - h;
            g.active = g.delta > lo;
        } else {
            real rc = (rp * rp + c * c) / ((real)2 * c), hc = rc - c;
            vec3 to_c = v3_sub(v3_scale(nw, hc), d); /* from the particle's centre to the sphere's */
            real dc2 = v3_dot(to_c, to_c);
            real dc = dem_sqrt(dc2);
            if (dc > (real)0 && rc * (h - hc) <= -(hc * dc)) { /* on the cup: hc + rc (h - hc) / dc <= 0 */
                /* the gap rc - dc as (rc^2 - dc^2) / (rc + dc), with e = h + c the height above the cup's bottom:
                 * rc - dc itself cancels (rc 10-40 mm against overlaps of 1e-7 m: a 2-20 % error in fp32) */
                real e = h + c;
                g.delta = ri - (e * ((real)2 * rc - e) - rho2) / (rc + dc);
                g.active = g.delta > lo;
                g.n = v3_scale(to_c, (real)1 / dc);
            } else if (rho2 > (real)0) { /* the rim, touched as an edge (q < 0: inside its circle) */
                real rho = dem_sqrt(rho2);
                wall_edge_contact(&g, radial, rho, nw, rho - rp, h, ri, reach);
            } else { /* on the axis, above the sphere's centre: every rim point as near; pushed along the normal */
                real dist = dem_sqrt(rp * rp + h * h);
                g.delta = ri - dist;
                g.active = g.delta > lo;
            }
        }
    } else { /* WALL_CYLINDER_INSIDE */
        real h = v3_dot(d, nw), len = wr[W_HEIGHT];
        vec3 radial = v3_sub(d, v3_scale(nw, h));
        real rho2 = v3_dot(radial, radial);
        if (rho2 > (real)0) {
            real rho = dem_sqrt(rho2);
            real q = rho - wr[W_RADIUS]; /* radial distance from the bore's surface (negative: inside the bore) */
            if (!(len > (real)0) || (h >= (real)0 && h <= len && q <= (real)0)) { /* the side, seen from inside */
                g.delta = ri + rho - wr[W_RADIUS];
                g.active = g.delta > lo;
                g.n = v3_scale(radial, (real)-1 / rho);
            } else if (q <= (real)0) { /* in the bore beyond an end: the rim, a circle, touched as an edge */
                wall_edge_contact(&g, radial, rho, nw, q, h > len ? h - len : h, ri, reach); /* a: the way past the end */
            } else if (h > len) { /* outside the bore, above: the die's top face (the die table) */
                g.delta = ri - (h - len);
                g.active = g.delta > lo;
                g.n = nw;
            } else if (h < (real)0) { /* below: its bottom face */
                g.delta = ri + h;
                g.active = g.delta > lo;
                g.n = v3_scale(nw, (real)-1);
            } else { /* a centre inside the die's body: pushed back out the nearest way, like a plane's */
                real top = len - h;
                g.active = 1;
                if (q <= top && q <= h) {
                    g.delta = ri + q;
                    g.n = v3_scale(radial, (real)-1 / rho);
                } else if (top <= h) {
                    g.delta = ri + top;
                    g.n = nw;
                } else {
                    g.delta = ri + h;
                    g.n = v3_scale(nw, (real)-1);
                }
            }
        }
        /* a centre exactly on the axis cannot touch: the host rejects particles wider than the cylinder */
    }
    return g;
}

DEM_INLINE wall_geom wall_geometry(int type, DEM_CONST_GLOBAL real *wr, vec3 xi, real ri)
{
    return wall_geometry_gap(type, wr, xi, ri, (real)0);
}

/* Particle i against wall k: wall_geometry_gap, except that a particle riding on the wall (ride[i] bit k, with
 * DEM_EFFECT_RIDERS) does not touch it - a membrane's ring sits on its platen, and the platen's force is the
 * granulate's alone. gap: 0, or r_i for a contact that may hold across a gap (JKR adhesion, DEM_EFFECT_ADHESION: far
 * beyond any JKR release, nanometres, which the law decides: laws/thornton_ning.h). */
DEM_INLINE wall_geom wall_met_gap(unsigned fx, DEM_CONST_GLOBAL int *wall_int, DEM_CONST_GLOBAL real *wall_real,
                                  DEM_CONST_GLOBAL unsigned *ride, int i, int k, vec3 xi, real ri, real gap)
{
    wall_geom g = wall_geometry_gap(wall_int[k * WI_STRIDE + WI_TYPE], wall_real + k * W_STRIDE, xi, ri, gap);
    if ((fx & DEM_EFFECT_RIDERS) && ((ride[i] >> k) & 1u))
        g.active = 0;
    return g;
}

/* The plain contact: every wall loop (forces, stress, MC-strain) goes through here */
DEM_INLINE wall_geom wall_met(unsigned fx, DEM_CONST_GLOBAL int *wall_int, DEM_CONST_GLOBAL real *wall_real,
                              DEM_CONST_GLOBAL unsigned *ride, int i, int k, vec3 xi, real ri)
{
    return wall_met_gap(fx, wall_int, wall_real, ride, i, k, xi, ri, (real)0);
}

/* Contacts that hold across a gap (laws/thornton_ning.h): a pair's whole bond (PM_TN_SIGB) and JKR adhesion
 * (DEM_EFFECT_ADHESION, PM_TN_K), a pair's or a wall's, pull until the law lets go, which it says by its state
 * (negated) or by law_result.active. Every caller that meets such a contact - the forces (contact_forces.h,
 * wall_forces.h), the stress (particle_stress.h), the host's energies (host/physics/energy.c, by contact_held) -
 * extends the geometry through these two (the walls' sums, wall_block_kept, take a contact the forces kept), for a contact that touched in the previous step (touched) and whose state is > 0; the state and the pair
 * table are read only then (not on the path of every contact). pm: the pair table's row of the two materials. */
DEM_INLINE int contact_held(unsigned fx, int pair, DEM_CONST_GLOBAL real *pm)
{
    return (fx & DEM_EFFECT_THORNTON_NING) &&
           ((pair && pm[PM_TN_SIGB] > (real)0) || ((fx & DEM_EFFECT_ADHESION) && pm[PM_TN_K] > (real)0));
}

/* A pair out of reach of pair_geometry (g inactive) that holds: its geometry out to a gap of r_a + r_b (far beyond a
 * bond's stretch or a JKR release: the law decides). The pair table's row of a's and b's materials (mat[a], mat[b] of
 * nmat) is found only for such a pair. */
DEM_INLINE pair_geom pair_geometry_held(unsigned fx, pair_geom g, vec3 xa, real ra, vec3 xb, real rb, int touched,
                                        DEM_CONST_GLOBAL real *st, DEM_CONST_GLOBAL real *pairmat,
                                        DEM_CONST_GLOBAL int *mat, int nmat, int a, int b)
{
    if (!g.active && (fx & DEM_EFFECT_THORNTON_NING) && touched && *st > (real)0 &&
        contact_held(fx, 1, pairmat + PM_STRIDE * (mat[a] * nmat + mat[b])))
        g = pair_geometry_reach(xa, ra, xb, rb, (real)2);
    return g;
}

/* A wall contact out of reach of wall_met (g inactive) that holds (JKR adhesion; a wall keeps no bond across a gap,
 * laws/thornton_ning.h): its geometry out to a gap of r_i */
DEM_INLINE wall_geom wall_met_held(unsigned fx, wall_geom g, DEM_CONST_GLOBAL int *wall_int,
                                   DEM_CONST_GLOBAL real *wall_real, DEM_CONST_GLOBAL unsigned *ride, int i, int k,
                                   vec3 xi, real ri, int touched, DEM_CONST_GLOBAL real *st, DEM_CONST_GLOBAL real *pm)
{
    if (!g.active && (fx & DEM_EFFECT_ADHESION) && touched && *st > (real)0 && contact_held(fx, 0, pm))
        g = wall_met_gap(fx, wall_int, wall_real, ride, i, k, xi, ri, ri);
    return g;
}

#endif /* DEM_CONTACT_GEOMETRY_H */
