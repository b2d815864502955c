/* reorder.c - the particles stored anew along a Morton curve through their current positions, at a neighbour rebuild
 * (dem_config.reorder), and the particle ids of the library's calls kept those of dem_start.
 *
 * Why: every kernel reads its partners' data by where they are stored. A packing in another code's order, or one
 * that flows (a pour, a die fill), scatters those reads; the same bed of 1e5 spheres ran 1.4x faster stored in
 * spatial order than as poured (docs/design.md). dem_sort_particles orders the particles once, before the start, and
 * renumbers them; this keeps the order as the packing moves, and renumbers nothing the caller sees.
 *
 * Why the bits do not move: every sum follows the particles' stable ids (common/neighbor.h: rows sorted by them,
 * each pair owned by the lower, the walls' and the host's sums over particles in their order), never the storage
 * order. So a run gives the same bits whether, when and how often it is reordered (tests/test_particle_order.c).
 *
 * What moves, at the start of a rebuild (before the binning): every buffer the registry says moves with its particle
 * (common/dem_buffers.h, the move column) to the new places, among them each particle's start of its owned pairs in
 * the old pair list (OWN_START: old_pair_number reads the old pairs through it) and where it was stored when the rows
 * were built (OLD_SLOT), and the current rows with their partners renamed; the pair-sized arrays stay where they are,
 * numbered as they were, until pair_index carries them into the new rows. The host's own per-particle arrays follow,
 * so the host code that reads device buffers by storage place needs no map; the calls that take or return
 * particle ids (dem_get_raw, dem_state_*, dem_contacts_get, dem_particle_*) map through sid / order (sim_api,
 * sim_dev): the stable id of the particle at each place is its id of dem_start.
 * Membranes, patches and riders name particles by stable id in their tables (springs, triangles, hinges, the channel's
 * starts, the vertices' triangles, riders: common/springs.h, patch_contacts.h), which therefore stay as they are; the
 * kernels find a particle's place through ORDER. What is kept per particle for them moves here like any other
 * per-particle buffer: RIDE, HOLD and the spheres' patch rows with their history (PCOUNT, PLIST, PHIST, PTOUCH; the
 * patch build that follows in this rebuild carries them over). The vertex rows (VCOUNT, VLIST: stable ids) and the
 * patch records (PREC) are rewritten before they are read: the build, the forces of the next step. */
#include "sim.h"
#include <math.h>
#include <stdlib.h>
#include <string.h>

/* dst[k] = src[from[k]] for n items of `item` bytes */
static void gather(unsigned char *dst, const unsigned char *src, const int *from, int n, size_t item)
{
    for (int k = 0; k < n; k++)
        memcpy(dst + item * (size_t)k, src + item * (size_t)from[k], item);
}

/* The buffer's contents moved: item k of the new order from item from[k] of the old; groups of n items (wall-major
 * blocks, ring rows) each moved alike. */
static void move_items(unsigned char *buf, unsigned char *tmp, size_t bytes, const int *from, int n, size_t item)
{
    size_t group = item * (size_t)n;
    for (size_t g = 0; g + group <= bytes; g += group) {
        gather(tmp, buf + g, from, n, item);
        memcpy(buf + g, tmp, group);
    }
}

/* the distance between particles a and b of positions x */
static double spacing(const double *x, int a, int b)
{
    double d = 0;
    for (int q = 0; q < 3; q++)
        d += (x[3 * a + q] - x[3 * b + q]) * (x[3 * a + q] - x[3 * b + q]);
    return sqrt(d);
}

int sim_reorder_due(const dem_sim *s)
{
    return s->cfg.reorder > 0 && !s->order.hold && s->n > 1 && s->rows.rebuilds % s->cfg.reorder == 0;
}

static int device_fail(dem_sim *s) { return sim_fail(s, DEM_ERR_DEVICE, "%s: %s", s->ops->name, DEM_CORE(s->be)->err); }

