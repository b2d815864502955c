/* energy.c - energy bookkeeping on the host, in double precision, from the backend's current state.
 * Elastic: the run's contact law's energy per contact (common/laws/laws.h, law_energy, compiled here in double: for
 * Hertz-Mindlin and the multi-contact laws Hertz's 8/15 E* sqrt(r*) d^(5/2), the integral of Eq. 3's elastic part),
 * walls included, and k e^2 / 2 per spring (e its extension); the Mindlin tangential spring's energy is not counted
 * (zero when mu = 0). Each energy is the exact sum of its terms rounded once to double (common/exact_sum.h): the same
 * bits in any particle order or split of the particles (docs/design.md "Sums that do not depend on the
 * decomposition"). */

/* the energies' exact sums while they are added up */
enum { EN_KIN, EN_POT, EN_ELA, EN_COUNT };
#define DEM_REAL_SIZE 8
#include "laws/laws.h"
#include "sim.h"
#include "dem_layout.h"
#include "ref_kernels.h" /* the reference's patch overlaps */
#include "exact_sum.h"   /* every sum over particles, contacts and springs: exact, rounded once */
#include "sorted_row.h"  /* row_pair_of: a pair's number from its row slot */
#include "contact_geometry.h" /* contact_held: which contacts hold across a gap */
#include <math.h>
#include <stdlib.h>
#include <string.h>

static double pair_estar(const dem_sim *s, int a, int b)
{
    const dem_material *p = &s->mats[a], *q = &s->mats[b];
    return 1 / ((1 - p->poisson * p->poisson) / p->young + (1 - q->poisson * q->poisson) / q->young);
}

/* The pair-table row of materials a and b as the law reads it, in double: the run's row widened, E* from the
 * materials in double (an fp32 run's energies are not rounded through its float table) */
static void pair_row(const dem_sim *s, int a, int b, double *row)
{
    for (int q = 0; q < PM_STRIDE; q++)
        row[q] = sim_real_at(s->setup.pairmat, PM_STRIDE * (size_t)(a * s->nmat + b) + q, s->setup.real_size);
    row[PM_ESTAR] = pair_estar(s, a, b);
}

/* Everything a series row needs in one device synchronisation (positions, velocities, spins, rows, wall forces):
 * each blocking read costs a wake-up of the device's threads, and a series every step made thirteen of them. */
static int energy_of(dem_sim *s, dem_energy_t *en, double *wall_force, double *wall_normal);
static int energy_acc(dem_sim *s, dem_energy_t *en, exact_acc *acc, double *wall_force, double *wall_normal, int own);

/* The elastic energy of a patch contact of overlap d (radius r): the work of the force F(d) = law(barrier(d)) of
 * common/patch_contacts.h from 0 to d. The law's energy up to the barrier (0.8 r, as there), then Simpson's rule on
 * 256 intervals over the rest. */
static double patch_contact_energy(unsigned fx, const double *row, double r, double d)
{
    double db = 0.8 * r;
    if (!(d > db))
        return law_energy(fx, row, r, d, 0);
    const int m = 256;
    double sum = 0, step = (d - db) / m;
    for (int k = 0; k <= m; k++) {
        double law = dem_patch_law_f64(db + k * step, r);
        sum += law_elastic(fx, row, r, law, 0) * (k == 0 || k == m ? 1 : k % 2 ? 4 : 2);
    }
    return law_energy(fx, row, r, db, 0) + sum * step / 3;
}

/* Sphere-patch contacts: each touching slot of the patch rows (common/patch_contacts.h), its overlap from the
 * positions x (in storage order) and its side, and the work of its normal law (patch_contact_energy), added to the
 * exact sum acc; the triangles' vertices (stable ids) read where they are stored: any storage order */
static int patch_energy(dem_sim *s, const double *x, dem_energy_t *en, exact_acc *acc)
{
    int n = s->n, maxp = DEM_CORE(s->be)->maxp, e = 0;
    int *cnt = sim_buffer_get(s, BUF_PCOUNT, &e), *list = sim_buffer_get(s, BUF_PLIST, &e);
    unsigned char *touch = sim_buffer_get(s, BUF_PTOUCH, &e);
    for (int q = 0; !e && q < n; q++) {
        int i = sim_dev(s, q);
        for (int k = 0; k < cnt[i]; k++) {
            if (!(touch[(size_t)i * maxp + k] & PATCH_TOUCHED))
                continue;
            int t = list[(size_t)i * maxp + k];
            double tx[9];
            for (int v = 0; v < 3; v++)
                memcpy(tx + 3 * v, x + 3 * sim_dev(s, s->mesh.tri[3 * t + v]), sizeof(double) * 3);
            double d = dem_patch_overlap_f64(x + 3 * i, tx, touch[(size_t)i * maxp + k], s->radius[i]), row[PM_STRIDE];
            if (d > 0) {
                pair_row(s, s->mat[i], s->mat[sim_dev(s, s->mesh.tri[3 * t])], row);
                exact_add_double(&acc[EN_ELA], patch_contact_energy(s->setup.effects, row, s->radius[i], d));
            }
            en->patch_contacts++;
        }
    }
    free(cnt), free(list), free(touch);
    return e;
}

