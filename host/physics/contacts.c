/* contacts.c - the contact network of the current state (dem_contacts_get): every touching particle pair and
 * particle-wall pair with the force the kernels computed, read from the device with one synchronisation and
 * assembled on the host in double. Pairs come from the records contact_pairs leaves (common/contact_forces.h: the
 * force on the lower id, numbered by the particle stored first: row_pair_of), walls from the per-particle wall forces
 * (common/wall_forces.h); geometry (overlap, normal, contact point) is recomputed from the positions as the kernels
 * define it. Order: pairs by (i, j), i < j, then particle-wall pairs by (particle, wall), in the ids of dem_start
 * however the particles are stored (host/core/reorder.c). */
#include "sim.h"
#include "dem_layout.h"
#include "sorted_row.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* splits f into its part along the unit n and the rest */
static void split(const double *f, const double *n, double *fn, double *ft)
{
    double a = f[0] * n[0] + f[1] * n[1] + f[2] * n[2];
    for (int d = 0; d < 3; d++) {
        fn[d] = a * n[d];
        ft[d] = f[d] - fn[d];
    }
}

int sim_contact_order(const void *a, const void *b)
{
    const dem_contact *p = a, *q = b;
    if (p->i != q->i)
        return (p->i > q->i) - (p->i < q->i);
    return p->j < 0 ? (p->j < q->j) - (p->j > q->j) : (p->j > q->j) - (p->j < q->j);
}

/* The device fields the network is assembled from, slices of one allocation (raw) read with one synchronisation */
enum { FX_, FCNT, FLIST, FSTART, FTOUCH, FREC, FMASK, FPF, FTRACE, FDISP, FWDISP, NF };
typedef struct {
    unsigned char *raw;
    const unsigned char *x, *rec, *pf, *tr, *disp, *wdisp;
    const int *cnt, *list, *start;
    const unsigned char *touch;
    const unsigned *mask;
    const int *sid; /* a pair is listed by its owner, the lower stable id (neighbor.h) */
    int n, nw, rs, mcs, mce;
} net_fields;

static int read_fields(dem_sim *s, net_fields *t)
{
    dem_core *c = DEM_CORE(s->be);
    dem_field f[NF] = {DEM_FIELD_X,          DEM_FIELD_NBR_COUNT,    DEM_FIELD_NBR_LIST,  DEM_FIELD_NBR_START,
                       DEM_FIELD_TOUCH,      DEM_FIELD_PAIR_RECORDS, DEM_FIELD_WALL_MASK, DEM_FIELD_WALL_PF,
                       DEM_FIELD_STRESS_TRACE, DEM_FIELD_MC_DISP,    DEM_FIELD_MC_WALL_DISP};
    size_t bytes[NF], total = 0;
    void *dst[NF];
    for (int k = 0; k < NF; k++) {
        dem_bufref r;
        if (dem_field_ref(c, f[k], &r, &bytes[k]))
            bytes[k] = 0;
        total += bytes[k] + 16;
    }
    if (!t->mcs)
        bytes[FTRACE] = 0;
    if (!t->mce)
        bytes[FDISP] = bytes[FWDISP] = 0;
    unsigned char *raw = malloc(total + 1);
    if (!raw)
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    size_t off = 0;
    for (int k = 0; k < NF; k++) {
        dst[k] = raw + off;
        off += bytes[k] + 16 - (bytes[k] % 16); /* aligned slices */
    }
    if (dem_stage_read_fields(s->ops, s->be, NF, f, dst, bytes)) {
        free(raw);
        return sim_fail(s, DEM_ERR_DEVICE, "%s: %s", s->ops->name, c->err);
    }
    t->raw = raw;
    t->x = dst[FX_], t->rec = dst[FREC], t->pf = dst[FPF], t->tr = dst[FTRACE], t->disp = dst[FDISP];
    t->wdisp = dst[FWDISP];
    t->cnt = dst[FCNT], t->list = dst[FLIST], t->start = dst[FSTART];
    t->touch = dst[FTOUCH];
    t->mask = dst[FMASK];
    return 0;
}

/* The touching pair p of i and j, j in slot k of i's row: the force of its record, the geometry of the positions */
static void pair_contact(const dem_sim *s, const net_fields *t, int i, int k, int j, int p, dem_contact *e)
{
    const unsigned char *x = t->x, *rec = t->rec, *tr = t->tr, *disp = t->disp;
    const int *cnt = t->cnt, *list = t->list, *start = t->start, *sid = t->sid;
    int rs = t->rs;
    size_t r0 = (size_t)p * PR_STRIDE;
    double F[3] = {sim_real_at(rec, r0 + PR_FX, rs), sim_real_at(rec, r0 + PR_FY, rs),
                   sim_real_at(rec, r0 + PR_FZ, rs)};
    double xi[3], xj[3], d2 = 0;
    for (int q = 0; q < 3; q++) {
        xi[q] = sim_real_at(x, 3 * (size_t)i + q, rs), xj[q] = sim_real_at(x, 3 * (size_t)j + q, rs);
        d2 += (xi[q] - xj[q]) * (xi[q] - xj[q]);
    }
    double dist = sqrt(d2), nrm[3];
    for (int q = 0; q < 3; q++) /* from j into i */
        nrm[q] = dist > 0 ? (xi[q] - xj[q]) / dist : (q == 2);
    e->i = i, e->j = j;
    e->overlap = s->radius[i] + s->radius[j] - dist;
    split(F, nrm, e->fn, e->ft);
    for (int q = 0; q < 3; q++)
        e->point[q] = xi[q] - nrm[q] * (s->radius[i] - 0.5 * e->overlap);
    if (t->mcs)
        e->extra[0] = sim_real_at(tr, (size_t)i, rs), e->extra[1] = sim_real_at(tr, (size_t)j, rs);
    if (t->mce) { /* D at i's slot of j and at j's slot of i */
        int kj = row_find_sid(list + start[j], cnt[j], sid, sid[i]);
        e->extra[0] = sim_real_at(disp, (size_t)start[i] + k, rs);
        e->extra[1] = kj >= 0 ? sim_real_at(disp, (size_t)start[j] + kj, rs) : 0;
    }
}

