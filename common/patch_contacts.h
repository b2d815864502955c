/* patch_contacts.h - spheres touching a membrane's triangular patches (seed 001 section 2.5, Eq. 17, Table 1, Fig. 3):
 * the candidate rows, the contact forces and their sums, without atomics on reals.
 *
 * Who is what: a particle with patch triangles (vtri_start[p] < vtri_start[p+1], p its stable id) is a patch vertex;
 * every other particle is a sphere. The vertices' tables (tri, vtri_start, vtri_list) and the vertex rows (vlist)
 * name particles by stable id (sid[place]; a stable id's place is order[id]), so that they hold when the particles
 * are stored anew (host/core/reorder.c moves the per-particle rows with their particles and leaves the tables). With DEM_EFFECT_PATCHES a patch vertex touches no particle as a sphere (nbr_build leaves it
 * out of every row); spheres touch its triangles instead. Vertices still touch walls with their own radius.
 *
 * Rows, rebuilt with the neighbour rows (the same skin and trigger), from the same cell grid:
 *   - sphere i: the patch triangles t with dist(x_i, t) < 1.5 r_i + skin, ascending t (plist[i*maxp ...]): more
 *     than the radius, because a contact whose sphere has crossed the patch's plane holds until the centre is r_i
 *     past it and r_i from the triangle along it (patch_geometry), within sqrt(2) r_i < 1.5 r_i. (Measured on a
 *     closed sphere membrane of 627 grains squeezed to 100 kPa on the reference: 1.26 times the time with rows of
 *     r_i + skin; with 2 r_i, 1.66 times, most of it in the vertices' sums.) Found through the
 *     vertices in the grid: a point of t lies within the longest edge of t from each of t's vertices, so with every
 *     patch edge shorter than `reach` each vertex of a listed triangle is within 1.5 r_i + skin + reach of x_i, and
 *     the search looks at the cells within that distance. Between rebuilds no particle moves more than skin/2, so a
 *     triangle left out stays farther than 1.5 r_i: it cannot touch (as for the neighbour rows). The candidates
 *     that do not touch add nothing to any sum.
 *   - patch vertex v: the spheres s with |x_s - x_v| < 1.5 r_s + skin + reach, by ascending stable id (vlist[v*maxv
 *     ...]): a
 *     superset of the spheres whose rows hold one of v's triangles (same argument), the ones whose forces v gathers.
 *   A patch vertex also checks its triangles' edges against `reach` (FLAG_PATCH_REACH); the host then widens the
 *   reach and builds again, as it grows a row that overflowed (FLAG_PATCH_NEEDED, FLAG_VROW_NEEDED).
 *   A sphere's new row takes each triangle's tangential history and touching flag from the old row (binary search).
 *
 * Forces (patch_forces, one sphere per item): for each listed triangle the closest point p (patch.h) and, where
 * |x_i - p| < r_i, a contact with normal n = (x_i - p)/|x_i - p| and overlap d = r_i - |x_i - p| (or, once the
 * centre has crossed the patch's plane, along the patch's normal: patch_forces), unless another
 * touching triangle of the same sphere removes it (Table 1 as patch.h extends it, patch_beats; the sphere's touching
 * triangles are all in its row). The law is the run's (laws/laws.h: law_force; the multi-contact laws act there as
 * Hertz-Mindlin), its overlap through the barrier of patch_law_overlap, with the pair table entry of the sphere's and the triangle's first vertex's
 * materials, r* = r_i (a flat patch), the patch's inverse mass the barycentric mean of
 * its vertices' (w0/m_a + w1/m_b + w2/m_c: a pinned patch is a wall), the contact point's velocity on the patch
 * w0 v_a + w1 v_b + w2 v_c (Fig. 3), and the sphere's contact point at the lever r_i - d, as for walls. The sphere
 * adds its contacts in ascending triangle id after its particle and wall contacts; each contact leaves its force F
 * on the sphere and the weights w in a record (PK_*). A contact that starts where a neighbouring one ended takes its
 * tangential spring (patch_forces).
 * Sums (patch_gather, one patch vertex per item, after the contribution channel): vertex v adds -(w_c F) of each
 * touching record of its triangles, by ascending sphere stable id, then ascending triangle id. Each vertex's share is a
 * product of the record's bits, so the shares sum to -F up to the rounding of w0 + w1 + w2 = 1 (tests/test_patch.c
 * measures it); the sphere's F and the shares are the same numbers on every device.
 */
