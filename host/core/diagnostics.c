/* diagnostics.c - what a simulation tells about itself: its last error (and a backend's, sim_be_fail), the kernels
 * launched by a step and a rebuild (the trace) and their times, device memory used and estimated, and the
 * description and build of the run. */
#include "sim.h"
#include "dem_layout.h"
#include <stdio.h>
#include <string.h>

const char *dem_error(const dem_sim *s) { return s ? s->report.err : "no simulation (out of memory?)"; }
int dem_error_particle(const dem_sim *s) { return s ? s->report.err_particle : -1; }
long dem_mdr_capped(const dem_sim *s, long *particle)
{
    if (particle)
        *particle = s ? s->report.mdr_capped_particle : -1;
    return s ? s->report.mdr_capped_step : -1;
}

int sim_be_fail(dem_sim *s)
{
    return sim_fail(s, DEM_ERR_DEVICE, "%s: %s", s->ops->name, DEM_CORE(s->be)->err);
}

/* Copies launches [a, z) of the core's trace after the n already in dst. */
int sim_copy_trace(const dem_core *c, int a, int z, unsigned char *dst, int n)
{
    for (int k = a; k < z && k < DEM_TRACE_MAX && n < DEM_TRACE_MAX; k++)
        dst[n++] = c->trace[k];
    return n;
}

const char *dem_describe(dem_sim *s)
{
    if (sim_stepped(s) != s) /* this rank's part's */
        return dem_describe((dem_sim *)sim_stepped(s));
    if (!s->be)
        return "not started";
    char fx[128];
    dem_effects_string(s->effects, fx, sizeof fx);
    snprintf(s->report.desc, sizeof s->report.desc, "%s, effects %s", s->ops->describe(s->be), fx);
    return s->report.desc;
}

int dem_kernel_times(dem_sim *s, const char ***names, const double **seconds, int *count)
{
    *count = 0;
    if (!s->be)
        return 0;
    if (s->ops->finish(s->be))
        return sim_be_fail(s);
    *names = (const char **)dem_kernel_names;
    *seconds = DEM_CORE(s->be)->ktime;
    *count = DEM_CORE(s->be)->timed ? K__COUNT : 0;
    return 0;
}

double dem_kernel_bytes(const dem_sim *s, int k)
{
    return s->be && k >= 0 && k < K__COUNT
               ? (double)dem_kernel_bound_list(DEM_CORE(s->be), (dem_kernel_id)k, NULL, NULL, 0, NULL)
               : 0;
}

int dem_kernel_buffers(const dem_sim *s, int k, const char **names, double *bytes, int max)
{
    int count = 0;
    if (s->be && k >= 0 && k < K__COUNT)
        dem_kernel_bound_list(DEM_CORE(s->be), (dem_kernel_id)k, names, bytes, max, &count);
    return count;
}

int dem_kernel_launched(const dem_sim *s, int rebuild, const char *name)
{
    s = sim_stepped(s); /* a split run: this rank's part's */
    const unsigned char *q = rebuild ? s->trace.rebuild : s->trace.step;
    int n = rebuild ? s->trace.nrebuild : s->trace.nstep;
    for (int k = 0; k < n; k++)
        if (!strcmp(dem_kernel_names[q[k]], name))
            return 1;
    return 0;
}

long dem_kernel_item_count(const dem_sim *s, int k)
{
    return s->be && k >= 0 && k < K__COUNT ? (long)dem_kernel_items(DEM_CORE(s->be), (dem_kernel_id)k) : 0;
}

int dem_particle_added_position(const dem_sim *s, int i, double x[3])
{
    if (i < 0 || i >= s->n)
        return DEM_ERR_ARG;
    for (int d = 0; d < 3; d++)
        x[d] = s->x[3 * (size_t)sim_dev(s, i) + d];
    return 0;
}

long dem_stage_ends(const dem_sim *s, long k, dem_stage_end *e)
{
    s = sim_stepped(s);
    long n = s->motion.stage_log_n;
    if (e && k >= 0 && k < n) {
        if (k >= n - DEM_STAGE_LOG)
            *e = s->motion.stage_log[k % DEM_STAGE_LOG];
        else
            *e = (dem_stage_end){-1, -1, -1, -1, 0};
    }
    return n;
}