/* Rows packed anew (dem_buffers.h DEM_ROWS: row i at start[i], cnt[i] long): row k of dst is row from[k] of src,
 * at nstart[k] (nstart: the scan of cnt in the new order, filled here); items of `item` bytes; with rename (ints: the
 * partners), each item x becomes rename[x]. Used to store the rows anew (move_rows) and to hand them to the callers
 * in their order (rows_to_api). */
static void pack_rows(unsigned char *dst, const unsigned char *src, size_t item, const int *cnt, const int *start,
                      const int *from, int n, int *nstart, const int *rename)
{
    nstart[0] = 0;
    for (int k = 0; k < n; k++) {
        nstart[k + 1] = nstart[k] + cnt[from[k]];
        memcpy(dst + item * (size_t)nstart[k], src + item * (size_t)start[from[k]], item * (size_t)cnt[from[k]]);
    }
    for (int q = 0; rename && q < nstart[n]; q++)
        ((int *)dst)[q] = rename[((int *)dst)[q]];
}

/* The current rows (dem_buffers.h DEM_ROWS: packed, row i at start[i]) in the new order: row k is the old row of
 * from[k], its partners renamed by to[]. buf and tmp hold at least the largest row buffer. (The values kept per pair
 * follow at the rebuild that comes next: pair_index finds each pair's old number through OLD_SLOT.) */
static int move_rows(dem_sim *s, const int *from, const int *to, unsigned char *buf, unsigned char *tmp)
{
    dem_core *c = DEM_CORE(s->be);
    int n = s->n, e = 0;
    int *cnt = malloc(sizeof(int) * (size_t)n), *start = malloc(sizeof(int) * ((size_t)n + 1));
    int *nstart = malloc(sizeof(int) * ((size_t)n + 1));
    dem_bufref rc = {TABLE_CUR, ROW_COUNT}, rst = {TABLE_CUR, ROW_START};
    if (!cnt || !start || !nstart)
        e = sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    else if (s->ops->read(s->be, rc, 0, cnt, sizeof(int) * (size_t)n, 1) ||
             s->ops->read(s->be, rst, 0, start, sizeof(int) * ((size_t)n + 1), 1))
        e = device_fail(s);
    for (int id = 0; !e && id < ROW__COUNT; id++) {
        size_t bytes = c->row_bytes[c->cur][id];
        if (!bytes || id == ROW_START)
            continue;
        dem_bufref r = {TABLE_CUR, id};
        if (s->ops->read(s->be, r, 0, buf, bytes, 1)) {
            e = device_fail(s);
            break;
        }
        if (id == ROW_COUNT)
            move_items(buf, tmp, bytes, from, n, sizeof(int));
        else { /* the partners: each row's run of slots to its new start, renamed */
            pack_rows(tmp, buf, sizeof(int), cnt, start, from, n, nstart, to);
            memcpy(buf, tmp, sizeof(int) * (size_t)nstart[n]);
        }
        if (s->ops->write(s->be, r, 0, buf, bytes, 1))
            e = device_fail(s);
    }
    if (!e && s->ops->write(s->be, rst, 0, nstart, sizeof(int) * ((size_t)n + 1), 1))
        e = device_fail(s);
    free(cnt), free(start), free(nstart);
    return e;
}

/* The new order: a Morton curve through the current positions (x, filled here from buf), from[k] the particle
 * that goes to place k and to[] its inverse; *same when the particles stay where they are. */