#ifndef DEM_PATCH_CONTACTS_H
#define DEM_PATCH_CONTACTS_H
#include "dem_kernels.h"
#include "vec3.h"
#include "dem_layout.h"
#include "../include/dem_effects.h"
#include "sorted_row.h"
#include "patch.h"
#include "laws/laws.h"

DEM_INLINE int patch_is_vertex(DEM_CONST_GLOBAL int *vtri_start, int p) { return vtri_start[p + 1] > vtri_start[p]; }

/* triangle t's vertex k: tri names it by stable id, x is read where it is stored */
#define PATCH_X(t, k) v3_load(x, order[tri[3 * (t) + (k)]])

DEM_INLINE patch_point patch_of(vec3 p, DEM_CONST_GLOBAL real *x, DEM_CONST_GLOBAL int *tri,
                                DEM_CONST_GLOBAL int *order, int t)
{
    return patch_closest(p, PATCH_X(t, 0), PATCH_X(t, 1), PATCH_X(t, 2));
}

/* Inserts key into the sorted row of count entries (capacity cap) unless it is there; returns the new count, which
 * goes on counting past the capacity (the entries beyond it are not stored). */
DEM_INLINE int patch_row_insert(DEM_GLOBAL int *row, int count, int cap, int key)
{
    int m = (count < cap ? count : cap) - 1;
    for (int q = 0; q <= m; q++)
        if (row[q] == key)
            return count;
    if (count >= cap && row[m] < key)
        return count + 1;
    if (count >= cap)
        m--;
    while (m >= 0 && row[m] > key) {
        row[m + 1] = row[m];
        m--;
    }
    row[m + 1] = key;
    return count + 1;
}

DEM_ITEM(patch_build)
{
    vec3 xi = v3_load(x, i);
    int c = cell_of[i];
    int cx = c % ncx, cy = (c / ncx) % ncy, cz = c / (ncx * ncy);
    int si = sid[i]; /* the tables of vertices (vtri_start, vtri_list, tri) are by stable id */
    int vertex = patch_is_vertex(vtri_start, si);
    real ri = radius[i], near = (real)1.5 * ri + skin; /* crossed contacts stay listed */
    real range = (real)1.5 * (vertex ? rmax : ri) + skin + reach; /* the cells to look at */
    int m = (int)(range * inv_cell) + 1, cnt = 0;
    if (vertex) { /* the triangles' edges against the reach */
        for (int q = vtri_start[si]; q < vtri_start[si + 1]; q++) {
            int t = vtri_list[q];
            for (int e = 0; e < 3; e++) {
                vec3 d = v3_sub(PATCH_X(t, e), PATCH_X(t, (e + 1) % 3));
                if (!(v3_dot(d, d) < reach * reach))
                    DEM_ATOMIC_MAX(&flags[FLAG_PATCH_REACH], 1);
            }
        }
    }
    DEM_GLOBAL int *row = vertex ? vlist + i * maxv : plist + i * maxp;
    int cap = vertex ? maxv : maxp;
    for (int z = cz - m > 0 ? cz - m : 0; z <= (cz + m < ncz ? cz + m : ncz - 1); z++)
        for (int y = cy - m > 0 ? cy - m : 0; y <= (cy + m < ncy ? cy + m : ncy - 1); y++)
            for (int xx = cx - m > 0 ? cx - m : 0; xx <= (cx + m < ncx ? cx + m : ncx - 1); xx++) {
                int cc = (z * ncy + y) * ncx + xx;
                for (int s = cell_start[cc]; s < cell_start[cc + 1]; s++) {
                    int j = cell_particles[s], sj = sid[j];
                    if (patch_is_vertex(vtri_start, sj) == vertex)
                        continue; /* spheres look for vertices, vertices for spheres */
                    int sph = vertex ? j : i, vtx = vertex ? i : j;
                    vec3 d = v3_sub(v3_load(x, sph), v3_load(x, vtx));
                    real cut = (real)1.5 * radius[sph] + skin + reach; /* the same expression from either side */
                    if (!(v3_dot(d, d) < cut * cut))
                        continue;
                    if (vertex) { /* the sphere's stable id: the vertex's sums go by it, wherever it is stored */
                        cnt = patch_row_insert(row, cnt, cap, sj);
                        continue;
                    }
                    for (int q = vtri_start[sj]; q < vtri_start[sj + 1]; q++) {
                        int t = vtri_list[q];
                        vec3 e = v3_sub(xi, patch_of(xi, x, tri, order, t).point);
                        if (v3_dot(e, e) < near * near)
                            cnt = patch_row_insert(row, cnt, cap, t);
                    }
                }
            }
    int stored = cnt < cap ? cnt : cap;
    if (vertex) {
        vcount[i] = stored;
        pcount[i] = 0;
        DEM_ATOMIC_MAX(&flags[FLAG_VROW_NEEDED], cnt);
        return;
    }
    pcount[i] = stored;
    vcount[i] = 0;
    DEM_ATOMIC_MAX(&flags[FLAG_PATCH_NEEDED], cnt);
    /* the history of the same triangle in the old row, or none */
    for (int k = 0; k < stored; k++) {
        int found = row_find(old_plist + i * old_maxp, old_pcount[i], row[k]);
        int t = found >= 0 ? old_ptouch[i * old_maxp + found] : 0;
        ptouch[i * maxp + k] = (unsigned char)t;
        if (fx & DEM_EFFECT_FRICTION)
            v3_store(phist, i * maxp + k, t ? v3_load(old_phist, i * old_maxp + found) : v3_zero());
    }
}

