/* stability.c - how close the time step is to the explicit integration's stability bound at the current overlaps
 * (dem_stability_get).
 *
 * The Rayleigh time the scenes size dt by does not depend on how far the particles overlap, but a Hertz contact's
 * stiffness grows as sqrt(delta): a compact pressed to 50 MPa (scenes/tablet_3k.yaml, docs/tableting.md) heated up
 * at 0.2 Rayleigh times - its kinetic energy rose from rest to 3 % of its elastic energy within 50 us and stayed -
 * and came to rest at 0.05 and 0.07.
 *
 * The estimate, per particle i (fixed particles left out): each of its contacts c is a two-body oscillator with
 *   normal      omega_n,c^2 = k_n,c (1/m_i + 1/m_j)
 *   tangential  omega_t,c^2 = k_t,c (1/m_i + 1/m_j + a_i^2/I_i + a_j^2/I_j)   (the contact point's sliding and
 *                                                                           both spheres' rolling: a the lever arm)
 * with k_n, k_t the run's law's stiffnesses at the current overlap (common/laws/laws.h, law_stiffness, compiled here
 * in double; Hertz-Mindlin's k_n = 2 E* sqrt(r* d), k_t = 8 G* sqrt(r* d): laws/hertz_mindlin.h; a wall is immovable,
 * 1/m_j = a_j^2/I_j = 0, r* = r_i). The particle's frequency of each kind is the root of the sum over its contacts
 * (Gershgorin's bound for the particle's row of the stiffness matrix). The damping, c sqrt(k m*) per contact
 * (laws/hertz_mindlin.h), is a damping ratio zeta = c/2 in the normal mode and c/2 sqrt(kappa)
 * in the tangential one (kappa: the tangential mode's inverse mass over 1/m_i + 1/m_j, 3.5 for like spheres); the
 * largest of a particle's contacts counts. An explicit step of a damped oscillator is stable for
 * omega dt < 2 (sqrt(1 + zeta^2) - zeta) (2 undamped; 0.45 for the tangential mode at e = 0.1, whose c is 2.27). The
 * ratio reported is the largest omega dt over that bound, over the particles and both kinds: 1 at the bound, if the
 * estimate were exact.
 *
 * It is an estimate: the true highest mode of the packing lies below the Gershgorin sum, sliding contacts are
 * softer than k_t, and the multi-contact laws' normal stiffness is not Hertz's at the geometric overlap (taken here
 * as if it were). Measured against it (docs/design.md "The time step under compaction"): how the kinetic energy of a
 * packing at rest moved over the following steps, at several dt and restitutions -
 *   the 50 MPa compact of MCC (tablet_3k's, held still 0.4 ms): e = 0.1: ratio 3.06 and 2.47 heated up (kinetic 2.5 %
 *            of the elastic energy), 1.61 stayed stirred (2e-4, not decaying), 1.09 and 0.78 came to rest (4e-9);
 *            e = 0.5: 1.58 stirred (1e-5), 1.33 and 1.07 at rest; e = 0.9: 1.22 and 0.82 at rest;
 *   64 spheres of MCC on a simple cubic lattice pressed 10 % into each other (tests/test_stability.c): e = 0.1:
 *            stirred from 1.2, creeping up at 1.0 (1e-13 to 1e-11 J), at rest at 0.7; e = 0.5: stirred from 1.35,
 *            at rest to 1.2; e = 0.9: stirred at 2, at rest to 1.5.
 *   seed 000's 514 rubber spheres at 28 % strain (scenes/rubber_514.yaml, e = 0.7): 1.17, at rest.
 * The damped bound brings the restitutions closer together but not onto one line: strong damping is estimated a
 * little too kindly (one contact's damping ratio stands for the particle's, though a particle's contacts' damping
 * adds up; summing it instead spread the onsets over 1.5-5). Hence DEM_STABILITY_LIMIT 1.2 for the warning - a
 * heavily damped packing between 1 and 1.2 may creep up slowly - and DEM_STABILITY_TARGET 0.7 for the advice.
 * MDR: each contact's normal slope is the law's own (laws/mdr.h mdr_row_slope, from the contact's row, read as the
 * energies read it: sim_law_rows), where it is above the closed form; the closed form was 30 times low at a sphere
 * pushed 1.1 R_o into a wall, and the held box of tools/mdr_stiffness/jacobian.py measured omega dt 1.480 against
 * an estimate of 0.584 from it (1.546 now; docs/design.md "The time step under compaction").
 * Springs, patches and membranes are not counted. */
