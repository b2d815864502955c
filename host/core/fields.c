/* fields.c - the caller's reads of the device's fields (dem_get_raw, dem_get_field, dem_field_bytes): read in
 * storage order and put in the callers' order when the particles were stored anew (reorder.c); whole registry
 * buffers for the host's own views (sim_buffer_get). */
#include "sim.h"
#include "dem_layout.h"
#include <stdlib.h>
#include <string.h>

void *sim_buffer_get(dem_sim *s, int id, int *e)
{
    size_t bytes = DEM_CORE(s->be)->bytes[id];
    void *p = malloc(bytes ? bytes : 1);
    if (!p) {
        if (!*e)
            *e = sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
        return NULL;
    }
    if (!*e && bytes && s->ops->read(s->be, (dem_bufref){TABLE_ONE, id}, 0, p, bytes, 1))
        *e = sim_fail(s, DEM_ERR_DEVICE, "%s", DEM_CORE(s->be)->err);
    return p;
}

size_t sim_stored_bytes(const dem_sim *s, dem_field f)
{
    dem_bufref r;
    size_t bytes;
    return s->be && !dem_field_ref(DEM_CORE(s->be), f, &r, &bytes) ? bytes : 0;
}

int sim_field_per_particle(dem_field f)
{
    switch (f) {
    case DEM_FIELD_X: case DEM_FIELD_V: case DEM_FIELD_W: case DEM_FIELD_FORCE: case DEM_FIELD_TORQUE: return 3;
    case DEM_FIELD_STRESS: return 6;
    case DEM_FIELD_STRESS_TRACE: case DEM_FIELD_RADIUS: return 1;
    default: return 0;
    }
}

size_t dem_field_bytes(const dem_sim *s, dem_field f)
{
    const dem_sim *p = sim_stepped(s);
    if (p != s) { /* a run split by dem_create_mpi: the whole run's, from this rank's part's */
        size_t b = dem_field_bytes(p, f);
        return sim_field_per_particle(f) && p->n ? b / (size_t)p->n * (size_t)s->n : b;
    }
    if (f == DEM_FIELD_MC_FORCE) /* kept per pair, handed out per row slot (dem_get_raw) */
        return (s->setup.effects & DEM_EFFECT_MC_STRAIN)
                   ? (size_t)s->setup.real_size * (size_t)(s->be ? DEM_CORE(s->be)->maxn[DEM_CORE(s->be)->cur] : s->rows.maxn)
                   : 0;
    if (s->run.started) /* the run's own sizes: the pair-sized fields follow the pairs allocated */
        return sim_stored_bytes(s, f);
    return dem_field_size(f, s->setup.effects, (size_t)s->n, (size_t)s->rows.maxn, (size_t)s->nwalls, (size_t)dem_cell_count(s),
                          (size_t)s->setup.real_size);
}

int dem_get_raw(dem_sim *s, dem_field f, void *dst, size_t bytes)
{
    if (!s->run.started)
        return sim_need_started(s);
    if (f == DEM_FIELD_STRESS && dem_stage_stress_tensor(s->ops, s->be)) /* computed from the current positions when asked */
        return sim_be_fail(s);
    int slots = f == DEM_FIELD_MC_FORCE; /* kept per pair, handed out per row slot */
    if (!bytes || (!slots && !s->order.count))
        return dem_stage_read_field(s->ops, s->be, f, dst, bytes) ? sim_be_fail(s) : 0;
    /* stored anew (dem_config.reorder): the whole field read, then put in the callers' order */
    size_t all = dem_field_bytes(s, f);
    if (bytes > all)
        return sim_fail(s, DEM_ERR_ARG, "field %d holds %zu bytes, %zu asked", (int)f, all, bytes);
    unsigned char *buf = malloc(all ? all : 1);
    if (!buf)
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    int e = slots ? sim_mc_force_slots(s, buf, all)
                  : dem_stage_read_field(s->ops, s->be, f, buf, all) ? sim_be_fail(s) : 0;
    if (!e && s->order.count)
        e = sim_field_to_api(s, f, buf, all);
    if (!e)
        memcpy(dst, buf, bytes);
    free(buf);
    return e;
}

int dem_get_field(dem_sim *s, dem_field f, double *dst)
{
    if (f == DEM_FIELD_NBR_COUNT || f == DEM_FIELD_NBR_LIST || f == DEM_FIELD_NBR_START || f == DEM_FIELD_CELL_START ||
        f == DEM_FIELD_CELL_PARTICLES ||
        f == DEM_FIELD_FLAGS || f == DEM_FIELD_TOUCH || f == DEM_FIELD_WALL_MASK || f == DEM_FIELD_IN_START ||
        f == DEM_FIELD_IN_PAIR)
        return sim_fail(s, DEM_ERR_ARG, "field %d holds integers: use dem_get_raw", (int)f);
    if (s->split_started) /* a run split by dem_create_mpi: gathered from the ranks' parts */
        return s->split_ops->get_field(s, f, dst);
    if (!s->run.started) /* (before it, the precision is not set: no size to divide by) */
        return sim_need_started(s);
    size_t bytes = dem_field_bytes(s, f), cnt = bytes / (size_t)s->setup.real_size;
    void *buf = malloc(bytes ? bytes : 1);
    if (!buf)
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    int e = dem_get_raw(s, f, buf, bytes);
    for (size_t k = 0; !e && k < cnt; k++)
        dst[k] = s->setup.real_size == 8 ? ((double *)buf)[k] : (double)((float *)buf)[k];
    free(buf);
    return e;
}

int sim_set_field(dem_sim *s, dem_field f, const double *vals)
{
    if (!s->run.started)
        return sim_need_started(s);
    size_t all = sim_stored_bytes(s, f), rs = (size_t)s->setup.real_size, cnt = all / rs;
    size_t width = s->n ? cnt / (size_t)s->n : 0;
    if (!width || width * (size_t)s->n != cnt)
        return sim_fail(s, DEM_ERR_ARG, "field %d is not a per-particle field", (int)f);
    unsigned char *buf = malloc(all);
    if (!buf)
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    for (int i = 0; i < s->n; i++) /* callers' id i to where it is stored */
        for (size_t q = 0; q < width; q++) {
            size_t at = (size_t)sim_dev(s, i) * width + q;
            double v = vals[(size_t)i * width + q];
            if (rs == 8)
                memcpy(buf + at * 8, &v, 8);
            else {
                float x = (float)v; /* a value of an fp32 run, widened: the same number */
                memcpy(buf + at * 4, &x, 4);
            }
        }
    int e = dem_stage_write_field(s->ops, s->be, f, buf, all) ? sim_be_fail(s) : 0;
    free(buf);
    return e;
}

