/* mc_strain.h - the strain-based multi-contact model of Brodu et al. (seed 000 section 3.1, Eq. 7-8): the field of
 * induced displacements (Eq. 7) and its iteration; the law itself (Eq. 8) is laws/mc_strain.h.
 *
 * Contact c of particle i sees, besides its own overlap d_c, the normal displacement that every other contact k of
 * the same particle induces at c (Eq. 7):
 *   d_k->c = -K f_k / d_kc [ (n_k.u_kc)(n_c.u_kc) + C1 n_k.n_c - C2 (n_k + u_kc).n_c / (1 + n_k.u_kc) ]
 * with K = gamma (1 + nu) / (2 pi E), C1 = 3 - 4 nu, C2 = 1 - 2 nu of particle i's material (PM_MCS_*, on the
 * diagonal of the pair table), f_k the elastic normal force of contact k, n the unit normal pointing INTO the
 * particle at a contact, u_kc the unit vector from contact point k to contact point c and d_kc their distance.
 * Contact points are those of the torques: x_i - (r_i - d/2) n for a particle pair, x_i - (r_i - d) n for a wall.
 * With inward normals two points on a sphere have n_k.u_kc >= 0, and two opposite contacts give
 * d_k->c = gamma (1 + nu)(3 - 2 nu) f_k / (2 pi E d_kc) > 0: squeezing a sphere at one pole deepens the other pole's
 * overlap, and (Poisson) the equator bulges out.
 * A pair contact feeds both particles' fields into the Hertz law (Eq. 8):
 *   f = 4/3 E* sqrt(r*) d_eff^(3/2),  d_eff = max(0, d_c + D_i,c + D_j,c),  D_i,c = sum_{k != c} d_k->c over i's
 * contacts (walls included), so f_ij = -f_ji still holds; a wall contact uses D_i,c alone. Damping and the
 * tangential stiffness follow d_eff; lever arms keep the geometric overlap. Only geometric overlaps are contacts,
 * unless DEM_MC_REACH is compiled in (LIGGGHTS' contact distance, dem_effects.h): then a pair whose centres are
 * closer than F (r_i + r_j), F = PM_MC_REACH, is an MC-strain contact too, with a negative geometric overlap d_c (a
 * gap) and its contact point at the middle of the gap; it receives displacements, and bears a force (and, with it,
 * induces displacements, and counts as touching) while d_c + D_i,c + D_j,c > 0. Its contact radius is taken as 0.
 *
 * f_k comes from the previous evaluation: the previous time step in the lagged scheme (published, one pass), or
 * the previous iteration when iterating (host/core/step_loop.c repeats mc_strain_disp + mc_strain_update until no force changes
 * by more than the relative tolerance, or the iteration cap). It is stored per pair (numbered like the records:
 * contacts.h row_pair: one real per pair, not one per row slot in both row sets) and per
 * particle-wall slot, carried across neighbour rebuilds and saved in checkpoints.
 *
 * Guards (the singular cases stay finite): d_kc is raised to the Hertz contact radius a_k = sqrt(r*_k d_k) of the
 * loading contact (the point-load field is meaningless inside the contact patch, and f_k / a_k ~ E* d_k stays
 * bounded as d_k -> 0); u_kc = 0 when the points coincide; 1 + n_k.u_kc is raised to MC_DENOM_MIN (it is >= 1 for
 * points on a sphere and can only fall below with overlaps beyond any physical range; since
 * |(n_k + u).n_c| <= sqrt(2 (1 + n_k.u)), the ratio stays <= sqrt(2 / MC_DENOM_MIN)).
 * Canonical order: D_i,c sums k over i's row in ascending partner id, then walls by index.
 */
#ifndef DEM_MC_STRAIN_H
#define DEM_MC_STRAIN_H
#include "dem_kernels.h"
#include "contacts.h"
#include "sorted_row.h"
#include "contact_geometry.h"
#include "laws/laws.h"

#define MC_DENOM_MIN ((real)0.1)
/* Contacts of one particle whose geometry mc_strain_disp keeps in private memory (computed once, not once per pair);
 * a particle with more takes the slower path that recomputes them. Both paths evaluate the same expressions on the
 * same inputs, so the result does not depend on which one ran. */
#ifndef MC_CACHE
#define MC_CACHE 16
#endif

