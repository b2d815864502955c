/* backend_ref.c - the reference backend: host arrays in `real`, each kernel a serial loop (ref_kernels.h) called with
 * its arguments looked up by their sources, as the OpenCL backend sets them (common/dem_kernels.h). Compiled once
 * per precision; exports dem_reference_ops_f32 / dem_reference_ops_f64. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "ref_kernels.h"
#include "backend.h"

struct dem_backend {
    dem_core core; /* first: DEM_CORE */
    void *mem[BUF__COUNT];
    void *rows[2][ROW__COUNT];
};

static double wall_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static void *ptr(dem_backend *b, dem_bufref r)
{
    if (r.table == TABLE_ONE)
        return b->mem[r.id];
    return b->rows[r.table == TABLE_CUR ? b->core.cur : 1 - b->core.cur][r.id];
}

static void ref_destroy(dem_backend *b)
{
    if (!b)
        return;
    for (int id = 0; id < BUF__COUNT; id++)
        free(b->mem[id]);
    for (int set = 0; set < 2; set++)
        for (int id = 0; id < ROW__COUNT; id++)
            free(b->rows[set][id]);
    free(b);
}

static int ref_alloc(dem_backend *b, dem_table table, int set, int id, size_t bytes, const void *init)
{
    void **m = table == TABLE_ONE ? &b->mem[id] : &b->rows[set][id];
    void *p = calloc(bytes ? bytes : 1, 1);
    if (!p)
        return dem_core_fail(&b->core, "reference backend: out of host memory (%zu bytes)", bytes);
    if (init && bytes)
        memcpy(p, init, bytes);
    free(*m);
    *m = p;
    if (table == TABLE_ONE)
        b->core.bytes[id] = bytes;
    else
        b->core.row_bytes[set][id] = bytes;
    return 0;
}

/* each kernel's reference loop with its arguments, in its list's order, from their sources */
#define ARG_I(type, src) c->si[SI_##src]
#define ARG_R(type, src) (real)c->sr[SR_##src]
#define ARG_BIN(type, src) (const type *)ptr(b, DEM_REF_BIN(c, src))
#define ARG_BOUT(type, src) (type *)ptr(b, DEM_REF_BOUT(c, src))
#define ARG_CIN(type, src) (const type *)ptr(b, DEM_REF_CIN(c, src))
#define ARG_COUT(type, src) (type *)ptr(b, DEM_REF_COUT(c, src))
#define ARG_NIN(type, src) (const type *)ptr(b, DEM_REF_NIN(c, src))
#define ARG_NOUT(type, src) (type *)ptr(b, DEM_REF_NOUT(c, src))
#define ARG_AIN(type, src) (const type *)ptr(b, DEM_REF_AIN(c, src))
#define ARG_AOUT(type, src) (type *)ptr(b, DEM_REF_AOUT(c, src))
#define ARG_FIRST(kind, type, name, src) ARG_##kind(type, src)
#define ARG_NEXT(kind, type, name, src) , ARG_##kind(type, src)
#define CALL_CASE(name)                                                                                              \
    case K_##name:                                                                                                   \
        REF(ref_##name)(c->fx, DEM_ARGS_##name(ARG_FIRST, ARG_NEXT));                                                \
        break;

static int ref_launch(dem_backend *b, dem_kernel_id id)
{
    const dem_core *c = &b->core;
    double t0 = wall_now();
    switch (id) {
        DEM_KERNEL_LIST(CALL_CASE)
    default:
        return dem_core_fail(&b->core, "no kernel %d", (int)id);
    }
    b->core.ktime[id] += wall_now() - t0;
    return 0;
}

static int ref_fill_int(dem_backend *b, dem_bufref r, int value, size_t count)
{
    int *p = ptr(b, r);
    for (size_t k = 0; k < count; k++)
        p[k] = value;
    return 0;
}

static int ref_copy(dem_backend *b, dem_bufref from, dem_bufref to, size_t bytes)
{
    if (bytes)
        memcpy(ptr(b, to), ptr(b, from), bytes);
    return 0;
}

static int ref_read(dem_backend *b, dem_bufref r, size_t offset, void *dst, size_t bytes, int blocking)
{
    (void)blocking;
    if (bytes)
        memcpy(dst, (const char *)ptr(b, r) + offset, bytes);
    return 0;
}

static int ref_write(dem_backend *b, dem_bufref r, size_t offset, const void *src, size_t bytes, int blocking)
{
    (void)blocking;
    if (bytes)
        memcpy((char *)ptr(b, r) + offset, src, bytes);
    return 0;
}

static int ref_finish(dem_backend *b) { (void)b; return 0; }

static int ref_map(dem_backend *b, dem_bufref r, size_t bytes, const void **host)
{
    (void)bytes;
    *host = ptr(b, r);
    return 0;
}

static int ref_unmap(dem_backend *b, dem_bufref r, const void *host)
{
    (void)b, (void)r, (void)host;
    return 0;
}

static const char *ref_describe(dem_backend *b)
{
    (void)b;
    return sizeof(real) == 8 ? "reference (serial C, fp64)" : "reference (serial C, fp32)";
}

static void ref_swap(dem_backend *b, int id1, int id2)
{
    void *m = b->mem[id1];
    size_t n = b->core.bytes[id1];
    b->mem[id1] = b->mem[id2], b->core.bytes[id1] = b->core.bytes[id2];
    b->mem[id2] = m, b->core.bytes[id2] = n;
}

static int ref_create(dem_backend **out, const dem_setup *s, char *err, size_t errlen);

const dem_backend_ops REF(dem_reference_ops) = {
    .name = sizeof(real) == 8 ? "reference-fp64" : "reference-fp32",
    .create = ref_create,
    .destroy = ref_destroy,
    .describe = ref_describe,
    .alloc = ref_alloc,
    .launch = ref_launch,
    .fill_int = ref_fill_int,
    .copy = ref_copy,
    .read = ref_read,
    .write = ref_write,
    .finish = ref_finish,
    .map = ref_map,
    .unmap = ref_unmap,
    .swap = ref_swap,
};

static int ref_create(dem_backend **out, const dem_setup *s, char *err, size_t errlen)
{
    if (s->real_size != (int)sizeof(real)) {
        snprintf(err, errlen, "reference backend built for %zu-byte reals, setup has %d", sizeof(real), s->real_size);
        return 1;
    }
    dem_backend *b = calloc(1, sizeof *b);
    if (!b) {
        snprintf(err, errlen, "reference backend: out of host memory");
        return 1;
    }
    dem_core_init(&b->core, s);
    b->core.timed = 1;
    snprintf(b->core.build, sizeof b->core.build, "reference (serial C, fp%d) compiled into the library",
             8 * (int)sizeof(real));
    if (dem_buffers_create(&REF(dem_reference_ops), b, s)) {
        snprintf(err, errlen, "%s (%d particles)", b->core.err, s->n);
        ref_destroy(b);
        return 1;
    }
    *out = b;
    return 0;
}