#define DEM_REAL_SIZE 8
#include "laws/laws.h"
#include "sim.h"
#include "dem_layout.h"
#include "sorted_row.h" /* row_pair_of: a pair's number from its row slot */
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* MDR's slope is the law's own, a difference over +-MDR_SLOPE_EPS of the overlap (laws/mdr.h mdr_row_slope) */
#define MDR_SLOPE_EPS 1e-6

/* the bound on omega dt of an explicit step with damping ratio zeta */
static double damped_bound(double zeta) { return 2 * (sqrt(1 + zeta * zeta) - zeta); }

typedef struct {
    double wn2, wt2, zn, zt; /* sums of the contacts' squared frequencies, largest damping ratios */
    int contacts;
} particle_modes;

/* adds contact c of particle i (mass terms: inverse masses and arm^2/I of both ends, j's zero for a wall) */
static void add_contact(particle_modes *pm, double kn, double kt, double inv_m, double inv_rot, double c)
{
    pm->wn2 += kn * inv_m;
    pm->wt2 += kt * (inv_m + inv_rot);
    double zn = 0.5 * c, zt = 0.5 * c * sqrt((inv_m + inv_rot) / inv_m);
    pm->zn = zn > pm->zn ? zn : pm->zn;
    pm->zt = zt > pm->zt ? zt : pm->zt;
    pm->contacts++;
}

/* the inverse of a mass or inertia v, 0 where v is not a positive finite number */
static double inv_of(double v) { return isfinite(v) && v > 0 ? 1 / v : 0; }

/* entry q of the run's pair table (as the kernels have it) for materials a and b, widened to double */
static double pair_at(const dem_sim *s, int a, int b, int q)
{
    return sim_real_at(s->setup.pairmat, PM_STRIDE * (size_t)(a * s->nmat + b) + q, s->setup.real_size);
}

/* the pair table's row of materials a and b widened to double for the law */
static void table_row(const dem_sim *s, int a, int b, double *row)
{
    for (int q = 0; q < PM_STRIDE; q++)
        row[q] = pair_at(s, a, b, q);
}

/* the positions x (widened to double) and the neighbour lists, read from the device in one synchronisation */
static int read_positions(dem_sim *s, unsigned char *raw, double *x, int *cnt, int *start, int *list, size_t lb)
{
    int n = s->n, rs = s->setup.real_size, e = 0;
    size_t n3 = 3 * (size_t)n;
    dem_field f[4] = {DEM_FIELD_X, DEM_FIELD_NBR_COUNT, DEM_FIELD_NBR_START, DEM_FIELD_NBR_LIST};
    void *dst[4] = {raw, cnt, start, list};
    size_t bytes[4] = {n3 * (size_t)rs, sizeof(int) * (size_t)n, sizeof(int) * ((size_t)n + 1), lb};
    if (dem_stage_read_fields(s->ops, s->be, 4, f, dst, bytes))
        e = sim_fail(s, DEM_ERR_DEVICE, "%s: %s", s->ops->name, DEM_CORE(s->be)->err);
    if (!e)
        sim_widen(raw, x, n3, rs);
    return e;
}

/* the damping factor c (zeta = c / 2) of a contact of materials a and b: the restitution's, PM_DAMP_N / sqrt(2 E*);
 * MDR's (M38, laws/mdr.h) is eta_d sqrt(2 m* E* (a_0 + a_1)) against a slope E* (a_0 + a_1) / 2: zeta = eta_d */
static double damping_of(const dem_sim *s, int a, int b)
{
    if (s->setup.effects & DEM_EFFECT_MDR)
        return 2 * pair_at(s, a, b, PM_MDR + 7);
    return pair_at(s, a, b, PM_DAMP_N) / sqrt(2 * pair_at(s, a, b, PM_ESTAR));
}

/* adds to pm the sphere contacts of particle i (inverse mass mi, rotational term roti), each pair from both ends:
 * every particle sums all of its contacts; rad: the radii (MDR's apparent ones, or the particles' own) */
