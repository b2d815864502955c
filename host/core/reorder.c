/* reorder.c - the particles stored anew along a Morton curve through their current positions, at a neighbour rebuild
 * (dem_config.reorder; issue 14), and the particle ids of the library's calls kept those of dem_start.
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
 * What moves, at the start of a rebuild (before the binning): every per-particle buffer (its rows' values included)
 * to the new places, the current rows' partners renamed, and each particle's start of its owned pairs in the old
 * pair list (old_pair_number reads the old pairs through it; the pair-sized arrays themselves stay where they are,
 * numbered as before, until pair_index carries them into the new rows). The host's own per-particle arrays follow,
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

/* A buffer sized by particles: particle-major (bytes / n per particle: its reals, or its reals per wall), or in
 * groups of n particles (WALL_PF: one group per wall; the series ring: one per row) of `per` reals each. */
enum { LAYOUT_PARTICLE, LAYOUT_GROUPS };
typedef struct {
    int id, layout, per;
} moved_buffer;

/* Every DEM_BUFFERS entry sized by particles; tests/test_particle_order.c reorders at every rebuild, so a buffer
 * missing here changes the bits there. Not here: what a rebuild or a step rewrites before reading it (cells, in/own
 * counts and starts, the pair arrays, the walls' partial sums, the vertex rows and the patch records), OWN_START, SID
 * and ORDER (below), and the membrane, patch and rider tables (by stable id: they stay). */
static const moved_buffer moved[] = {
    {BUF_X, LAYOUT_PARTICLE, 0},          {BUF_V, LAYOUT_PARTICLE, 0},         {BUF_W, LAYOUT_PARTICLE, 0},
    {BUF_FORCE, LAYOUT_PARTICLE, 0},      {BUF_TORQUE, LAYOUT_PARTICLE, 0},    {BUF_RADIUS, LAYOUT_PARTICLE, 0},
    {BUF_INVMASS, LAYOUT_PARTICLE, 0},    {BUF_INVINERTIA, LAYOUT_PARTICLE, 0}, {BUF_INVVOL, LAYOUT_PARTICLE, 0},
    {BUF_X_BUILD, LAYOUT_PARTICLE, 0},    {BUF_MAT, LAYOUT_PARTICLE, 0},
    {BUF_WALL_HIST, LAYOUT_PARTICLE, 0},  {BUF_WALL_MASK, LAYOUT_PARTICLE, 0}, {BUF_TRACE, LAYOUT_PARTICLE, 0},
    {BUF_STRESS, LAYOUT_PARTICLE, 0},     {BUF_MC_WALL_FN, LAYOUT_PARTICLE, 0}, {BUF_MC_WALL_DISP, LAYOUT_PARTICLE, 0},
    {BUF_RIDE, LAYOUT_PARTICLE, 0},       {BUF_HOLD, LAYOUT_PARTICLE, 0},      {BUF_WALL_PF, LAYOUT_GROUPS, 3},
    {BUF_SERIES_RING, LAYOUT_GROUPS, SE_STRIDE}, {BUF_PCOUNT, LAYOUT_PARTICLE, 0},   {BUF_PLIST, LAYOUT_PARTICLE, 0},
    {BUF_PHIST, LAYOUT_PARTICLE, 0},      {BUF_PTOUCH, LAYOUT_PARTICLE, 0},
};

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
    return s->cfg.reorder > 0 && !s->reorder_hold && s->n > 1 && s->rebuilds % s->cfg.reorder == 0;
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