int dem_energy(dem_sim *s, dem_energy_t *en) { return energy_of(s, en, NULL, NULL); }

void sim_row_exact(const dem_sim *s, exact_acc acc[SE_STRIDE]) { memcpy(acc, s->row_acc, sizeof s->row_acc); }

/* ---- series rows (dem_sample) ---- */

/* Rows are summed on the device (common/series.h) unless a membrane's springs or patches add terms that only the
 * host computes. */
static int device_rows(const dem_sim *s) { return !(s->setup.effects & (DEM_EFFECT_SPRINGS | DEM_EFFECT_PATCHES)); }

/* what the host knows of the step just taken */
static void sample_begin(const dem_sim *s, dem_sample *o)
{
    memset(o, 0, sizeof *o);
    o->step = s->run.step;
    o->time = dem_time(s);
    o->mc = s->mc.stats;
    for (int w = 0; w < s->nwalls; w++)
        memcpy(o->wall_pos + 3 * w, s->motion.pos[w], sizeof(double) * 3);
}

/* Rows [0, count) of the ring into out[0..count): each row's per-particle terms summed exactly in storage order
 * (any order gives the same bits) and rounded once to double; its walls' sums as the step made them (in the run's
 * precision), widened. */
static void rows_from_ring(dem_sim *s, int count, const unsigned char *terms, const unsigned char *walls,
                           dem_sample *out)
{
    int rs = s->setup.real_size, nw = s->nwalls, n = s->n;
    const unsigned *ghost = s->setup.ghost; /* by place: a rank's ghosts are its owners' to count (part.c) */
    double one[SE_STRIDE];
    for (int r = 0; r < count; r++) {
        double t[SE_STRIDE];
        exact_acc *a = s->row_acc; /* kept: the last row's exact sums (sim_row_exact) */
        for (int q = 0; q < SE_STRIDE; q++)
            exact_clear(&a[q]);
        if (rs == 8) { /* the terms as they lie, without the copy through one[] */
            const double *row = (const double *)(terms + (size_t)r * n * SE_STRIDE * rs);
            for (size_t k = 0; k < (size_t)n * SE_STRIDE; k += SE_STRIDE)
                if (!ghost || !ghost[k / SE_STRIDE])
                    for (int q = 0; q < SE_STRIDE; q++)
                        exact_add_double(&a[q], row[k + q]);
        } else {
            for (int k = 0; k < n; k++) {
                if (ghost && ghost[k])
                    continue;
                sim_widen(terms + ((size_t)r * n + k) * SE_STRIDE * rs, one, SE_STRIDE, rs);
                for (int q = 0; q < SE_STRIDE; q++)
                    exact_add_double(&a[q], one[q]); /* a float widened: the same number */
            }
        }
        for (int q = 0; q < SE_STRIDE; q++)
            t[q] = exact_to_double(&a[q]);
        dem_energy_t *en = &out[r].energy;
        en->kinetic = t[SE_KIN];
        en->potential = t[SE_POT];
        en->elastic = t[SE_ELA];
        en->contacts = (long)t[SE_CON];
        en->wall_contacts = (long)t[SE_WCON];
        en->total = en->kinetic + en->elastic + en->potential;
        if (!nw || !(s->effects & DEM_EFFECT_WALLS))
            continue;
        double wr[WP_STRIDE * DEM_MAX_WALLS]; /* the row's walls (series_wall_row), widened */
        sim_widen(walls + (size_t)r * WP_STRIDE * nw * rs, wr, WP_STRIDE * (size_t)nw, rs);
        for (int k = 0; k < nw; k++) {
            for (int q = 0; q < 3; q++)
                out[r].wall_force[3 * k + q] = wr[k * WP_STRIDE + WP_FX + q];
            out[r].wall_normal[k] = wr[k * WP_STRIDE + WP_FN];
        }
    }
}