static void add_sphere_contacts(const dem_sim *s, const double *x, const double *rad, const int *cnt, const int *start,
                                const int *list, const sim_law_rows *lr, double *pair_kn, int i, double mi,
                                double roti, particle_modes *pm)
{
    unsigned fx = s->setup.effects;
    int friction = (fx & DEM_EFFECT_FRICTION) != 0, damping = (fx & DEM_EFFECT_DAMPING) != 0;
    double ri = rad[i], row[PM_STRIDE];
    for (int k = 0; k < cnt[i]; k++) {
        int j = list[start[i] + k];
        double rj = rad[j], d[3];
        for (int q = 0; q < 3; q++)
            d[q] = x[3 * i + q] - x[3 * j + q];
        double delta = ri + rj - sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        if (!(delta > 0))
            continue;
        int a = s->mat[i], b = s->mat[j];
        double kn, kt;
        table_row(s, a, b, row);
        law_stiffness(fx, row, ri * rj / (ri + rj), delta, &kn, &kt);
        int p = lr->mdr ? row_pair_of(cnt, list, start, lr->own, s->setup.sid, i, k) : -1;
        if (p >= 0 && pair_kn[p] < 0) { /* MDR: the law's own slope from the pair's row, once a pair (its first end);
                                          side 0 is the higher stable id's (laws/mdr.h) */
            int hi = s->setup.sid[j] > s->setup.sid[i] ? j : i, lo = hi == j ? i : j;
            mdr_material m = mdr_material_of(row);
            mdr_particle p0 = mdr_particle_load(lr->mdr + MDR_P_STRIDE * hi);
            mdr_particle p1 = mdr_particle_load(lr->mdr + MDR_P_STRIDE * lo);
            pair_kn[p] = mdr_row_slope(&m, lr->pair_st + (size_t)p * DEM_LAW_PAIR_W(fx), 1, &p0, &p1, delta,
                                       MDR_SLOPE_EPS * delta);
        }
        if (p >= 0)
            kn = pair_kn[p] > kn ? pair_kn[p] : kn;
        int fixed_j = (s->pflags[j] & DEM_PARTICLE_FIXED) != 0;
        double mj = fixed_j ? 0 : inv_of(sim_mass(s, j));
        double rotj = fixed_j || (s->pflags[j] & DEM_PARTICLE_NO_ROTATION) ? 0 : inv_of(sim_inertia(s, j));
        double ai = ri - 0.5 * delta, aj = rj - 0.5 * delta;
        double c = damping ? damping_of(s, a, b) : 0;
        add_contact(pm, kn, friction ? kt : 0, mi + mj, ai * ai * roti + aj * aj * rotj, c);
    }
}

/* adds to pm the wall contacts of particle i (inverse mass mi, rotational term roti): a wall is immovable */
static void add_wall_contacts(const dem_sim *s, const double *x, const double *rad, const sim_law_rows *lr, int i,
                              double mi, double roti, particle_modes *pm)
{
    unsigned fx = s->setup.effects;
    int friction = (fx & DEM_EFFECT_FRICTION) != 0, damping = (fx & DEM_EFFECT_DAMPING) != 0;
    double ri = rad[i], row[PM_STRIDE];
    for (int w = 0; (fx & DEM_EFFECT_WALLS) && w < s->nwalls; w++) {
        if (sim_rides_on(s, i, w)) /* a rider does not touch its wall */
            continue;
        const dem_wall *wl = &s->walls[w];
        double delta = dem_wall_overlap(wl, s->motion.pos[w], x + 3 * i, ri, NULL); /* the kernels' geometry */
        if (!(delta > 0))
            continue;
        int a = s->mat[i], b = wl->material;
        double kn, kt;
        table_row(s, a, b, row);
        law_stiffness(fx, row, ri, delta, &kn, &kt);
        if (lr->mdr) { /* MDR: the law's own slope from the wall slot's row, its magnifier (M39) included */
            mdr_material m = mdr_material_of(row);
            mdr_particle p = mdr_particle_load(lr->mdr + MDR_P_STRIDE * i);
            double slope = mdr_row_slope(&m, lr->wall_st + ((size_t)i * s->nwalls + w) * DEM_LAW_WALL_W(fx), 0, &p, &p,
                                         delta, MDR_SLOPE_EPS * delta);
            kn = slope > kn ? slope : kn;
        }
        double ai = ri - delta; /* a wall contact's lever arm (wall_forces.h) */
        double c = damping ? damping_of(s, a, b) : 0;
        add_contact(pm, kn, friction ? kt : 0, mi, ai * ai * roti, c);
    }
}