int dem_kernel_sequence(const dem_sim *s, int rebuild, char *buf, size_t len)
{
    s = sim_stepped(s); /* a split run: this rank's part's */
    const unsigned char *q = rebuild ? s->trace.rebuild : s->trace.step;
    int n = rebuild ? s->trace.nrebuild : s->trace.nstep;
    size_t o = 0;
    if (len)
        buf[0] = 0;
    for (int k = 0; k < n && o < len;) {
        /* a repeated pair of launches (an iteration) is written once with its count */
        int rep = 1;
        while (k + 2 * rep + 1 < n && q[k + 2 * rep] == q[k] && q[k + 2 * rep + 1] == q[k + 1])
            rep++;
        if (rep > 1) {
            o += (size_t)snprintf(buf + o, len - o, "%s%d x (%s, %s)", o ? ", " : "", rep, dem_kernel_names[q[k]],
                                  dem_kernel_names[q[k + 1]]);
            k += 2 * rep;
        } else {
            o += (size_t)snprintf(buf + o, len - o, "%s%s", o ? ", " : "", dem_kernel_names[q[k]]);
            k++;
        }
    }
    return n;
}

size_t dem_device_bytes(const dem_sim *s)
{
    s = sim_stepped(s);
    if (!s->be)
        return 0;
    const dem_core *c = DEM_CORE(s->be);
    size_t sum = 0;
    for (int id = 0; id < BUF__COUNT; id++)
        sum += c->bytes[id];
    for (int set = 0; set < 2; set++)
        for (int id = 0; id < ROW__COUNT; id++)
            sum += c->row_bytes[set][id];
    return sum;
}

size_t dem_device_bytes_part(const dem_sim *s, dem_memory_part part)
{
    s = sim_stepped(s);
    if (!s->be)
        return 0;
    const dem_core *c = DEM_CORE(s->be);
    size_t sum = 0;
    for (int id = 0; id < BUF__COUNT; id++)
        if (dem_buffer_part(id) == (int)part)
            sum += c->bytes[id];
    for (int set = 0; set < 2 && part == DEM_MEM_ROWS; set++)
        for (int id = 0; id < ROW__COUNT; id++)
            sum += c->row_bytes[set][id];
    return sum;
}

const char *dem_memory_part_name(dem_memory_part part)
{
    static const char *const names[DEM_MEM__COUNT] = {"particles", "pairs", "neighbour rows", "walls",
                                                      "cells",     "output", "membranes and riders"};
    return (int)part >= 0 && part < DEM_MEM__COUNT ? names[part] : "?";
}

int dem_memory_estimate(dem_sim *s, const dem_config *c, size_t *bytes)
{
    *bytes = 0;
    if (s->run.started || s->split_started)
        return sim_fail(s, DEM_ERR_STATE, "dem_memory_estimate is for a run not started (dem_device_bytes after)");
    if (s->split_ops) /* (it would pack the set-up the parts are copied from) */
        return sim_fail(s, DEM_ERR_STATE, "dem_memory_estimate: not on a run split over MPI ranks (dem_create_mpi): "
                        "each rank's part is sized at dem_start; dem_device_bytes after it gives this rank's");
    s->cfg = *c;
    int e = sim_validate(s);
    if (e || (e = sim_pack(s)))
        return e;
    dem_core core;
    dem_core_init(&core, &s->setup);
    core.pair_cap = (size_t)DEM_ESTIMATE_PAIRS_PER_PARTICLE * (size_t)s->n;
    for (int id = 0; id < BUF__COUNT; id++)
        *bytes += dem_buffer_bytes(&core, id);
    for (int set = 0; set < 2; set++)
        for (int id = 0; id < ROW__COUNT; id++)
            *bytes += dem_row_bytes(&core, id, core.maxn[set]);
    return 0;
}

#ifndef DEM_BUILD_FLAGS
#define DEM_BUILD_FLAGS "unknown"
#endif
#if defined(__clang__)
#define DEM_COMPILER "clang " __clang_version__
#elif defined(__GNUC__)
#define DEM_COMPILER "gcc " __VERSION__
#else
#define DEM_COMPILER "unknown"
#endif

const char *dem_build_info(dem_sim *s)
{
    snprintf(s->report.build, sizeof s->report.build, "libdem %s; host code compiled by %s with %s; kernels: %s", DEM_VERSION,
             DEM_COMPILER, DEM_BUILD_FLAGS, s->be ? DEM_CORE(s->be)->build : "not started");
    return s->report.build;
}