static int order_anew(dem_sim *s, unsigned char *buf, double *x, int *from, int *to, int *same)
{
    int n = s->n, rs = s->setup.real_size, finite = 1;
    *same = 1;
    if (s->ops->read(s->be, (dem_bufref){TABLE_ONE, BUF_X}, 0, buf, 3 * (size_t)n * rs, 1))
        return device_fail(s);
    for (int k = 0; k < 3 * n; k++) {
        x[k] = rs == 8 ? ((double *)buf)[k] : ((float *)buf)[k];
        finite &= isfinite(x[k]) != 0;
    }
    if (!finite) /* left as stored: the binning that follows reports the particle */
        return 0;
    /* Worth it only when the storage has become scattered: the mean distance between particles stored next to each
     * other (one pass over the positions) more than `gain` times what it was after the last look; then, more than
     * `gain` times what the new order gives (a Morton sort). A move cost 0.12 s at 1e5 particles on this project's
     * VM, some six rebuilds (docs/design.md). */
    double gain = s->cfg.reorder_gain > 0 ? s->cfg.reorder_gain : DEM_REORDER_GAIN, now = 0, anew = 0;
    for (int k = 0; k + 1 < n; k++)
        now += spacing(x, k, k + 1);
    if (gain > 1 && s->order.ref > 0 && !(now > gain * s->order.ref))
        return 0;
    if (sim_morton_order(x, n, from))
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    for (int k = 0; k < n; k++) {
        to[from[k]] = k;
        *same &= from[k] == k;
    }
    for (int k = 0; k + 1 < n; k++)
        anew += spacing(x, from[k], from[k + 1]);
    if (gain > 1 && !(now > gain * anew)) {
        *same = 1;
        s->order.ref = now; /* close enough: looked at again when it has spread `gain` times this */
    } else
        s->order.ref = anew;
    return 0;
}

/* Every device buffer the registry moves with its particles (common/dem_buffers.h, the move column) */
static int move_buffers(dem_sim *s, const int *from, unsigned char *buf, unsigned char *tmp)
{
    dem_core *c = DEM_CORE(s->be);
    for (int id = 0; id < BUF__COUNT; id++) {
        size_t item, bytes = c->bytes[id];
        if (dem_buffer_move(c, id, &item) == DEM_MOVE_STAY || !bytes || !item)
            continue;
        dem_bufref r = {TABLE_ONE, id};
        if (s->ops->read(s->be, r, 0, buf, bytes, 1))
            return device_fail(s);
        move_items(buf, tmp, bytes, from, s->n, item);
        if (s->ops->write(s->be, r, 0, buf, bytes, 1))
            return device_fail(s);
    }
    return 0;
}

/* The host's per-particle arrays, in the device's order: its own description in double as the caller gave it (not
 * registry buffers: another precision, and body and flags have no device twin), then the setup's copy of every
 * buffer that moves (what the host reads by place after the start: ride, sid), each array once; the setup's identity
 * (OLD_SLOT's value after a rebuild) means places, not particles, and stays. */
static void move_host(dem_sim *s, const int *from, unsigned char *tmp)
{
    int n = s->n;
    dem_core *c = DEM_CORE(s->be);
    struct {
        void *a;
        size_t item;
    } own[] = {{s->x, 3 * sizeof(double)}, {s->v, 3 * sizeof(double)}, {s->w, 3 * sizeof(double)},
               {s->radius, sizeof(double)}, {s->body, 2 * sizeof(double)}, {s->mat, sizeof(int)},
               {s->pflags, sizeof(unsigned)}, {s->ghost, 1}};
    const void *done[BUF__COUNT + 2] = {s->setup.identity, s->mat};
    int ndone = 2;
    for (size_t k = 0; k < sizeof own / sizeof own[0]; k++)
        if (own[k].a) /* ghost: only in a rank's part of a split run */
            move_items(own[k].a, tmp, own[k].item * (size_t)n, from, n, own[k].item);
    for (int id = 0; id < BUF__COUNT; id++) {
        size_t item;
        const void *p = dem_buffer_init(&s->setup, id);
        int seen = p == NULL;
        for (int q = 0; q < ndone && !seen; q++)
            seen = done[q] == p;
        if (seen || dem_buffer_move(c, id, &item) == DEM_MOVE_STAY || !c->bytes[id] || !item)
            continue;
        move_items((unsigned char *)p, tmp, c->bytes[id], from, n, item); /* the setup's own copy (sim_pack) */
        done[ndone++] = p;
    }
}