/* Particle i's contact with wall w: the force the wall forces kept, the geometry of the kernels */
static void wall_contact(const dem_sim *s, const net_fields *t, int i, int w, dem_contact *e)
{
    int n = t->n, nw = t->nw, rs = t->rs;
    const dem_wall *wl = &s->walls[w];
    const double *p = s->motion.pos[w];
    double xi[3], F[3], nrm[3];
    for (int q = 0; q < 3; q++) {
        xi[q] = sim_real_at(t->x, 3 * (size_t)i + q, rs);
        F[q] = sim_real_at(t->pf, 3 * ((size_t)w * n + i) + q, rs);
    }
    /* the kernels' geometry: a plane, a cylinder's side, a finite die's rim or faces; n into the particle (a JKR
     * contact, DEM_EFFECT_ADHESION, may touch across a gap: wall_forces.h) */
    double gap = (s->setup.effects & DEM_EFFECT_ADHESION) ? s->radius[i] : 0;
    e->overlap = sim_wall_overlap_gap(wl, p, xi, s->radius[i], gap, nrm);
    e->i = i, e->j = -1 - w;
    split(F, nrm, e->fn, e->ft);
    for (int q = 0; q < 3; q++)
        e->point[q] = xi[q] - nrm[q] * (s->radius[i] - e->overlap);
    if (t->mcs)
        e->extra[0] = e->extra[1] = sim_real_at(t->tr, (size_t)i, rs);
    if (t->mce)
        e->extra[0] = sim_real_at(t->wdisp, (size_t)i * nw + w, rs);
}

int dem_contacts_get(dem_sim *s, dem_contact **out, long *count, long *npairs)
{
    *out = NULL, *count = 0, *npairs = 0;
    if (!s->run.started)
        return sim_need_started(s);
    if ((s->setup.effects & DEM_EFFECT_WALLS) && s->nwalls > 0 && !(s->setup.effects & DEM_KEEP_WALL_FORCES))
        return sim_fail(s, DEM_ERR_STATE, "the contact network of a run with walls needs dem_config.contacts = 1 at "
                                          "dem_start (the wall forces per particle are kept only then)");
    int n = s->n, nw = s->nwalls;
    unsigned fx = s->setup.effects;
    net_fields t = {.n = n, .nw = nw, .rs = s->setup.real_size, .sid = s->setup.sid,
                    .mcs = (fx & DEM_EFFECT_MC_STRESS) != 0, .mce = (fx & DEM_EFFECT_MC_STRAIN) != 0};
    int err = read_fields(s, &t);
    if (err)
        return err;
    const int *cnt = t.cnt, *list = t.list, *start = t.start, *sid = t.sid;
    int *own = sim_own_starts(cnt, list, start, n);
    if (!own) {
        free(t.raw);
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    }
    long np = 0, nwc = 0;
    for (int i = 0; i < n; i++) {
        for (int k = 0; k < cnt[i]; k++)
            if (sid[list[start[i] + k]] > sid[i]) {
                int p = row_pair_of(cnt, list, start, own, sid, i, k);
                np += p >= 0 && t.touch[p];
            }
        for (int w = 0; w < nw; w++)
            nwc += (t.mask[i] >> w) & 1u;
    }
    dem_contact *cs = calloc((size_t)(np + nwc) + 1, sizeof *cs);
    if (!cs) {
        free(t.raw), free(own);
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    }
    long m = 0;
    for (int i = 0; i < n; i++) /* each owner's touching pairs; put in (i, j) order below */
        for (int k = 0; k < cnt[i]; k++) {
            int j = list[start[i] + k], p = sid[j] > sid[i] ? row_pair_of(cnt, list, start, own, sid, i, k) : -1;
            if (p >= 0 && t.touch[p])
                pair_contact(s, &t, i, k, j, p, &cs[m++]);
        }
    free(own);
    for (int i = 0; i < n; i++)
        for (int w = 0; w < nw; w++)
            if ((t.mask[i] >> w) & 1u)
                wall_contact(s, &t, i, w, &cs[m++]);
    free(t.raw);
    for (long k = 0; s->order.count && k < np + nwc; k++) { /* stored anew (host/core/reorder.c): the callers' ids */
        cs[k].i = sim_api(s, cs[k].i);
        if (cs[k].j >= 0)
            cs[k].j = sim_api(s, cs[k].j);
    }
    qsort(cs, (size_t)np, sizeof *cs, sim_contact_order); /* whatever the storage order */
    qsort(cs + np, (size_t)nwc, sizeof *cs, sim_contact_order);
    *out = cs, *count = np + nwc, *npairs = np;
    return 0;
}