DEM_INLINE vec3 patch_normal(DEM_CONST_GLOBAL real *x, DEM_CONST_GLOBAL int *tri, DEM_CONST_GLOBAL int *order, int t)
{
    vec3 a = PATCH_X(t, 0);
    return v3_cross(v3_sub(PATCH_X(t, 1), a), v3_sub(PATCH_X(t, 2), a));
}

/* The side of the patch a contact's sphere is on (1 below, 0 above, -1 not known: a new contact starts on the side its
 * centre is on), from its flags (ptouch) of the previous step - kept while it touches, whether the selection kept it
 * or not - except next to a contact of the same sphere that had crossed its patch's plane (ref: that patch's normal
 * towards the side its sphere came from, the first such contact in the row; zero: none): a patch sharing a vertex
 * with it whose normal is within 60 degrees of ref's line takes the side ref points to, so that a sphere that crossed
 * one patch is on the same side of the next one it slides over (it was thrown through the next). Farther turned
 * patches (a fold) keep their own sides: taken over blindly, a neighbour's side threw spheres through the folds of a
 * crumpled membrane. */
DEM_INLINE int patch_side(unsigned flags, vec3 nrm, vec3 ref, int near_ref)
{
    if ((flags & (PATCH_CROSSED | PATCH_KNOWN)) != (PATCH_CROSSED | PATCH_KNOWN) && near_ref) {
        real c = v3_dot(nrm, ref);
        if ((real)4 * c * c >= v3_dot(nrm, nrm) * v3_dot(ref, ref) && c != (real)0)
            return c < (real)0;
    }
    return flags & PATCH_KNOWN ? (flags & PATCH_BELOW) != 0 : -1;
}

/* A sphere of radius ri at xi against triangle t */
typedef struct {
    patch_point pp; /* the closest point of the triangle (patch.h) */
    vec3 e;         /* xi - pp.point */
    real e2;        /* |e|^2: the distance patch_beats compares */
    vec3 nrm;       /* N */
    real h;         /* e . N, positive on the sphere's side */
    int below;      /* that side (patch_side) */
    int crossed;    /* the centre is on the patch's plane or past it: the contact pushes along +-N */
    int touch;      /* the sphere touches */
    int rank;       /* in the selection (patch_beats): patch_rank */
} patch_geom;