int sim_reorder(dem_sim *s)
{
    dem_core *c = DEM_CORE(s->be);
    int n = s->n, e = 0, same = 1;
    size_t most = 3 * sizeof(double) * (size_t)n, item;
    most = most > sizeof(int) * ((size_t)n + 1) ? most : sizeof(int) * ((size_t)n + 1);
    for (int id = 0; id < BUF__COUNT; id++)
        if (dem_buffer_move(c, id, &item) != DEM_MOVE_STAY)
            most = c->bytes[id] > most ? c->bytes[id] : most;
    for (int id = 0; id < ROW__COUNT; id++)
        most = c->row_bytes[c->cur][id] > most ? c->row_bytes[c->cur][id] : most;
    unsigned char *buf = malloc(most), *tmp = malloc(most);
    int *from = malloc(sizeof(int) * (size_t)n), *to = malloc(sizeof(int) * (size_t)n);
    if (!buf || !tmp || !from || !to)
        e = sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    if (!e)
        e = order_anew(s, buf, (double *)tmp, from, to, &same);
    if (!e && !same)
        e = move_buffers(s, from, buf, tmp);
    /* the current rows: moved with their particles (packed anew in the new order), their partners renamed */
    if (!e && !same)
        e = move_rows(s, from, to, buf, tmp);
    if (!e && !same) {
        s->order.reordered = 1; /* OLD_SLOT (moved) holds where each particle was stored when the rows were built */
        move_host(s, from, tmp);
        int *sid = (int *)s->setup.sid, *order = (int *)s->setup.order; /* the setup's (sim_pack) */
        for (int k = 0; k < n; k++) /* where each stable id is stored now */
            order[sid[k]] = k;
        if (s->ops->write(s->be, (dem_bufref){TABLE_ONE, BUF_ORDER}, 0, order, sizeof(int) * (size_t)n, 1))
            e = device_fail(s);
        s->order.count++;
    }
    free(buf), free(tmp), free(from), free(to);
    return e;
}

/* How a field follows its particles (the registry's move column of its buffer; the rows' counts are one int per
 * particle): DEM_MOVE_STAY for what is not by particle (walls, cells, flags, the pair-sized fields: those stay in
 * storage order) */
static int field_move_kind(dem_sim *s, dem_field f, size_t *item)
{
    dem_bufref r;
    size_t bytes;
    *item = sizeof(int);
    if (f == DEM_FIELD_NBR_COUNT)
        return DEM_MOVE_P;
    if (dem_field_ref(DEM_CORE(s->be), f, &r, &bytes) || r.table != TABLE_ONE)
        return DEM_MOVE_STAY;
    return dem_buffer_move(DEM_CORE(s->be), r.id, item);
}

/* dst: src (bytes) with item k (of `item` bytes; each group of n items alike) taken from item from[k]; what is not
 * by particle, or a tail past the groups (OWN_START's n-th entry), copied as it is */
static void items_move(int kind, size_t item, int n, const unsigned char *src, unsigned char *dst, size_t bytes,
                       const int *from)
{
    size_t group = kind == DEM_MOVE_STAY ? 0 : item * (size_t)n, done = 0;
    for (; group && done + group <= bytes; done += group)
        gather(dst + done, src + done, from, n, item);
    memcpy(dst + done, src + done, bytes - done);
}

/* buf (the whole field, bytes) with item k taken from item from[k]; names in the rows and cells renamed by to[] */
static int field_move(dem_sim *s, dem_field f, const unsigned char *src, unsigned char *dst, size_t bytes,
                      const int *from, const int *to)
{
    int n = s->n;
    size_t item;
    int kind = field_move_kind(s, f, &item);
    items_move(kind, item, n, src, dst, bytes, from);
    if (f == DEM_FIELD_CELL_PARTICLES)
        for (size_t q = 0; q < bytes / sizeof(int); q++) {
            int *v = (int *)dst + q;
            if (*v >= 0 && *v < n)
                *v = to[*v];
        }
    return 0;
}