/* the particle whose largest omega dt over its damped bound is the largest, into st (ratio, mode, particle) */
static void worst_particle(const dem_sim *s, const particle_modes *pm, dem_stability *st)
{
    int friction = (s->setup.effects & DEM_EFFECT_FRICTION) != 0;
    double dt = s->dt;
    for (int i = 0; i < s->n; i++) {
        if (!pm[i].contacts || (s->ghost && s->ghost[i])) /* a part's ghosts: their owners' (app/run_mpi.c) */
            continue;
        double rn = dt * sqrt(pm[i].wn2) / damped_bound(pm[i].zn);
        double rt = friction ? dt * sqrt(pm[i].wt2) / damped_bound(pm[i].zt) : 0;
        double r = rn > rt ? rn : rt;
        if (r > st->ratio || (r == st->ratio && r > 0 && sim_api(s, i) < st->particle)) { /* ties: the lowest id,
                                                                                             however stored */
            st->ratio = r;
            st->tangential = rt > rn;
            st->omega_dt = dt * sqrt(rt > rn ? pm[i].wt2 : pm[i].wn2);
            st->zeta = rt > rn ? pm[i].zt : pm[i].zn;
            st->particle = sim_api(s, i);
            st->contacts = pm[i].contacts;
        }
    }
}

int dem_stability_get(dem_sim *s, dem_stability *st)
{
    memset(st, 0, sizeof *st);
    st->particle = -1;
    st->dt_advice = INFINITY;
    if (!s->run.started)
        return sim_need_started(s);
    int n = s->n, rs = s->setup.real_size;
    size_t n3 = 3 * (size_t)n, lb = dem_field_bytes(s, DEM_FIELD_NBR_LIST);
    unsigned char *raw = malloc(n3 * (size_t)rs + sizeof(int) * (2 * (size_t)n + 1) + lb);
    double *x = malloc(sizeof(double) * n3);
    particle_modes *pm = calloc((size_t)n, sizeof *pm);
    if (!raw || !x || !pm) {
        free(raw), free(x), free(pm);
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    }
    int *cnt = (int *)(raw + n3 * (size_t)rs), *start = cnt + n, *list = start + n + 1;
    int e = read_positions(s, raw, x, cnt, start, list, lb);
    /* MDR: the law's rows (each contact's slope from its own state) and the apparent radii its contacts see, the
     * particles' rows' R (which mdr_begin also copies to RADIUS), in storage order like x */
    double *rad = NULL;
    sim_law_rows lr = {0};
    double *pair_kn = NULL; /* each pair's MDR slope, from the first of its ends to meet it */
    if (!e && (s->setup.effects & DEM_EFFECT_MDR)) {
        e = sim_law_rows_read(s, cnt, list, start, &lr);
        rad = e ? NULL : malloc(sizeof(double) * (size_t)(n ? n : 1));
        pair_kn = e ? NULL : malloc(sizeof(double) * (lr.npairs + 1));
        for (int i = 0; rad && i < n; i++)
            rad[i] = lr.mdr[MDR_P_STRIDE * (size_t)i + 1];
        for (size_t p = 0; pair_kn && p < lr.npairs; p++)
            pair_kn[p] = -1; /* not yet computed */
        if (!e && (!rad || !pair_kn))
            e = sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    }
    for (int i = 0; !e && i < n; i++) {
        if (s->pflags[i] & DEM_PARTICLE_FIXED)
            continue;
        double mi = inv_of(sim_mass(s, i));
        double roti = (s->pflags[i] & DEM_PARTICLE_NO_ROTATION) ? 0 : inv_of(sim_inertia(s, i));
        add_sphere_contacts(s, x, rad ? rad : s->radius, cnt, start, list, &lr, pair_kn, i, mi, roti, &pm[i]);
        add_wall_contacts(s, x, rad ? rad : s->radius, &lr, i, mi, roti, &pm[i]);
    }
    if (!e)
        worst_particle(s, pm, st);
    if (!e && st->ratio > 0)
        st->dt_advice = s->dt * DEM_STABILITY_TARGET / st->ratio;
    free(raw), free(x), free(pm), free(rad), free(pair_kn);
    sim_law_rows_free(&lr);
    return e;
}