int dem_step_sampled(dem_sim *s, long nsteps, const unsigned char *want, dem_sample *rows)
{
    long nrows = 0, last = -1;
    for (long k = 0; want && k < nsteps; k++)
        if (want[k])
            nrows++, last = k;
    if (nrows && !rows)
        return sim_fail(s, DEM_ERR_ARG, "dem_step_sampled: %ld samples and no rows to take them", nrows);
    if (s->split_started)
        return s->split_ops->step(s, nsteps, want, rows);
    if (!s->run.started)
        return sim_need_started(s);
    int dev = device_rows(s), cap = DEM_CORE(s->be)->series_rows, held = 0, e = 0;
    dem_sample *o = rows;
    for (long k = 0; !e && k < nsteps; k++) {
        int wk = want && want[k];
        /* on the device a sampled step writes its row itself; the host's samples need the walls' sums */
        if ((e = sim_step_once(s, (wk && !dev) || k == nsteps - 1, wk && dev ? held : -1)) || !wk)
            continue;
        sample_begin(s, o);
        if (!dev)
            e = energy_of(s, &o->energy, o->wall_force, o->wall_normal);
        else if (++held == cap || k == last) {
            const void *terms, *walls;
            if (dem_stage_series_map(s->ops, s->be, held, &terms, &walls))
                e = sim_fail(s, DEM_ERR_DEVICE, "%s: %s", s->ops->name, DEM_CORE(s->be)->err);
            else {
                rows_from_ring(s, held, terms, walls, o - (held - 1));
                if (dem_stage_series_unmap(s->ops, s->be, terms, walls))
                    e = sim_fail(s, DEM_ERR_DEVICE, "%s: %s", s->ops->name, DEM_CORE(s->be)->err);
            }
            held = 0;
        }
        o++;
    }
    return e;
}

int dem_sample_get(dem_sim *s, dem_sample *out)
{
    if (s->split_started)
        return s->split_ops->sample(s, out);
    sample_begin(s, out);
    return energy_of(s, &out->energy, out->wall_force, out->wall_normal);
}

int sim_sample_own(dem_sim *s, dem_sample *out, exact_acc acc[SE_STRIDE])
{
    sample_begin(s, out);
    exact_acc en[EN_COUNT];
    int e = energy_acc(s, &out->energy, en, out->wall_force, out->wall_normal, 1);
    for (int q = 0; q < SE_STRIDE; q++)
        exact_clear(&acc[q]);
    acc[SE_KIN] = en[EN_KIN], acc[SE_POT] = en[EN_POT], acc[SE_ELA] = en[EN_ELA];
    exact_add_double(&acc[SE_CON], (double)out->energy.contacts);
    exact_add_double(&acc[SE_WCON], (double)out->energy.wall_contacts);
    return e;
}

/* The state energy_of reads, widened to double in the simulation's scratch block: positions, velocities, spins and
 * the neighbour lists */
typedef struct {
    double *x, *v, *w;
    int *cnt, *start, *list;
    /* a law with memory (laws/law.h): the pairs' states by pair number (neighbor.h), where each particle's hosted
     * pairs start in that numbering, the particle-wall slots' states and MDR's particle rows; zero otherwise */
    sim_law_rows lr;
} host_state;

/* reads hs (and the walls' forces where asked) in one device synchronisation, into one scratch block kept in the
 * simulation (a series every step allocated and freed it every step) */