typedef struct {
    int active;
    vec3 p;     /* contact point [m] */
    vec3 n;     /* unit normal into the particle */
    real delta; /* geometric overlap [m] */
    real rstar; /* effective radius [m] */
} mc_contact;

/* The pair geometry MC-strain works with: with DEM_MC_REACH, neighbours within the contact distance too (pm: any
 * pair-table entry, PM_MC_REACH is the same in all). */
DEM_INLINE pair_geom mc_pair_geometry(unsigned fx, vec3 xa, real ra, vec3 xb, real rb, DEM_CONST_GLOBAL real *pm)
{
    return (fx & DEM_MC_REACH) ? pair_geometry_reach(xa, ra, xb, rb, pm[PM_MC_REACH]) : pair_geometry(xa, ra, xb, rb);
}

/* Hertz contact radius sqrt(r* d) of a contact, 0 across a gap */
DEM_INLINE real mc_contact_radius(mc_contact m) { return m.delta > (real)0 ? dem_sqrt(m.rstar * m.delta) : (real)0; }

/* The geometry of one contact of particle i (contacts.h: a pair or a wall). */
DEM_INLINE mc_contact mc_contact_get(unsigned fx, int i, contact_ref r, vec3 xi, real ri, DEM_CONST_GLOBAL real *x,
                                     DEM_CONST_GLOBAL real *radius, DEM_CONST_GLOBAL int *wall_int,
                                     DEM_CONST_GLOBAL real *wall_real, DEM_CONST_GLOBAL unsigned *ride,
                                     DEM_CONST_GLOBAL real *pairmat)
{
    mc_contact m;
    if (r.kind != CONTACT_WALL) {
        int j = r.partner;
        pair_geom g = mc_pair_geometry(fx, xi, ri, v3_load(x, j), radius[j], pairmat);
        m.active = g.active;
        m.n = g.n;
        m.delta = g.delta;
        m.rstar = g.rstar;
        m.p = v3_sub(xi, v3_scale(g.n, ri - (real)0.5 * g.delta));
    } else {
        int k = r.partner;
        wall_geom g = wall_met(fx, wall_int, wall_real, ride, i, k, xi, ri);
        m.active = (fx & DEM_EFFECT_WALLS) ? g.active : 0;
        m.n = g.n;
        m.delta = g.delta;
        m.rstar = ri;
        m.p = v3_sub(xi, v3_scale(g.n, ri - g.delta));
    }
    return m;
}

/* Eq. 7: displacement at contact c induced by contact k carrying the elastic normal force fk (pmi: i's material),
 * from nku = n_k.u_kc, ncu = n_c.u_kc, nkc = n_k.n_c, the distance d of the two points, inv_d = 1/d (0 when d = 0)
 * and ak = sqrt(r*_k d_k); (n_k + u).n_c is evaluated as nkc + ncu. The pairs (k, c) and (c, k) share d, nkc and
 * the two dot products (u_ck = -u_kc, so their n.u change sign exactly): the geometry is computed once per pair.
 * With nu = 1/2, C2 = 0 and its term is skipped (x - 0 * y == x bit for bit, y being finite). */
DEM_INLINE real mc_strain_term(DEM_CONST_GLOBAL real *pmi, real nku, real ncu, real nkc, real ak, real fk, real d,
                               real inv_d)
{
    if (!(d > ak) && !(ak > (real)0))
        return (real)0;
    real inv = d > ak ? inv_d : (real)1 / ak; /* 1 / max(d_kc, a_k) */
    real br = nku * ncu + pmi[PM_MCS_C1] * nkc;
    real c2 = pmi[PM_MCS_C2];
    if (c2 != (real)0) {
        real den = (real)1 + nku;
        if (den < MC_DENOM_MIN)
            den = MC_DENOM_MIN;
        br = br - c2 * ((nkc + ncu) / den);
    }
    return -(pmi[PM_MCS_K] * fk * inv) * br;
}

/* Distance from contact point pk to pc, its inverse and the unit vector (zero when the points coincide). */
DEM_INLINE vec3 mc_direction(vec3 pk, vec3 pc, real *d, real *inv_d)
{
    vec3 dp = v3_sub(pc, pk);
    *d = dem_sqrt(v3_dot(dp, dp));
    *inv_d = *d > (real)0 ? (real)1 / *d : (real)0;
    return v3_scale(dp, *inv_d);
}