/* The sphere's crossed contact that orients its other contacts (patch_side), from the flags of the previous step:
 * *ref its patch's normal towards the side its sphere came from, its triangle's vertices in tref; 0 if none */
DEM_INLINE int patch_ref(int i, int cnt, int maxp, DEM_CONST_GLOBAL real *x, DEM_CONST_GLOBAL int *tri,
                         DEM_CONST_GLOBAL int *order, DEM_CONST_GLOBAL int *plist, DEM_GLOBAL dem_byte *ptouch, vec3 *ref, int *tref)
{
    for (int k = 0; k < cnt; k++) {
        unsigned f = ptouch[i * maxp + k];
        if ((f & (PATCH_CROSSED | PATCH_KNOWN)) == (PATCH_CROSSED | PATCH_KNOWN)) {
            int t = plist[i * maxp + k];
            *ref = v3_scale(patch_normal(x, tri, order, t), f & PATCH_BELOW ? (real)-1 : (real)1);
            tref[0] = tri[3 * t], tref[1] = tri[3 * t + 1], tref[2] = tri[3 * t + 2];
            return 1;
        }
    }
    *ref = v3_zero();
    tref[0] = tref[1] = tref[2] = -1;
    return 0;
}

/* Crossed: the sphere was on one side of the patch and its centre is now on the plane or past it, over the face (or
 * over its rim to the tie's precision: patch.h PATCH_TIE; a sphere pressed through the edge two patches share is in
 * neither's face by rounding) - or over an edge or a vertex if it had crossed already (flags & PATCH_CROSSED: a
 * sphere that crossed may leave the face's prism before it comes back). A crossed contact touches while the centre
 * is less than ri past the plane and less than ri from the triangle along it. Its rank in the selection is its
 * point's (patch_rank), as for any contact. ref, tref: patch_ref. */
DEM_INLINE patch_geom patch_geometry(vec3 xi, real ri, unsigned flags, vec3 ref, const int *tref,
                                     DEM_CONST_GLOBAL real *x, DEM_CONST_GLOBAL int *tri, DEM_CONST_GLOBAL int *order,
                                     int t)
{
    patch_geom g;
    g.pp = patch_of(xi, x, tri, order, t);
    g.e = v3_sub(xi, g.pp.point);
    g.e2 = v3_dot(g.e, g.e);
    g.rank = patch_rank(g.pp);
    g.nrm = patch_normal(x, tri, order, t);
    int tk[3] = {tri[3 * t], tri[3 * t + 1], tri[3 * t + 2]};
    g.below = patch_side(flags, g.nrm, ref, tref[0] >= 0 && patch_common(tk, tref) > 0);
    g.h = g.below == 1 ? -v3_dot(g.e, g.nrm) : v3_dot(g.e, g.nrm);
    g.crossed = 0;
    real n2 = v3_dot(g.nrm, g.nrm), lat2 = (real)0;
    if (g.below >= 0 && g.h <= (real)0 && n2 > (real)0) {
        vec3 lat = v3_sub(g.e, v3_scale(g.nrm, v3_dot(g.e, g.nrm) / n2));
        lat2 = v3_dot(lat, lat);
        g.crossed = g.pp.kind == PATCH_FACE || (flags & PATCH_CROSSED) ||
                    lat2 <= PATCH_TIE * PATCH_TIE * dem_sqrt(n2);
    }
    if (!g.crossed)
        g.touch = g.e2 < ri * ri && g.e2 > (real)0;
    else
        g.touch = lat2 < ri * ri && -g.h < ri * dem_sqrt(n2);
    return g;
}

/* The flags a touching contact leaves for the next step (PATCH_NEXT_*): a crossed one keeps its side; any other takes
 * the side its centre is on (a sphere may go round a membrane's rim or over a ridge), unless on the plane */
