/* part.c - a run of part of a scene's particles, for a run split over MPI ranks (host/mpi/, app/run_mpi.c): the
 * particles a rank does not hold dropped before dem_start, and its ghosts (copies of other ranks' particles) marked,
 * so that the walls' sums count its own particles only (common/wall_forces.h) and so do the series rows' sums
 * (host/physics/energy.c). Nothing here changes a run that does not call it. */
#include "sim.h"
#include "dem_layout.h"
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The particles of src with keep[i] != 0, in their order, into s (s == src: in place, the arrays as they are; else
 * s's arrays are allocated here for them, its set-up's other fields already src's). Returns the count kept. */
static int keep_from(dem_sim *s, const dem_sim *src, const unsigned char *keep)
{
    int m = 0, in_place = s == src, src_n = src->n, src_srcn = src->order.source_n;
    for (int i = 0; i < src_n; i++)
        m += keep[i] != 0;
    if (!in_place) {
        size_t k = (size_t)(m ? m : 1);
        s->x = malloc(sizeof(double) * 3 * k), s->v = malloc(sizeof(double) * 3 * k);
        s->w = malloc(sizeof(double) * 3 * k), s->body = malloc(sizeof(double) * 2 * k);
        s->radius = malloc(sizeof(double) * k), s->mat = malloc(sizeof(int) * k), s->pflags = malloc(sizeof(unsigned) * k);
        s->order.source = src->order.source ? malloc(sizeof(int) * k) : NULL;
        s->cap = m;
        if (!s->x || !s->v || !s->w || !s->body || !s->radius || !s->mat || !s->pflags ||
            (src->order.source && !s->order.source))
            return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    }
    m = 0;
    for (int i = 0; i < src_n; i++) {
        if (!keep[i])
            continue;
        memmove(s->x + 3 * m, src->x + 3 * i, sizeof(double) * 3);
        memmove(s->v + 3 * m, src->v + 3 * i, sizeof(double) * 3);
        memmove(s->w + 3 * m, src->w + 3 * i, sizeof(double) * 3);
        memmove(s->body + 2 * m, src->body + 2 * i, sizeof(double) * 2);
        s->radius[m] = src->radius[i];
        s->mat[m] = src->mat[i];
        s->pflags[m] = src->pflags[i];
        if (src->order.source && i < src_srcn)
            s->order.source[m] = src->order.source[i];
        m++;
    }
    s->order.source_n = src->order.source && src_srcn > m ? m : src_srcn;
    s->n = m;
    return m;
}

/* Why s cannot be cut into parts (membranes and riders: their tables name particles by index), NULL where it can */
static const char *split_refused(const dem_sim *s)
{
    if (s->mesh.nsprings || s->mesh.ntri || s->mesh.nhinges || s->mesh.npatch || s->mesh.natt)
        return "a scene with membranes or riders cannot be split over ranks yet: run it in one process "
               "(docs/design.md \"Runs over MPI\")";
    return NULL;
}

dem_sim *sim_part_copy(const dem_sim *src, const unsigned char *keep, char *err, size_t len)
{
    err[0] = 0;
    if (src->run.started || src->be || src->nsetup_mem || src->motion.table || src->scratch.buf) {
        snprintf(err, len, "sim_part_copy: the run to copy has started");
        return NULL;
    }
    if (split_refused(src)) {
        snprintf(err, len, "%s", split_refused(src));
        return NULL;
    }
    dem_sim *s = malloc(sizeof *s);
    if (!s) {
        snprintf(err, len, "out of host memory");
        return NULL;
    }
    memcpy(s, src, sizeof *s); /* the set-up's values; the arrays it owns are its own below */
    s->x = s->v = s->w = s->radius = s->body = NULL;
    s->mat = NULL, s->pflags = NULL, s->ghost = NULL, s->order.source = NULL;
    s->setup_mem = NULL, s->nsetup_mem = s->setup_mem_cap = 0;
    s->mesh.spring_ij = NULL, s->mesh.spring_kr = NULL, s->mesh.tri = NULL, s->mesh.hinge = NULL;
    s->mesh.hinge_k = NULL, s->mesh.patch = NULL, s->mesh.att = NULL; /* none (refused above); the pressure stays */
    s->mesh.spring_cap = s->mesh.tri_cap = s->mesh.hinge_cap = s->mesh.patch_cap = s->mesh.att_cap = 0;
    s->halo_hook = NULL, s->halo_ctx = NULL;
    s->split_ops = NULL, s->split_ctx = NULL, s->split_started = 0; /* a part of a dem_create_mpi run steps alone */
    s->said_ids = NULL;
    if (!(s->whole_volume > 0)) /* until_density's volume: the whole scene's spheres, not the part's */
        s->whole_volume = sim_particle_volume(src);
    if (keep_from(s, src, keep) < 0) {
        snprintf(err, len, "%s", s->report.err);
        dem_destroy(s);
        return NULL;
    }
    return s;
}

/* Marks particle i a ghost where ghost[i] != 0 (NULL: none). Before dem_start. */
int sim_set_ghosts(dem_sim *s, const unsigned char *ghost)
{
    if (sim_not_started(s))
        return DEM_ERR_STATE;
    free(s->ghost);
    s->ghost = NULL;
    if (!ghost)
        return 0;
    if (!(s->ghost = malloc(s->n ? (size_t)s->n : 1)))
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    memcpy(s->ghost, ghost, (size_t)s->n);
    return 0;
}

int sim_halo_set(dem_sim *s, int nsend, const int *send, int nrecv, const int *recv)
{
    if (!s->run.started)
        return sim_fail(s, DEM_ERR_STATE, "sim_halo_set: dem_start first");
    if (nsend < 0 || nrecv < 0 || nsend > INT_MAX - nrecv || (size_t)nsend + (size_t)nrecv > INT_MAX / HALO_W)
        return sim_fail(s, DEM_ERR_ARG, "sim_halo_set: %d rows to send and %d to receive", nsend, nrecv);
    int total = nsend + nrecv, *idx = malloc(sizeof(int) * ((size_t)total + 1));
    if (!idx)
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    int e = 0;
    for (int k = 0; k < total && !e; k++) {
        idx[k] = k < nsend ? send[k] : recv[k - nsend];
        if (idx[k] < 0 || idx[k] >= s->n)
            e = sim_fail(s, DEM_ERR_ARG, "sim_halo_set: particle %d of a run of %d", idx[k], s->n);
    }
    dem_core *c = DEM_CORE(s->be);
    if (!e) {
        c->halo_cap = total;
        c->si[SI_NSEND] = nsend, c->si[SI_NRECV] = nrecv;
        if (s->ops->alloc(s->be, TABLE_ONE, 0, BUF_HALO_IDX, dem_buffer_bytes(c, BUF_HALO_IDX), total ? idx : NULL) ||
            s->ops->alloc(s->be, TABLE_ONE, 0, BUF_HALO_BUF, dem_buffer_bytes(c, BUF_HALO_BUF), NULL))
            e = sim_be_fail(s);
    }
    free(idx);
    return e;
}

/* The rows of width reals a kernel k packs (out: read to the host) or unpacks (in: written from it first) */
static int halo_out(dem_sim *s, dem_kernel_id k, int width, void *out)
{
    dem_core *c = DEM_CORE(s->be);
    size_t bytes = (size_t)width * (size_t)c->si[SI_NSEND] * (size_t)c->rs;
    return bytes && (dem_launch(s->ops, s->be, k) ||
                     s->ops->read(s->be, (dem_bufref){TABLE_ONE, BUF_HALO_BUF}, 0, out, bytes, 1))
               ? sim_be_fail(s)
               : 0;
}

static int halo_in(dem_sim *s, dem_kernel_id k, int width, const void *in)
{
    dem_core *c = DEM_CORE(s->be);
    size_t row = (size_t)width * (size_t)c->rs, bytes = row * (size_t)c->si[SI_NRECV];
    return bytes && (s->ops->write(s->be, (dem_bufref){TABLE_ONE, BUF_HALO_BUF}, row * (size_t)c->si[SI_NSEND], in,
                                   bytes, 1) ||
                     dem_launch(s->ops, s->be, k))
               ? sim_be_fail(s)
               : 0;
}

int sim_halo_pack(dem_sim *s, void *out) { return halo_out(s, K_halo_pack, HALO_W, out); }
int sim_halo_unpack(dem_sim *s, const void *in) { return halo_in(s, K_halo_unpack, HALO_W, in); }

/* the alias of the row kernels set to buffer id, width reals per particle; 0, or a refusal */
static int halo_rows(dem_sim *s, int id, int width)
{
    dem_core *c = DEM_CORE(s->be);
    if (width < 1 || width > HALO_W || c->bytes[id] < (size_t)width * (size_t)s->n * (size_t)c->rs)
        return sim_fail(s, DEM_ERR_ARG, "buffer %d: not %d reals per particle, or more than a message row's %d", id,
                        width, (int)HALO_W);
    c->alias[ALIAS_HALO_ROWS] = (dem_bufref){TABLE_ONE, id};
    c->si[SI_HALO_WIDTH] = width;
    return 0;
}

int sim_halo_pack_rows(dem_sim *s, int id, int width, void *out)
{
    int e = halo_rows(s, id, width);
    return e ? e : halo_out(s, K_halo_pack_rows, width, out);
}

int sim_halo_unpack_rows(dem_sim *s, int id, int width, const void *in)
{
    int e = halo_rows(s, id, width);
    return e ? e : halo_in(s, K_halo_unpack_rows, width, in);
}

/* The split's check of the moves on the device (common/halo.h): mark, or the largest distance an own particle has
 * moved since the mark and the largest move of the last step, from the blocks' largest values (a NaN kept) */
int sim_move_check(dem_sim *s, int mark, double out[2])
{
    dem_core *c = s->run.started ? DEM_CORE(s->be) : NULL;
    out[0] = out[1] = 0;
    if (!c || !(c->fx & DEM_HAS_GHOSTS))
        return sim_fail(s, DEM_ERR_STATE, "sim_move_check: a started part of a split run only");
    if (mark)
        return dem_launch(s->ops, s->be, K_move_mark) ? sim_be_fail(s) : 0;
    size_t nb = (size_t)c->si[SI_NBLOCKS_RED], bytes = 2 * nb * (size_t)c->rs;
    unsigned char *buf = malloc(bytes ? bytes : 1);
    if (!buf)
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    int e = bytes && (dem_launch(s->ops, s->be, K_move_check) ||
                      s->ops->read(s->be, (dem_bufref){TABLE_ONE, BUF_MOVE_MAX}, 0, buf, bytes, 1))
                ? sim_be_fail(s)
                : 0;
    for (size_t k = 0; !e && k < 2 * nb; k++) {
        double m = sim_real_at(buf, k, c->rs);
        out[k % 2] = m > out[k % 2] || m != m ? m : out[k % 2];
    }
    free(buf);
    return e;
}

void sim_run_record_get(const dem_sim *s, sim_run_record *r)
{
    memcpy(r->servo, s->motion.servo, sizeof r->servo);
    memcpy(r->servo_sum, s->motion.servo_sum, sizeof r->servo_sum);
    memcpy(r->servo_err, s->motion.servo_err, sizeof r->servo_err);
    memcpy(r->log, s->motion.stage_log, sizeof r->log);
    r->log_n = s->motion.stage_log_n;
    r->mc_first_capped = s->mc.stats.first_capped, r->mc_last_capped = s->mc.stats.last_capped;
    r->mdr_capped_step = s->report.mdr_capped_step, r->mdr_capped_particle = s->report.mdr_capped_particle;
}

void sim_run_record_set(dem_sim *s, const sim_run_record *r)
{
    memcpy(s->motion.servo, r->servo, sizeof r->servo);
    memcpy(s->motion.servo_sum, r->servo_sum, sizeof r->servo_sum);
    memcpy(s->motion.servo_err, r->servo_err, sizeof r->servo_err);
    memcpy(s->motion.stage_log, r->log, sizeof r->log);
    s->motion.stage_log_n = r->log_n;
    s->mc.stats.first_capped = r->mc_first_capped, s->mc.stats.last_capped = r->mc_last_capped;
    s->report.mdr_capped_step = r->mdr_capped_step, s->report.mdr_capped_particle = r->mdr_capped_particle;
}

int sim_mc_disp_get(dem_sim *s, long *count, int **pi, int **pj, double **d)
{
    *count = 0, *pi = *pj = NULL, *d = NULL;
    if (!s->run.started || !(s->setup.effects & DEM_EFFECT_MC_STRAIN))
        return sim_fail(s, DEM_ERR_STATE, "sim_mc_disp_get: a started MC-strain run");
    int e = 0, rs = s->setup.real_size;
    size_t b;
    int *cnt = sim_field_stored(s, DEM_FIELD_NBR_COUNT, &b, &e);
    int *list = sim_field_stored(s, DEM_FIELD_NBR_LIST, &b, &e);
    int *start = sim_field_stored(s, DEM_FIELD_NBR_START, &b, &e);
    unsigned char *mcd = sim_field_stored(s, DEM_FIELD_MC_DISP, &b, &e);
    long m = 0;
    for (int i = 0; !e && i < s->n; i++)
        m += cnt[i];
    if (!e) {
        *pi = malloc(sizeof(int) * (size_t)(m + 1)), *pj = malloc(sizeof(int) * (size_t)(m + 1));
        *d = malloc(sizeof(double) * (size_t)(m + 1));
        if (!*pi || !*pj || !*d)
            e = sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    }
    for (int i = 0; !e && i < s->n; i++)
        for (int k = 0; k < cnt[i]; k++) {
            size_t slot = (size_t)start[i] + (size_t)k;
            float f;
            (*pi)[*count] = sim_api(s, i), (*pj)[*count] = sim_api(s, list[slot]);
            if (rs == 8)
                memcpy(&(*d)[*count], mcd + slot * 8, 8);
            else
                memcpy(&f, mcd + slot * 4, 4), (*d)[*count] = f;
            (*count)++;
        }
    free(cnt), free(list), free(start), free(mcd);
    if (e) {
        free(*pi), free(*pj), free(*d);
        *pi = *pj = NULL, *d = NULL, *count = 0;
    }
    return e;
}

int sim_mc_disp_set(dem_sim *s, long count, const int *pi, const int *pj, const double *d)
{
    if (!s->run.started || !(s->setup.effects & DEM_EFFECT_MC_STRAIN))
        return sim_fail(s, DEM_ERR_STATE, "sim_mc_disp_set: a started MC-strain run");
    int e = 0, rs = s->setup.real_size;
    size_t b, bytes;
    int *cnt = sim_field_stored(s, DEM_FIELD_NBR_COUNT, &b, &e);
    int *list = sim_field_stored(s, DEM_FIELD_NBR_LIST, &b, &e);
    int *start = sim_field_stored(s, DEM_FIELD_NBR_START, &b, &e);
    unsigned char *mcd = sim_field_stored(s, DEM_FIELD_MC_DISP, &bytes, &e);
    for (long q = 0; !e && q < count; q++) {
        if (pi[q] < 0 || pi[q] >= s->n || pj[q] < 0 || pj[q] >= s->n) {
            e = sim_fail(s, DEM_ERR_ARG, "sim_mc_disp_set: no particle %d or %d", pi[q], pj[q]);
            break;
        }
        int i = sim_dev(s, pi[q]), j = sim_dev(s, pj[q]);
        for (int k = 0; k < cnt[i]; k++) /* its row is short: a scan */
            if (list[start[i] + k] == j) {
                size_t slot = (size_t)start[i] + (size_t)k;
                float f = (float)d[q]; /* an fp32 run's value, widened: the same number */
                if (rs == 8)
                    memcpy(mcd + slot * 8, &d[q], 8);
                else
                    memcpy(mcd + slot * 4, &f, 4);
                break;
            }
    }
    if (!e && bytes && dem_stage_write_field(s->ops, s->be, DEM_FIELD_MC_DISP, mcd, bytes))
        e = sim_be_fail(s);
    free(cnt), free(list), free(start), free(mcd);
    return e;
}

long sim_id_from(const long *ids, long n, long v)
{
    long lo = 0, hi = n;
    while (lo < hi) {
        long mid = lo + (hi - lo) / 2;
        if (ids[mid] < v)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}