/* f_k of contact r, number c of particle i: per pair from fn (h: the row's slots before c whose partner is stored
 * after i, contacts.h row_pair) or per wall slot from wall_fn */
DEM_INLINE real mc_fn_of(int i, contact_ref r, int c, int h, int own, int in, DEM_CONST_GLOBAL int *in_pair,
                         DEM_CONST_GLOBAL real *fn, DEM_CONST_GLOBAL real *wall_fn)
{
    return r.kind == CONTACT_WALL ? wall_fn[r.slot] : fn[row_pair(i, r.partner, c, h, own, in, in_pair)];
}

/* D_i,c for every contact c of particle i: row slots into disp[nbr_start[i] + c], walls into wall_disp[i*nwalls + k];
 * zero where c does not touch. f_k is read from fn (per pair) and wall_fn (walls). Each D_i,c sums k in canonical
 * order (ascending contact number), whichever path computes it. */
DEM_ITEM(mc_strain_disp)
{
    vec3 xi = v3_load(x, i);
    real ri = radius[i];
    int cnt = nbr_count[i], lower = row_lower(nbr_lower[i]), nw = (fx & DEM_EFFECT_WALLS) ? nwalls : 0;
    int row0 = nbr_start[i]; /* read once: the loops below write disp, which the compiler cannot tell apart */
    int total = contact_count(cnt, nw);
    DEM_CONST_GLOBAL real *pmi = pairmat + PM_STRIDE * (mat[i] * nmat + mat[i]);
    /* fast path: the touching contacts, gathered once (in canonical order), then each unordered pair once */
    vec3 cp[MC_CACHE], cn[MC_CACHE];
    real fc[MC_CACHE], ac[MC_CACHE], sum[MC_CACHE];
    int where[MC_CACHE], nc = 0, own = own_start[i], in = in_start[i], h = 0;
    for (int c = 0; c < total && nc <= MC_CACHE; c++) {
        contact_ref r = contact_at(i, c, cnt, lower, row0, nwalls, nbr_list);
        int hc = h; /* h as row_pair takes it for c, then counted on past c */
        h += r.kind != CONTACT_WALL && r.partner > i;
        mc_contact cc = mc_contact_get(fx, i, r, xi, ri, x, radius, wall_int, wall_real, ride, pairmat);
        contact_set(r, disp, wall_disp, (real)0);
        if (!cc.active)
            continue;
        if (nc == MC_CACHE) {
            nc++; /* too many: the slow path below */
            break;
        }
        cp[nc] = cc.p;
        cn[nc] = cc.n;
        fc[nc] = mc_fn_of(i, r, c, hc, own, in, in_pair, fn, wall_fn);
        ac[nc] = mc_contact_radius(cc);
        sum[nc] = (real)0;
        where[nc++] = c;
    }
    if (nc <= MC_CACHE) {
        /* a < b: b receives from a (k = a < c = b), then a from b; for a fixed contact the terms arrive in
         * ascending k, as in the canonical sum */
        for (int a = 0; a < nc; a++)
            for (int b = a + 1; b < nc; b++) {
                if (!(fc[a] > (real)0) && !(fc[b] > (real)0))
                    continue;
                real d, inv_d;
                vec3 u = mc_direction(cp[a], cp[b], &d, &inv_d); /* from a's point to b's */
                real nau = v3_dot(cn[a], u), nbu = v3_dot(cn[b], u), nab = v3_dot(cn[a], cn[b]);
                if (fc[a] > (real)0)
                    sum[b] = sum[b] + mc_strain_term(pmi, nau, nbu, nab, ac[a], fc[a], d, inv_d);
                if (fc[b] > (real)0)
                    sum[a] = sum[a] + mc_strain_term(pmi, -nbu, -nau, nab, ac[b], fc[b], d, inv_d);
            }
        for (int a = 0; a < nc; a++)
            contact_set(contact_at(i, where[a], cnt, lower, row0, nwalls, nbr_list), disp, wall_disp, sum[a]);
        return;
    }
    for (int c = 0; c < total; c++) { /* slow path: recompute each contact's geometry where needed */
        contact_ref rc = contact_at(i, c, cnt, lower, row0, nwalls, nbr_list);
        mc_contact cc = mc_contact_get(fx, i, rc, xi, ri, x, radius, wall_int, wall_real, ride, pairmat);
        real s = (real)0;
        if (cc.active)
            for (int k = 0, hk = 0; k < total; k++) {
                contact_ref rk = contact_at(i, k, cnt, lower, row0, nwalls, nbr_list);
                real fk = mc_fn_of(i, rk, k, hk, own, in, in_pair, fn, wall_fn);
                hk += rk.kind != CONTACT_WALL && rk.partner > i;
                if (k == c || !(fk > (real)0))
                    continue;
                mc_contact kk = mc_contact_get(fx, i, rk, xi, ri, x, radius, wall_int, wall_real, ride, pairmat);
                if (!kk.active)
                    continue;
                real d, inv_d;
                vec3 u = mc_direction(kk.p, cc.p, &d, &inv_d);
                s = s + mc_strain_term(pmi, v3_dot(kk.n, u), v3_dot(cc.n, u), v3_dot(kk.n, cc.n),
                                       mc_contact_radius(kk), fk, d, inv_d);
            }
        contact_set(rc, disp, wall_disp, s);
    }
}