DEM_INLINE unsigned patch_next(patch_geom g)
{
    int side = g.below;
    if (!g.crossed) {
        real hraw = v3_dot(g.e, g.nrm);
        side = hraw < (real)0 ? 1 : hraw > (real)0 ? 0 : side;
    }
    return (side >= 0 ? PATCH_NEXT_KNOWN : 0u) | (side == 1 ? PATCH_NEXT_BELOW : 0u) |
           (g.crossed ? PATCH_NEXT_CROSSED : 0u);
}

/* The overlap the Hertz law is given for a geometric overlap d of a sphere of radius r on a patch: d itself up to
 * 0.8 r; beyond, a barrier that grows as 0.8 r + 0.2 r u / (1 - u), u = (d - 0.8 r) / (0.2 r), until u = 0.95
 * (d = 0.99 r, 4.6 r for the law), then on along its tangent (slope 400), so that the force and its slope are
 * continuous and the force grows without end. Hertz's law alone lets the centre reach the patch's plane at a
 * pressure of about 0.2 E* (an estimate: ~300 kPa for seed 001's rubber membrane; grains got out from ~270 kPa).
 * With the barrier, a closed sphere membrane of 627 grains at 1 MPa kept every centre inside, the nearest 0.012 r from the
 * membrane (tests/test_patch_contacts.c, test_one_megapascal; with u = 0.9 and slope 100 one came 0.01 r outside);
 * a sphere pressed further still is pushed back (crossed contacts, patch_geometry). Runs whose overlaps stay below
 * 0.8 r have Hertz's bits (seed 001's triaxial case 1, 3000 steps: the same state hash as before). By a hand estimate
 * the barrier's stiffest, at 4.6 r and slope 400, is about twice a glass-glass contact of the same spheres, within
 * the Rayleigh step. */
DEM_INLINE real patch_law_overlap(real d, real r)
{
    real db = (real)0.8 * r, span = r - db;
    if (!(d > db))
        return d;
    real u = (d - db) / span;
    if (u < (real)0.95)
        return db + span * u / ((real)1 - u);
    return db + span * (real)19 + (d - db - (real)0.95 * span) * (real)400;
}

/* Whether contact k of sphere i stays this step, and its geometry: it touches, and no other touching triangle of the
 * sphere removes it (Table 1 as patch.h extends it; the sphere's touching triangles are all in its row). A contact
 * that has crossed its patch's plane is removed only by another that has; it removes the edge and vertex contacts
 * of the patches around it that have not (their normal, from the edge to the centre, would push the sphere on
 * through). */
DEM_INLINE int patch_kept(int i, int k, int cnt, int maxp, vec3 xi, real ri, DEM_CONST_GLOBAL real *x,
                          DEM_CONST_GLOBAL int *tri, DEM_CONST_GLOBAL int *order, DEM_CONST_GLOBAL int *plist,
                          DEM_GLOBAL dem_byte *ptouch, vec3 ref, const int *tref, patch_geom *gk)
{
    int t = plist[i * maxp + k];
    *gk = patch_geometry(xi, ri, ptouch[i * maxp + k], ref, tref, x, tri, order, t);
    if (!gk->touch)
        return 0;
    if (gk->rank == PATCH_FACE)
        return 1;
    int tk[3] = {tri[3 * t], tri[3 * t + 1], tri[3 * t + 2]};
    for (int j = 0; j < cnt; j++) {
        if (j == k)
            continue;
        int u = plist[i * maxp + j];
        patch_geom gj = patch_geometry(xi, ri, ptouch[i * maxp + j], ref, tref, x, tri, order, u);
        if (!gj.touch || (gk->crossed && !gj.crossed))
            continue; /* a crossed contact is removed only by a crossed one */
        int tj[3] = {tri[3 * u], tri[3 * u + 1], tri[3 * u + 2]};
        if (gj.crossed && !gk->crossed && patch_common(tk, tj) > 0)
            return 0; /* at an edge or a vertex next to a crossed patch, its push alone */
        if (patch_beats(u, tj, gj.rank, gj.e2, t, tk, gk->rank, gk->e2))
            return 0;
    }
    return 1;
}