static int read_state(dem_sim *s, host_state *hs, double *wall_force, double *wall_normal)
{
    int n = s->n, rs = s->setup.real_size;
    size_t n3 = 3 * (size_t)n, lb = dem_field_bytes(s, DEM_FIELD_NBR_LIST);
    size_t need = 3 * n3 * sizeof(double) + sizeof(int) * (2 * (size_t)n + 1) + lb + 8 + 3 * n3 * (size_t)rs +
                  4 * DEM_MAX_WALLS * (size_t)rs + 64;
    if (need > s->scratch.bytes) {
        free(s->scratch.buf);
        s->scratch.buf = malloc(need);
        s->scratch.bytes = s->scratch.buf ? need : 0;
    }
    if (!s->scratch.buf)
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    hs->x = (double *)s->scratch.buf, hs->v = hs->x + n3, hs->w = hs->v + n3;
    hs->cnt = (int *)(hs->w + n3), hs->start = hs->cnt + n, hs->list = hs->start + n + 1;
    size_t off = (size_t)((unsigned char *)hs->list + lb - (unsigned char *)s->scratch.buf);
    unsigned char *raw = (unsigned char *)s->scratch.buf + (off + 7) / 8 * 8; /* the reals aligned */
    unsigned char *wraw = raw + 3 * n3 * rs;
    dem_field f[8] = {DEM_FIELD_X,         DEM_FIELD_V,        DEM_FIELD_W,          DEM_FIELD_NBR_COUNT,
                      DEM_FIELD_NBR_START, DEM_FIELD_NBR_LIST, DEM_FIELD_WALL_FORCE, DEM_FIELD_WALL_NORMAL_FORCE};
    void *dst[8] = {raw, raw + n3 * rs, raw + 2 * n3 * rs, hs->cnt, hs->start, hs->list, wraw,
                    wraw + 3 * (size_t)s->nwalls * rs};
    size_t bytes[8] = {n3 * rs, n3 * rs, n3 * rs, sizeof(int) * n, sizeof(int) * (n + 1), lb,
                       3 * (size_t)s->nwalls * rs, (size_t)s->nwalls * rs};
    if (dem_stage_read_fields(s->ops, s->be, wall_force && s->nwalls ? 8 : 6, f, dst, bytes))
        return sim_fail(s, DEM_ERR_DEVICE, "%s: %s", s->ops->name, DEM_CORE(s->be)->err);
    sim_widen(raw, hs->x, n3, rs);
    sim_widen(raw + n3 * rs, hs->v, n3, rs);
    sim_widen(raw + 2 * n3 * rs, hs->w, n3, rs);
    if (wall_force)
        sim_widen(raw + 3 * n3 * rs, wall_force, 3 * (size_t)s->nwalls, rs);
    if (wall_normal)
        sim_widen(raw + 3 * n3 * rs + 3 * (size_t)s->nwalls * rs, wall_normal, (size_t)s->nwalls, rs);
    return 0;
}

/* The law states of a law with memory, widened (sim.h sim_law_rows); the pairs' only where the pair touched in the
 * last step (a stale state of a pair that parted is not read by the law either) */
int sim_law_rows_read(dem_sim *s, const int *cnt, const int *list, const int *start, sim_law_rows *lr)
{
    int e = 0, rs = s->setup.real_size;
    dem_core *c = DEM_CORE(s->be);
    unsigned fx = s->setup.effects;
    size_t pw = (size_t)DEM_LAW_PAIR_W(fx), ww = (size_t)DEM_LAW_WALL_W(fx);
    size_t np = c->bytes[BUF_PAIR_LAW] / ((size_t)rs * pw), nw = c->bytes[BUF_WALL_LAW] / ((size_t)rs * ww);
    unsigned char *ps = sim_buffer_get(s, BUF_PAIR_LAW, &e), *ws = sim_buffer_get(s, BUF_WALL_LAW, &e);
    unsigned char *touch = sim_buffer_get(s, BUF_TOUCH, &e);
    unsigned *mask = sim_buffer_get(s, BUF_WALL_MASK, &e);
    memset(lr, 0, sizeof *lr);
    lr->npairs = np;
    lr->pair_st = calloc(np * pw + 1, sizeof(double));
    lr->wall_st = calloc(nw * ww + 1, sizeof(double));
    if (fx & DEM_EFFECT_MDR) { /* the particles' rows, in storage order like the rest */
        unsigned char *mp = sim_buffer_get(s, BUF_MDR_PART, &e);
        lr->mdr = calloc((size_t)MDR_P_STRIDE * s->n + 1, sizeof(double));
        if (!e && lr->mdr)
            sim_widen(mp, lr->mdr, (size_t)MDR_P_STRIDE * s->n, rs);
        else if (!e)
            e = sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
        free(mp);
    }
    lr->own = e ? NULL : sim_own_starts(cnt, list, start, s->n);
    if (!e && (!lr->pair_st || !lr->wall_st || !lr->own))
        e = sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    for (size_t p = 0; !e && p < np; p++)
        if (touch[p])
            sim_widen(ps + p * pw * rs, lr->pair_st + p * pw, pw, rs);
    for (size_t q = 0; !e && s->nwalls && q < nw; q++)
        if ((mask[q / (size_t)s->nwalls] >> (q % (size_t)s->nwalls)) & 1u)
            sim_widen(ws + q * ww * rs, lr->wall_st + q * ww, ww, rs);
    free(ps), free(ws), free(touch), free(mask);
    return e;
}