int sim_reorder(dem_sim *s)
{
    dem_core *c = DEM_CORE(s->be);
    int n = s->n, rs = s->setup.real_size;
    size_t most = 0;
    for (size_t k = 0; k < sizeof moved / sizeof moved[0]; k++)
        most = c->bytes[moved[k].id] > most ? c->bytes[moved[k].id] : most;
    for (int id = 0; id < ROW__COUNT; id++)
        most = c->row_bytes[c->cur][id] > most ? c->row_bytes[c->cur][id] : most;
    most = most > 3 * sizeof(double) * (size_t)n ? most : 3 * sizeof(double) * (size_t)n;
    most = most > sizeof(int) * ((size_t)n + 1) ? most : sizeof(int) * ((size_t)n + 1);
    unsigned char *buf = malloc(most), *tmp = malloc(most);
    int *from = malloc(sizeof(int) * (size_t)n), *to = malloc(sizeof(int) * (size_t)n);
    if (!buf || !tmp || !from || !to) {
        free(buf), free(tmp), free(from), free(to);
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    }
    int e = 0;
    /* the new order: a Morton curve through the current positions */
    double *x = (double *)tmp;
    if (s->ops->read(s->be, (dem_bufref){TABLE_ONE, BUF_X}, 0, buf, 3 * (size_t)n * rs, 1))
        e = device_fail(s);
    int finite = 1;
    for (int k = 0; !e && k < 3 * n; k++) {
        x[k] = rs == 8 ? ((double *)buf)[k] : ((float *)buf)[k];
        finite &= isfinite(x[k]) != 0;
    }
    if (!e && !finite) { /* left as stored: the binning that follows reports the particle */
        free(buf), free(tmp), free(from), free(to);
        return 0;
    }
    /* Worth it only when the storage has become scattered: the mean distance between particles stored next to each
     * other (one pass over the positions) more than `gain` times what it was after the last look; then, more than
     * `gain` times what the new order gives (a Morton sort). A move cost 0.12 s at 1e5 particles on this project's
     * VM, some six rebuilds (docs/design.md). */
    double gain = s->cfg.reorder_gain > 0 ? s->cfg.reorder_gain : DEM_REORDER_GAIN, now = 0, anew = 0;
    for (int k = 0; !e && k + 1 < n; k++)
        now += spacing(x, k, k + 1);
    if (!e && gain > 1 && s->reorder_ref > 0 && !(now > gain * s->reorder_ref)) {
        free(buf), free(tmp), free(from), free(to);
        return 0;
    }
    if (!e && sim_morton_order(x, n, from))
        e = sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    int same = 1;
    for (int k = 0; !e && k < n; k++) {
        to[from[k]] = k;
        same &= from[k] == k;
    }
    for (int k = 0; !e && k + 1 < n; k++)
        anew += spacing(x, from[k], from[k + 1]);
    if (gain > 1 && !(now > gain * anew)) {
        same = 1;
        s->reorder_ref = now; /* close enough: looked at again when it has spread `gain` times this */
    } else
        s->reorder_ref = anew;
    /* the device's buffers */
    for (size_t k = 0; !e && !same && k < sizeof moved / sizeof moved[0]; k++) {
        const moved_buffer *m = &moved[k];
        size_t bytes = c->bytes[m->id];
        if (!bytes)
            continue;
        size_t item = m->layout == LAYOUT_PARTICLE ? bytes / (size_t)n : (size_t)m->per * (size_t)rs;
        dem_bufref r = {TABLE_ONE, m->id};
        if (s->ops->read(s->be, r, 0, buf, bytes, 1))
            e = device_fail(s);
        else {
            move_items(buf, tmp, bytes, from, n, item);
            if (s->ops->write(s->be, r, 0, buf, bytes, 1))
                e = device_fail(s);
        }
    }
    /* the current rows: moved with their particles (packed anew in the new order), their partners renamed */
    if (!e && !same)
        e = move_rows(s, from, to, buf, tmp);
    /* where each particle was stored when the current rows were built (old_pair_number finds the pairs' old hosts) */
    if (!e && !same) {
        int *old = (int *)buf;
        dem_bufref r = {TABLE_ONE, BUF_OLD_SLOT};
        if (s->ops->read(s->be, r, 0, tmp, sizeof(int) * (size_t)n, 1))
            e = device_fail(s);
        for (int k = 0; !e && k < n; k++)
            old[k] = ((int *)tmp)[from[k]];
        if (!e && s->ops->write(s->be, r, 0, old, sizeof(int) * (size_t)n, 1))
            e = device_fail(s);
        s->reordered = 1;
    }
    /* each particle's first hosted pair in the (unmoved) pair list moves with it */
    if (!e && !same) {
        dem_bufref r = {TABLE_ONE, BUF_OWN_START};
        if (s->ops->read(s->be, r, 0, buf, sizeof(int) * (size_t)n, 1))
            e = device_fail(s);
        else {
            move_items(buf, tmp, sizeof(int) * (size_t)n, from, n, sizeof(int));
            if (s->ops->write(s->be, r, 0, buf, sizeof(int) * (size_t)n, 1))
                e = device_fail(s);
        }
    }
    if (!e && !same) {
        /* the host's per-particle arrays, in the device's order */
        move_items((unsigned char *)s->x, tmp, 3 * sizeof(double) * (size_t)n, from, n, 3 * sizeof(double));
        move_items((unsigned char *)s->v, tmp, 3 * sizeof(double) * (size_t)n, from, n, 3 * sizeof(double));
        move_items((unsigned char *)s->w, tmp, 3 * sizeof(double) * (size_t)n, from, n, 3 * sizeof(double));
        move_items((unsigned char *)s->radius, tmp, sizeof(double) * (size_t)n, from, n, sizeof(double));
        move_items((unsigned char *)s->body, tmp, 2 * sizeof(double) * (size_t)n, from, n, 2 * sizeof(double));
        move_items((unsigned char *)s->mat, tmp, sizeof(int) * (size_t)n, from, n, sizeof(int));
        move_items((unsigned char *)s->pflags, tmp, sizeof(unsigned) * (size_t)n, from, n, sizeof(unsigned));
        static const int packed3[] = {0, 1, 2}, packed1[] = {3, 4, 5, 8};
        for (int k = 0; k < 3; k++)
            move_items(s->packed[packed3[k]], tmp, 3 * (size_t)rs * (size_t)n, from, n, 3 * (size_t)rs);
        for (int k = 0; k < 4; k++)
            move_items(s->packed[packed1[k]], tmp, (size_t)rs * (size_t)n, from, n, (size_t)rs);
        for (int k = 20; k <= 22; k++) /* ride, hold, sid: the id of dem_start of the particle at each place */
            if (s->packed[k])
                move_items(s->packed[k], tmp, sizeof(int) * (size_t)n, from, n, sizeof(int));
        int *sid = s->packed[22], *order = s->packed[23]; /* order: where each id is stored */
        for (int k = 0; k < n; k++)
            order[sid[k]] = k;
        if (s->ops->write(s->be, (dem_bufref){TABLE_ONE, BUF_SID}, 0, sid, sizeof(int) * (size_t)n, 1) ||
            s->ops->write(s->be, (dem_bufref){TABLE_ONE, BUF_ORDER}, 0, order, sizeof(int) * (size_t)n, 1))
            e = device_fail(s);
        s->reorders++;
    }
    free(buf), free(tmp), free(from), free(to);
    return e;
}

