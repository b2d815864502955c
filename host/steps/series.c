/* series.c - the series rows' buffers (common/series.h): a sampled step's terms go to a row of the device's ring,
 * written by the step's own kernels; the ring is read back in one synchronisation. Written once for every backend. */
#include "backend.h"

int dem_stage_series_arm(const dem_backend_ops *o, dem_backend *b, int on, int row)
{
    dem_core *c = DEM_CORE(b);
    c->si[SI_SERIES_SAMPLE] = on;
    c->si[SI_SERIES_ROW] = row;
    return on ? dem_buffer_ensure(o, b, BUF_SERIES_RING) || dem_buffer_ensure(o, b, BUF_SERIES_WALL) : 0;
}

/* mapped, not read: a copy of the ring was 1 % of a 514-sphere run with a row every step, and the sums read it again
 * from beyond the cache */
int dem_stage_series_map(const dem_backend_ops *o, dem_backend *b, int rows, const void **terms, const void **walls)
{
    dem_core *c = DEM_CORE(b);
    size_t tb = (size_t)rows * SE_STRIDE * (size_t)c->n * (size_t)c->rs,
           wb = (size_t)rows * WP_STRIDE * (size_t)c->nwalls * (size_t)c->rs;
    dem_bufref rt = {TABLE_ONE, BUF_SERIES_RING}, rw = {TABLE_ONE, BUF_SERIES_WALL};
    *terms = *walls = NULL;
    if (o->map(b, rt, tb, terms))
        return 1;
    if (wb && o->map(b, rw, wb, walls)) {
        o->unmap(b, rt, *terms);
        *terms = NULL;
        return 1;
    }
    return 0;
}

int dem_stage_series_unmap(const dem_backend_ops *o, dem_backend *b, const void *terms, const void *walls)
{
    dem_bufref rt = {TABLE_ONE, BUF_SERIES_RING}, rw = {TABLE_ONE, BUF_SERIES_WALL};
    int e = terms && o->unmap(b, rt, terms);
    return (walls && o->unmap(b, rw, walls)) || e;
}