void sim_law_rows_free(sim_law_rows *lr)
{
    free(lr->pair_st), free(lr->wall_st), free(lr->own), free(lr->mdr);
    memset(lr, 0, sizeof *lr);
}

/* adds particle i's kinetic energy (translation, then rotation) and its potential energy in gravity to acc */
static void add_motion_energy(const dem_sim *s, const host_state *hs, int i, exact_acc *acc)
{
    const double *x = hs->x, *v = hs->v, *w = hs->w;
    double m = sim_mass(s, i), I = sim_inertia(s, i);
    unsigned fl = s->pflags[i];
    double v2 = v[3 * i] * v[3 * i] + v[3 * i + 1] * v[3 * i + 1] + v[3 * i + 2] * v[3 * i + 2];
    double w2 = w[3 * i] * w[3 * i] + w[3 * i + 1] * w[3 * i + 1] + w[3 * i + 2] * w[3 * i + 2];
    if (!(fl & DEM_PARTICLE_FIXED)) {
        exact_add_double(&acc[EN_KIN], 0.5 * m * v2);
        if (s->effects & DEM_EFFECT_GRAVITY)
            exact_add_double(&acc[EN_POT], -(m * (s->gravity[0] * x[3 * i] + s->gravity[1] * x[3 * i + 1] +
                                                  s->gravity[2] * x[3 * i + 2])));
    }
    if (!(fl & (DEM_PARTICLE_FIXED | DEM_PARTICLE_NO_ROTATION)))
        exact_add_double(&acc[EN_KIN], 0.5 * I * w2);
}

/* adds the elastic energy of particle i's contacts to acc and counts them in en: its sphere pairs from their owner
 * (the lower stable id), then its walls */
static void add_contact_energy(const dem_sim *s, const host_state *hs, int i, dem_energy_t *en, exact_acc *acc)
{
    const double *x = hs->x;
    const int *sid = s->setup.sid; /* ascending stable id, each pair from its owner (neighbor.h): any storage order */
    unsigned fx = s->setup.effects;
    int mdr = (fx & DEM_EFFECT_MDR) != 0; /* MDR: the apparent radii, and each contact's energy from its row */
    double r = mdr ? hs->lr.mdr[MDR_P_STRIDE * i + 1] : s->radius[i];
    for (int k = 0; k < hs->cnt[i]; k++) {
        int j = hs->list[hs->start[i] + k];
        if (sid[j] < sid[i])
            continue;
        double rj = mdr ? hs->lr.mdr[MDR_P_STRIDE * j + 1] : s->radius[j];
        double d[3] = {x[3 * i] - x[3 * j], x[3 * i + 1] - x[3 * j + 1], x[3 * i + 2] - x[3 * j + 2]};
        double delta = r + rj - sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
        /* a bond or a JKR contact (laws/thornton_ning.h) holds across a gap until it lets go: its state (> 0) is kept
         * while it touches, and cleared when it ends (contact_forces.h; contact_geometry.h, pair_geometry_held) */
        int p = hs->lr.pair_st && (delta > 0 || (fx & DEM_EFFECT_THORNTON_NING))
                    ? row_pair_of(hs->cnt, hs->list, hs->start, hs->lr.own, sid, i, k) : -1;
        double st = p >= 0 ? hs->lr.pair_st[(size_t)p * DEM_LAW_PAIR_W(fx)] : 0, row[PM_STRIDE];
        if (delta > 0 || st > 0) /* (the table only for a contact that may hold) */
            pair_row(s, s->mat[i], s->mat[j], row);
        if (delta > 0 || (st > 0 && contact_held(fx, 1, row))) {
            double rs = r * rj / (r + rj);
            if (mdr && p >= 0) { /* side 0 is j, of the higher stable id (laws/mdr.h) */
                mdr_material m = mdr_material_of(row);
                mdr_particle p0 = mdr_particle_load(hs->lr.mdr + MDR_P_STRIDE * j);
                mdr_particle p1 = mdr_particle_load(hs->lr.mdr + MDR_P_STRIDE * i);
                exact_add_double(&acc[EN_ELA], mdr_pair_row_energy(&m, hs->lr.pair_st + (size_t)p * MDR_PAIR_STRIDE, &p0, &p1));
            } else if (!mdr)
                exact_add_double(&acc[EN_ELA], law_energy(fx, row, rs, delta, st));
            en->contacts++;
        }
    }
    for (int k = 0; k < s->nwalls; k++) {
        if (sim_rides_on(s, i, k)) /* a rider does not touch its wall (contact_geometry.h, wall_met) */
            continue;
        const dem_wall *wl = &s->walls[k];
        size_t slot = ((size_t)i * s->nwalls + k) * DEM_LAW_WALL_W(fx);
        /* a JKR contact (DEM_EFFECT_ADHESION) holds across a gap until it lets go, as a pair's: its state (the largest
         * contact radius) is > 0 while it touches and cleared when it ends (wall_forces.h) */
        double row[PM_STRIDE];
        pair_row(s, s->mat[i], wl->material, row);
        int held = hs->lr.wall_st && hs->lr.wall_st[slot] > 0 && contact_held(fx, 0, row); /* wall_met_held's test */
        double delta = sim_wall_overlap_gap(wl, s->motion.pos[k], x + 3 * i, r, held ? r : 0, NULL); /* the kernels' */
        if (delta > 0 || held) {
            if (mdr) {
                mdr_material m = mdr_material_of(row);
                mdr_particle p = mdr_particle_load(hs->lr.mdr + MDR_P_STRIDE * i);
                exact_add_double(&acc[EN_ELA], mdr_wall_row_energy(&m, hs->lr.wall_st + slot, &p));
            } else
                exact_add_double(&acc[EN_ELA], law_energy(fx, row, r, delta, hs->lr.wall_st ? hs->lr.wall_st[slot] : 0));
            en->wall_contacts++;
        }
    }
}

