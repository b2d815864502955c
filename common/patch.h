/* patch.h - the geometry of a sphere touching a membrane's triangular patches (seed 001 section 2.5, Eq. 17 and
 * Table 1): where on a triangle a point is closest, classified face, edge or vertex, with the barycentric weights
 * that carry the contact's velocity from and its force to the three vertices (Fig. 3); and which of a sphere's
 * patch contacts are kept. The force pass that uses them is common/patch_contacts.h.
 *
 * Closest point: the Voronoi regions of the triangle's features, tested in order (Ericson, Real-Time Collision
 * Detection, section 5.1.5), with only + - * /. Edge k joins vertices k and k+1 (mod 3). Within one triangle the
 * weights follow the kind exactly - a vertex contact has the weights (1, 0, 0), an edge contact a zero weight for the
 * vertex off the edge - where Eq. 17 would test a cross product for zero in floating point. Between triangles it is
 * not exact: a point on the edge two triangles share may come out as a face point of both (each rounds its own
 * region tests); the selection treats such a point as the edge's (patch_rank).
 *
 * Selection (Table 1). The table orders the contacts of a sphere with two patches that share an edge: face over edge
 * over vertex, two faces both stay, and "rand" for two edges or two vertices; the text adds that of vertex contacts at
 * one mesh vertex one is selected. Read literally, only patches with a common edge compete, and a sphere resting on
 * a flat sheet near a mesh vertex then keeps a face contact and an edge contact of a patch that shares only that
 * vertex: twice the force (tests/test_patch_contacts.c found it). So the rule here extends the table to every pair
 * of a sphere's patches with a vertex in common: a face contact always stays and removes every edge or vertex
 * contact; of two edge or vertex contacts the nearer stays, and at the same distance (the same point: Table 1's
 * cases) the edge over the vertex and, for "rand", the lower patch id. Patches with no vertex in common do not
 * compete (two regions of the membrane). Each removal is by a contact that ranks strictly higher in one order
 * (faces, then distance, kind, id), so the best contact of a sphere always stays. Deterministic and independent of
 * the order the contacts are listed in, so the same on every device and after a restart; a random pick would need
 * a counter-based hash for that and would buy nothing physical (the candidates are at the same point). An edge
 * point computed from two triangles may differ in its last bit; then the nearer by that bit stays. A face point
 * within rounding of an edge or a vertex ranks as that edge or vertex (patch_rank): on a shared edge the two faces'
 * region tests round independently, and by rank the point is then one contact, not two.
 */
#ifndef DEM_PATCH_H
#define DEM_PATCH_H
#include "dem_real.h"
#include "vec3.h"

#define PATCH_FACE 2 /* the kinds, numbered by the feature's dimension */
#define PATCH_EDGE 1
#define PATCH_VERTEX 0

typedef struct {
    vec3 point;  /* closest point on the triangle */
    real w[3];   /* barycentric weights of point: w0 a + w1 b + w2 c */
    int kind;    /* PATCH_FACE, PATCH_EDGE, PATCH_VERTEX */
    int index;   /* edge k (vertices k, k+1 mod 3) or vertex k; 0 for a face */
} patch_point;

DEM_INLINE patch_point patch_feature(int kind, int index, real w0, real w1, real w2, vec3 point)
{
    patch_point r;
    r.kind = kind, r.index = index, r.w[0] = w0, r.w[1] = w1, r.w[2] = w2, r.point = point;
    return r;
}