/* A registry buffer (bytes) read as stored put in the callers' order, and back (dem_state_get / dem_state_set) */
int sim_buffer_to_api(dem_sim *s, int id, void *buf, size_t bytes)
{
    size_t item;
    int kind = dem_buffer_move(DEM_CORE(s->be), id, &item);
    if (!s->order.count || kind == DEM_MOVE_STAY)
        return 0;
    unsigned char *tmp = malloc(bytes ? bytes : 1);
    if (!tmp)
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    memcpy(tmp, buf, bytes);
    items_move(kind, item, s->n, tmp, buf, bytes, s->setup.order);
    free(tmp);
    return 0;
}

void sim_buffer_from_api(dem_sim *s, int id, const void *src, void *dst, size_t bytes)
{
    size_t item;
    int kind = dem_buffer_move(DEM_CORE(s->be), id, &item);
    items_move(s->order.count ? kind : DEM_MOVE_STAY, item, s->n, src, dst, bytes, s->setup.sid);
}

/* A field laid out like the current rows (packed: row i at start[i], dem_buffers.h DEM_ROWS) in the callers' order:
 * their row k is the stored row of particle order[k], packed anew from 0 (NBR_START: the starts of that packing),
 * partners renamed to the callers' ids (NBR_LIST), the values kept per slot moved with them (MC_FORCE, MC_DISP).
 * Slots past the rows hold nothing meaningful. */
static int rows_to_api(dem_sim *s, dem_field f, unsigned char *buf, size_t bytes)
{
    int n = s->n, e = 0;
    const int *order = s->setup.order, *sid = s->setup.sid;
    int *cnt = malloc(sizeof(int) * (size_t)n), *start = malloc(sizeof(int) * ((size_t)n + 1));
    int *api = malloc(sizeof(int) * ((size_t)n + 1));
    unsigned char *tmp = malloc(bytes ? bytes : 1);
    if (!cnt || !start || !api || !tmp)
        e = sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    else if (dem_stage_read_field(s->ops, s->be, DEM_FIELD_NBR_COUNT, cnt, sizeof(int) * (size_t)n) ||
             dem_stage_read_field(s->ops, s->be, DEM_FIELD_NBR_START, start, sizeof(int) * ((size_t)n + 1)))
        e = device_fail(s);
    if (!e) {
        size_t item = f == DEM_FIELD_MC_FORCE || f == DEM_FIELD_MC_DISP ? (size_t)s->setup.real_size : sizeof(int);
        memcpy(tmp, buf, bytes);
        pack_rows(buf, tmp, f == DEM_FIELD_NBR_START ? 0 : item, cnt, start, order, n, api,
                  f == DEM_FIELD_NBR_LIST ? sid : NULL);
        if (f == DEM_FIELD_NBR_START)
            memcpy(buf, api, bytes < sizeof(int) * ((size_t)n + 1) ? bytes : sizeof(int) * ((size_t)n + 1));
    }
    free(cnt), free(start), free(api), free(tmp);
    return e;
}

int sim_field_to_api(dem_sim *s, dem_field f, void *buf, size_t bytes)
{
    if (!s->order.count)
        return 0;
    if (f == DEM_FIELD_NBR_LIST || f == DEM_FIELD_NBR_START || f == DEM_FIELD_MC_FORCE || f == DEM_FIELD_MC_DISP)
        return rows_to_api(s, f, buf, bytes);
    unsigned char *tmp = malloc(bytes ? bytes : 1);
    if (!tmp)
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    memcpy(tmp, buf, bytes);
    field_move(s, f, tmp, buf, bytes, s->setup.order, s->setup.sid);
    free(tmp);
    return 0;
}

int sim_field_from_api(dem_sim *s, dem_field f, const void *src, void *dst, size_t bytes)
{
    if (!s->order.count) {
        memcpy(dst, src, bytes);
        return 0;
    }
    return field_move(s, f, src, dst, bytes, s->setup.sid, s->setup.order);
}