/* adds the springs' energy k (|rho| - rho0)^2 / 2 to acc, at positions x; ends by stable id */
static void add_spring_energy(const dem_sim *s, const double *x, exact_acc *acc)
{
    for (int k = 0; k < s->mesh.nsprings; k++) {
        int a = sim_dev(s, s->mesh.spring_ij[2 * k]), b = sim_dev(s, s->mesh.spring_ij[2 * k + 1]);
        double d2 = 0, r2 = 0, rest = s->mesh.spring_kr[3 * k + 1];
        for (int q = 0; q < 3; q++) {
            d2 += (x[3 * a + q] - x[3 * b + q]) * (x[3 * a + q] - x[3 * b + q]);
            r2 += (s->x[3 * a + q] - s->x[3 * b + q]) * (s->x[3 * a + q] - s->x[3 * b + q]);
        }
        double ext = sqrt(d2) - (rest < 0 ? sqrt(r2) : rest);
        exact_add_double(&acc[EN_ELA], 0.5 * s->mesh.spring_kr[3 * k] * ext * ext);
    }
}

/* The energies' exact sums into acc[EN_COUNT] and the contacts counted in en, over every particle, or (own) over
 * those not ghosts of a rank's part: its own particles' motion, the pairs whose lower stable id is its own (held with
 * their partners) and its own particles' walls. A part holds no membrane (part.c refuses them). */
static int energy_acc(dem_sim *s, dem_energy_t *en, exact_acc *acc, double *wall_force, double *wall_normal, int own)
{
    memset(en, 0, sizeof *en);
    for (int q = 0; q < EN_COUNT; q++)
        exact_clear(&acc[q]);
    if (!s->run.started)
        return sim_need_started(s);
    host_state hs = {0}; /* set by read_state where it succeeds */
    int e = read_state(s, &hs, wall_force, wall_normal);
    if (!e && (s->setup.effects & DEM_LAW_STATE_BITS))
        e = sim_law_rows_read(s, hs.cnt, hs.list, hs.start, &hs.lr);
    for (int i = 0; !e && i < s->n; i++) { /* storage order: exact sums, the same bits in any order */
        if (own && s->ghost && s->ghost[i]) /* by place, as rows_from_ring's */
            continue;
        add_motion_energy(s, &hs, i, acc);
        add_contact_energy(s, &hs, i, en, acc);
    }
    if (!e)
        add_spring_energy(s, hs.x, acc);
    if (!e && (s->setup.effects & DEM_EFFECT_PATCHES) && s->mesh.npatch)
        e = patch_energy(s, hs.x, en, acc);
    sim_law_rows_free(&hs.lr);
    return e;
}

static int energy_of(dem_sim *s, dem_energy_t *en, double *wall_force, double *wall_normal)
{
    exact_acc acc[EN_COUNT];
    int e = energy_acc(s, en, acc, wall_force, wall_normal, 0);
    en->kinetic = exact_to_double(&acc[EN_KIN]);
    en->potential = exact_to_double(&acc[EN_POT]);
    en->elastic = exact_to_double(&acc[EN_ELA]);
    en->total = en->kinetic + en->elastic + en->potential;
    return e;
}