DEM_INLINE patch_point patch_closest(vec3 p, vec3 a, vec3 b, vec3 c)
{
    vec3 ab = v3_sub(b, a), ac = v3_sub(c, a), ap = v3_sub(p, a);
    real d1 = v3_dot(ab, ap), d2 = v3_dot(ac, ap);
    if (d1 <= (real)0 && d2 <= (real)0)
        return patch_feature(PATCH_VERTEX, 0, (real)1, (real)0, (real)0, a);
    vec3 bp = v3_sub(p, b);
    real d3 = v3_dot(ab, bp), d4 = v3_dot(ac, bp);
    if (d3 >= (real)0 && d4 <= d3)
        return patch_feature(PATCH_VERTEX, 1, (real)0, (real)1, (real)0, b);
    real vc = d1 * d4 - d3 * d2;
    if (vc <= (real)0 && d1 >= (real)0 && d3 <= (real)0) {
        real v = d1 / (d1 - d3);
        return patch_feature(PATCH_EDGE, 0, (real)1 - v, v, (real)0, v3_add(a, v3_scale(ab, v)));
    }
    vec3 cp = v3_sub(p, c);
    real d5 = v3_dot(ab, cp), d6 = v3_dot(ac, cp);
    if (d6 >= (real)0 && d5 <= d6)
        return patch_feature(PATCH_VERTEX, 2, (real)0, (real)0, (real)1, c);
    real vb = d5 * d2 - d1 * d6;
    if (vb <= (real)0 && d2 >= (real)0 && d6 <= (real)0) {
        real w = d2 / (d2 - d6);
        return patch_feature(PATCH_EDGE, 2, (real)1 - w, (real)0, w, v3_add(a, v3_scale(ac, w)));
    }
    real va = d3 * d6 - d5 * d4;
    if (va <= (real)0 && d4 - d3 >= (real)0 && d5 - d6 >= (real)0) {
        real w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return patch_feature(PATCH_EDGE, 1, (real)0, (real)1 - w, w, v3_add(b, v3_scale(v3_sub(c, b), w)));
    }
    real sum = va + vb + vc;
    if (!(sum > (real)0)) /* a triangle of no area: its first vertex */
        return patch_feature(PATCH_VERTEX, 0, (real)1, (real)0, (real)0, a);
    real v = vb / sum, w = vc / sum;
    return patch_feature(PATCH_FACE, 0, (real)1 - v - w, v, w, v3_add(a, v3_add(v3_scale(ab, v), v3_scale(ac, w))));
}

/* The rank of a contact in the selection (patch_beats): its kind, except that a face point within PATCH_TIE of an
 * edge (one weight at most PATCH_TIE) ranks as an edge point and one within it of a vertex (two weights) as a vertex
 * point. A point on the edge two triangles share is a face point of either, both or neither of them by the rounding
 * of their region tests (patch_closest computes them from each triangle's own vertices, in its own order): two face
 * contacts would both stay, twice the force (a sphere sliding along a vertex row of a flat sheet felt up to 1.88x its
 * weight). Ranked as edge points they compete, and one stays: the nearer by the bits of their distances, then the
 * lower patch id (patch_beats). Each contact's rank is a function of its own triangle and point alone, so every
 * contact of a sphere is judged on the same numbers whichever contact asks: the decisions are consistent and one
 * contact always stays. PATCH_TIE (2^-40 in fp64, 2^-17 in fp32: 8192 and 128 times the unit roundoff) is above the
 * rounding of a weight: a face contact that near an edge (1e-12 of its length in fp64) is at the edge's point. */
#if DEM_REAL_SIZE == 8
#define PATCH_TIE ((real)9.094947017729282e-13)
#else
#define PATCH_TIE ((real)7.62939453125e-6)
#endif
DEM_INLINE int patch_rank(patch_point pp)
{
    if (pp.kind != PATCH_FACE)
        return pp.kind;
    int small = (pp.w[0] <= PATCH_TIE) + (pp.w[1] <= PATCH_TIE) + (pp.w[2] <= PATCH_TIE);
    return small == 0 ? PATCH_FACE : small == 1 ? PATCH_EDGE : PATCH_VERTEX;
}

/* The number of vertices two triangles (three vertex ids each) have in common */
DEM_INLINE int patch_common(const int *t, const int *u)
{
    int n = 0;
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 3; j++)
            n += t[i] == u[j];
    return n;
}

/* Whether contact j removes contact i of the same sphere (Table 1, extended; see the head of this file): ti, tj the
 * triangles' vertex ids, k their ranks (patch_rank), d2 the squared distances from the sphere's centre to their
 * closest points. Only a triangle with a vertex in common competes; a face contact is never removed and removes
 * every edge or vertex contact; of two edge or vertex contacts the nearer stays, at the same distance the edge,
 * then the lower patch id. */
DEM_INLINE int patch_beats(int idj, const int *tj, int kj, real d2j, int idi, const int *ti, int ki, real d2i)
{
    if (ki == PATCH_FACE || patch_common(ti, tj) == 0)
        return 0;
    if (kj == PATCH_FACE)
        return 1;
    if (d2j != d2i)
        return d2j < d2i;
    if (kj != ki)
        return kj > ki;
    return idj < idi;
}

/* Whether contact i of a sphere stays, among its n patch contacts: patch ids id[k], vertex ids tri[3k..3k+2],
 * ranks kind[k] (patch_rank) and squared distances d2[k]. */
DEM_INLINE int patch_keep(int i, int n, const int *id, const int *tri, const int *kind, const real *d2)
{
    for (int j = 0; j < n; j++)
        if (j != i && patch_beats(id[j], tri + 3 * j, kind[j], d2[j], id[i], tri + 3 * i, kind[i], d2[i]))
            return 0;
    return 1;
}
#endif /* DEM_PATCH_H */
