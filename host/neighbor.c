/* neighbor.c - the neighbour-row steps (kernels/neighbor.cl): capacity of the rows being built, the build, and the
 * commit (history carried into the new rows, which become current; pair-record offsets; x_build). Written once for
 * every backend. */
#include "backend.h"

int dem_stage_nbr_reserve(const dem_backend_ops *o, dem_backend *b, int maxn)
{
    dem_core *c = DEM_CORE(b);
    int set = 1 - c->cur;
    if (c->maxn[set] == maxn)
        return 0;
    for (int id = 0; id < ROW__COUNT; id++) {
        size_t bytes = dem_row_bytes(c, id, maxn);
        if (bytes != c->row_bytes[set][id] && o->alloc(b, TABLE_NEW, set, id, bytes, NULL))
            return 1;
    }
    c->maxn[set] = maxn;
    dem_core_sync(c);
    return 0;
}

int dem_stage_nbr_build(const dem_backend_ops *o, dem_backend *b) { return dem_launch(o, b, K_nbr_build); }

int dem_stage_nbr_commit(const dem_backend_ops *o, dem_backend *b)
{
    dem_core *c = DEM_CORE(b);
    /* the old pair numbering and history, which pair_index carries into the new (neighbor.h); the copy of the history
     * is grown here to the capacity of the history itself (which may have grown at the last commit) */
    dem_bufref hist = {TABLE_ONE, BUF_PAIR_HIST}, old_hist = {TABLE_ONE, BUF_PAIR_HIST_OLD};
    dem_bufref touch = {TABLE_ONE, BUF_TOUCH}, old_touch = {TABLE_ONE, BUF_TOUCH_OLD};
    dem_bufref own = {TABLE_ONE, BUF_OWN_START}, old_own = {TABLE_ONE, BUF_OWN_START_OLD};
    if ((c->bytes[BUF_PAIR_HIST_OLD] != c->bytes[BUF_PAIR_HIST] &&
         o->alloc(b, TABLE_ONE, 0, BUF_PAIR_HIST_OLD, c->bytes[BUF_PAIR_HIST], NULL)) ||
        (c->bytes[BUF_TOUCH_OLD] != c->bytes[BUF_TOUCH] &&
         o->alloc(b, TABLE_ONE, 0, BUF_TOUCH_OLD, c->bytes[BUF_TOUCH], NULL)))
        return 1;
    if ((c->bytes[BUF_PAIR_HIST] && o->copy(b, hist, old_hist, c->bytes[BUF_PAIR_HIST])) ||
        (c->bytes[BUF_TOUCH] && o->copy(b, touch, old_touch, c->bytes[BUF_TOUCH])) ||
        o->copy(b, own, old_own, c->bytes[BUF_OWN_START]) || dem_launch(o, b, K_nbr_carry))
        return 1;
    c->cur = 1 - c->cur;
    dem_core_sync(c);
    int total = 0, owned = 0;
    dem_bufref start = {TABLE_ONE, BUF_IN_START};
    if (dem_stage_scan(o, b, BUF_IN_COUNT, BUF_IN_START, BUF_IN_BLOCK_SUM, c->n) ||
        dem_stage_scan(o, b, BUF_OWN_COUNT, BUF_OWN_START, BUF_OWN_BLOCK_SUM, c->n) ||
        o->read(b, start, (size_t)c->n * sizeof(int), &total, sizeof total, 1) ||
        o->read(b, own, (size_t)c->n * sizeof(int), &owned, sizeof owned, 1))
        return 1;
    if (owned != total) /* every pair is owned by one row and mirrored in one other (pair_index checks symmetry) */
        return dem_core_fail(c, "neighbour rows list %d owned and %d incoming pairs (a library bug; please report)",
                             owned, total);
    if ((size_t)total > c->pair_cap || c->bytes[BUF_PAIR] == 0) { /* rewritten every step before being read */
        /* 1/8 to spare: the pair arrays are two thirds of the memory, and growing them costs one allocation at a
         * rebuild (the history and flags are carried from their copies either way) */
        c->pair_cap = (size_t)total + (size_t)total / 8 + 16;
        if (o->alloc(b, TABLE_ONE, 0, BUF_PAIR, dem_buffer_bytes(c, BUF_PAIR), NULL) ||
            o->alloc(b, TABLE_ONE, 0, BUF_PAIR_SLOT, dem_buffer_bytes(c, BUF_PAIR_SLOT), NULL) ||
            o->alloc(b, TABLE_ONE, 0, BUF_IN_PAIR, dem_buffer_bytes(c, BUF_IN_PAIR), NULL) ||
            o->alloc(b, TABLE_ONE, 0, BUF_PAIR_MIRROR, dem_buffer_bytes(c, BUF_PAIR_MIRROR), NULL) ||
            o->alloc(b, TABLE_ONE, 0, BUF_TOUCH, dem_buffer_bytes(c, BUF_TOUCH), NULL) ||
            o->alloc(b, TABLE_ONE, 0, BUF_PAIR_HIST, dem_buffer_bytes(c, BUF_PAIR_HIST), NULL))
            return 1;
    }
    c->si[SI_NPAIRS] = total;
    dem_bufref x = {TABLE_ONE, BUF_X}, xb = {TABLE_ONE, BUF_X_BUILD};
    return dem_launch(o, b, K_pair_index) || o->copy(b, x, xb, c->bytes[BUF_X]);
}