/* Three passes over the sphere's row; ptouch holds the flags of dem_layout.h (PATCH_*). 1: which contacts stay, and
 * every touching contact's side for the next step (patch_next). 2: the forces of those that stay; a contact that
 * starts on a triangle sharing a vertex with one that ended in this step (the sphere slid across an edge or a
 * vertex) takes that one's tangential spring - the first such in row order - so that the tangential spring of a
 * sphere moving across a membrane does not restart from zero at every crossing (it fell from 1.2 N to 0 where a
 * dragged sphere passed onto the next patch: tests/test_patch_contacts.c, test_spring_across_edges). 3: the flags of
 * the next step; ended contacts lose their history, and contacts that no longer touch their side.
 * The normal: from the closest point to the centre, n = e/|e| with overlap r - |e|, while the centre is on its side;
 * once it is on the plane or past it (crossed, patch_geometry), n = +-N/|N| towards the side it came from, overlap
 * r + its depth past the plane: the contact does not flip, and pushes the sphere back until it is wholly through or
 * has left the triangle's prism by a radius (Hertz's law alone lets spheres through seed 001's rubber membrane from
 * ~270 kPa). The law is Hertz's with the barrier of patch_law_overlap. */
DEM_ITEM(patch_forces)
{
    int cnt = pcount[i];
    if (cnt == 0)
        return;
    vec3 xi = v3_load(x, i), vi = v3_load(v, i), wi = v3_zero();
    if (fx & DEM_EFFECT_FRICTION)
        wi = v3_load(w, i);
    real ri = radius[i];
    vec3 fi = v3_load(force, i), ti = v3_zero(), ref;
    if (fx & DEM_EFFECT_FRICTION)
        ti = v3_load(torque, i);
    int tref[3];
    patch_ref(i, cnt, maxp, x, tri, order, plist, ptouch, &ref, tref);
    for (int k = 0; k < cnt; k++) { /* pass 1 */
        patch_geom gk;
        unsigned kept = patch_kept(i, k, cnt, maxp, xi, ri, x, tri, order, plist, ptouch, ref, tref, &gk) ? PATCH_KEPT : 0u;
        if (gk.touch)
            ptouch[i * maxp + k] = (unsigned char)(ptouch[i * maxp + k] | kept | patch_next(gk));
    }
    for (int k = 0; k < cnt; k++) { /* pass 2 */
        int slot = i * maxp + k, t = plist[slot];
        unsigned state = ptouch[slot];
        if (!(state & PATCH_KEPT))
            continue;
        patch_geom g = patch_geometry(xi, ri, state, ref, tref, x, tri, order, t);
        int a = order[tri[3 * t]], b = order[tri[3 * t + 1]], cc = order[tri[3 * t + 2]]; /* where they are stored */
        vec3 n;
        real delta;
        if (!g.crossed) {
            real dist = dem_sqrt(g.e2);
            n = v3_scale(g.e, (real)1 / dist);
            delta = ri - dist;
        } else { /* back towards the side it came from */
            real len = dem_sqrt(v3_dot(g.nrm, g.nrm));
            n = v3_scale(g.nrm, (g.below == 1 ? (real)-1 : (real)1) / len);
            delta = ri - g.h / len;
        }
        real law = patch_law_overlap(delta, ri);
        DEM_CONST_GLOBAL real *pm = pairmat + PM_STRIDE * (mat[i] * nmat + mat[a]);
        real invm_p = g.pp.w[0] * invmass[a] + g.pp.w[1] * invmass[b] + g.pp.w[2] * invmass[cc];
        real mstar = law_effective_mass(invmass[i], invm_p);
        real arm = ri - delta;
        vec3 vp = v3_add(v3_add(v3_scale(v3_load(v, a), g.pp.w[0]), v3_scale(v3_load(v, b), g.pp.w[1])),
                         v3_scale(v3_load(v, cc), g.pp.w[2]));
        vec3 vc = vi, h = v3_zero();
        if (fx & DEM_EFFECT_FRICTION) {
            vc = v3_add(vi, v3_cross(wi, v3_scale(n, -arm)));
            if (state & PATCH_TOUCHED) {
                h = v3_load(phist, slot);
            } else { /* a new contact: the spring of a neighbour that ended now, if any */
                int tk[3] = {tri[3 * t], tri[3 * t + 1], tri[3 * t + 2]};
                for (int j = 0; j < cnt; j++) {
                    int u = plist[i * maxp + j];
                    int tj[3] = {tri[3 * u], tri[3 * u + 1], tri[3 * u + 2]};
                    if ((ptouch[i * maxp + j] & (PATCH_TOUCHED | PATCH_KEPT)) == PATCH_TOUCHED &&
                        patch_common(tk, tj) > 0) {
                        h = v3_load(phist, i * maxp + j);
                        break;
                    }
                }
            }
        }
        law_in lc; /* the run's law at the patch's overlap (laws/laws.h); r* = r_i, as at a wall */
        lc.site = LAW_AT_PATCH;
        lc.a = lc.b = i, lc.ra = lc.rb = ri;
        lc.n = n, lc.delta = law, lc.rstar = ri, lc.mstar = mstar, lc.vrel = v3_sub(vc, vp), lc.hist = h, lc.dt = dt;
        lc.st = (real)0; /* no law with memory acts at patches (host/core/effects.c refuses them together) */
        lc.row_in = 0, lc.row_out = 0, lc.sums = 0, lc.energy = 0;
        lc.pm = lc.pmi = pm;
        law_ctx none;
        none.trace = none.invvol = none.mdr_part = pm, none.disp_a = none.disp_b = (real)0;
        law_result r = law_force(fx, lc, none);
        if (fx & DEM_EFFECT_FRICTION) {
            v3_store(phist, slot, r.hist);
            ti = v3_sub(ti, v3_scale(v3_cross(n, r.ft), arm));
        }
        DEM_GLOBAL real *rec = prec + slot * PK_STRIDE;
        rec[PK_FX] = r.force.x, rec[PK_FY] = r.force.y, rec[PK_FZ] = r.force.z;
        rec[PK_W0] = g.pp.w[0], rec[PK_W1] = g.pp.w[1], rec[PK_W2] = g.pp.w[2];
        fi = v3_add(fi, r.force);
    }
    for (int k = 0; k < cnt; k++) { /* pass 3 */
        int slot = i * maxp + k;
        unsigned state = ptouch[slot];
        if (!(state & PATCH_KEPT) && (state & PATCH_TOUCHED) && (fx & DEM_EFFECT_FRICTION))
            v3_store(phist, slot, v3_zero()); /* the contact ended: so does its history */
        unsigned next = (state & PATCH_KEPT ? PATCH_TOUCHED : 0u) | (state & PATCH_NEXT_KNOWN ? PATCH_KNOWN : 0u) |
                        (state & PATCH_NEXT_BELOW ? PATCH_BELOW : 0u) | (state & PATCH_NEXT_CROSSED ? PATCH_CROSSED : 0u);
        ptouch[slot] = (unsigned char)next;
    }
    v3_store(force, i, fi);
    if (fx & DEM_EFFECT_FRICTION)
        v3_store(torque, i, ti);
}

DEM_ITEM(patch_gather)
{
    int nv = vcount[i];
    if (nv == 0)
        return;
    vec3 f = v3_load(force, i);
    int si = sid[i];
    for (int q = 0; q < nv; q++) {
        int s = order[vlist[i * maxv + q]]; /* the row: stable ids, ascending */
        for (int p = vtri_start[si]; p < vtri_start[si + 1]; p++) {
            int t = vtri_list[p];
            int k = row_find(plist + s * maxp, pcount[s], t);
            if (k < 0 || !(ptouch[s * maxp + k] & PATCH_TOUCHED))
                continue;
            DEM_CONST_GLOBAL real *rec = prec + (s * maxp + k) * PK_STRIDE;
            int corner = tri[3 * t] == si ? 0 : tri[3 * t + 1] == si ? 1 : 2;
            f = v3_sub(f, v3_scale(v3(rec[PK_FX], rec[PK_FY], rec[PK_FZ]), rec[PK_W0 + corner]));
        }
    }
    v3_store(force, i, f);
}
#endif /* DEM_PATCH_CONTACTS_H */