/* How a field is laid out by particle: 1 particle-major (bytes / n each), 2 in groups of n (WALL_PF: per wall), 0 not
 * by particle (walls, cells, flags, the pair-sized fields: those stay in storage order). */
static int field_layout(dem_field f)
{
    switch (f) {
    case DEM_FIELD_X: case DEM_FIELD_V: case DEM_FIELD_W: case DEM_FIELD_FORCE: case DEM_FIELD_TORQUE:
    case DEM_FIELD_X_BUILD: case DEM_FIELD_NBR_COUNT: case DEM_FIELD_WALL_HIST:
    case DEM_FIELD_WALL_MASK: case DEM_FIELD_STRESS: case DEM_FIELD_STRESS_TRACE:
    case DEM_FIELD_MC_WALL_FORCE: case DEM_FIELD_MC_WALL_DISP:
        return 1;
    case DEM_FIELD_WALL_PF:
        return 2;
    default:
        return 0;
    }
}

/* buf (the whole field, bytes) with item k taken from item from[k]; names in the rows and cells renamed by to[] */
static int field_move(dem_sim *s, dem_field f, const unsigned char *src, unsigned char *dst, size_t bytes,
                      const int *from, const int *to)
{
    int n = s->n, layout = field_layout(f);
    if (layout && bytes) {
        size_t item = layout == 1 ? bytes / (size_t)n : 3 * (size_t)s->setup.real_size, group = item * (size_t)n;
        for (size_t g = 0; g + group <= bytes; g += group)
            gather(dst + g, src + g, from, n, item);
    } else
        memcpy(dst, src, bytes);
    if (f == DEM_FIELD_CELL_PARTICLES)
        for (size_t q = 0; q < bytes / sizeof(int); q++) {
            int *v = (int *)dst + q;
            if (*v >= 0 && *v < n)
                *v = to[*v];
        }
    return 0;
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
    if (!s->reorders)
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
    if (!s->reorders) {
        memcpy(dst, src, bytes);
        return 0;
    }
    return field_move(s, f, src, dst, bytes, s->setup.sid, s->setup.order);
}