/* The overlap the law sees (Eq. 8): mc_strain_overlap, laws/mc_strain.h */

/* One iteration: the elastic normal force of every contact of particle i from the current displacements, into
 * fn (the pairs i owns) and wall_fn; raises FLAG_MC_PENDING if one moved by more than tol (relative). A run holding
 * ghosts (DEM_HAS_GHOSTS: a rank's part of a split run) counts only the contacts of its own particles: a contact of
 * two ghosts, or a ghost's wall, is its owners' to count (their ranks' flags are merged, host/mpi/halo.c). */
DEM_INLINE int mc_changed(real fnew, real fold, real tol)
{
    real d = fnew > fold ? fnew - fold : fold - fnew;
    real m = fnew > fold ? fnew : fold;
    return d > tol * m;
}

DEM_ITEM(mc_strain_update)
{
    vec3 xi = v3_load(x, i);
    real ri = radius[i];
    int mi = mat[i], cnt = nbr_count[i], lower = row_lower(nbr_lower[i]), changed = 0, row0 = nbr_start[i];
    int nw = (fx & DEM_EFFECT_WALLS) ? nwalls : 0, own = own_start[i], in = in_start[i], h = 0;
    for (int c = 0; c < contact_count(cnt, nw); c++) { /* the pairs i owns, then its walls */
        contact_ref r = contact_at(i, c, cnt, lower, row0, nwalls, nbr_list);
        int hc = h;
        h += r.kind != CONTACT_WALL && r.partner > i;
        real f = (real)0;
        if (r.kind == CONTACT_OWNED) {
            int slot = r.slot, j = r.partner, m = row_find_sid(nbr_list + nbr_start[j], nbr_count[j], sid, sid[i]);
            if (m < 0)
                continue;
            m += nbr_start[j]; /* the partner's slot of the pair */
            pair_geom g = mc_pair_geometry(fx, xi, ri, v3_load(x, j), radius[j], pairmat);
            if (g.active)
                f = mc_strain_elastic(pairmat + PM_STRIDE * (mi * nmat + mat[j]), g.rstar,
                                      mc_strain_overlap(g.delta, disp[slot], disp[m]), (real)0);
            int p = row_pair(i, j, c, hc, own, in, in_pair);
            if (!((fx & DEM_HAS_GHOSTS) && ghost[i] && ghost[j]))
                changed |= mc_changed(f, fn[p], tol);
            fn[p] = f;
        } else if (r.kind == CONTACT_WALL) {
            int k = r.partner;
            wall_geom g = wall_met(fx, wall_int, wall_real, ride, i, k, xi, ri);
            if (g.active)
                f = mc_strain_elastic(pairmat + PM_STRIDE * (mi * nmat + wall_int[k * WI_STRIDE + WI_MATERIAL]), ri,
                                      mc_strain_overlap(g.delta, wall_disp[r.slot], (real)0), (real)0);
            if (!((fx & DEM_HAS_GHOSTS) && ghost[i]))
                changed |= mc_changed(f, wall_fn[r.slot], tol);
            wall_fn[r.slot] = f;
        }
    }
    if (changed)
        DEM_ATOMIC_MAX(&flags[FLAG_MC_PENDING], 1);
}
#endif /* DEM_MC_STRAIN_H */
