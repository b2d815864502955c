/* cl_backend.c - the OpenCL backend: device set-up, the one program holding every kernel, buffers, transfers.
 * The per-kernel launches live in host/<kernel>.c. */
#include "cl_backend.h"
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const kernel_names[K__COUNT] = {
    "bin_index", "scan_block_sum", "scan_block_sums", "scan_apply", "bin_scatter", "bin_sort",
    "nbr_build", "nbr_carry", "contact_pairs", "contact_forces", "wall_reduce_block", "wall_reduce_final",
    "integrate_kick_drift", "integrate_kick", "stress_trace", "stress_tensor", "mc_strain_disp", "mc_strain_update"};

static const char *const kernel_files[] = {"kernels/binning.cl", "kernels/neighbor.cl", "kernels/contact_forces.cl",
                                           "kernels/wall_forces.cl", "kernels/integrate.cl",
                                           "kernels/particle_stress.cl", "kernels/mc_strain.cl"};
static const char *const header_files[] = {"common/dem_real.h", "common/dem_layout.h", "common/vec3.h",
                                           "common/hertz_mindlin.h", "common/contact_forces.h",
                                           "common/wall_forces.h", "common/integrate.h", "common/binning.h",
                                           "common/neighbor.h", "common/dem_effects.h",
                                           "common/contact_geometry.h", "common/particle_stress.h",
                                           "common/mc_strain.h", "common/sorted_row.h"};

int clb_arg_int(dem_backend *b, cl_kernel k, cl_uint idx, int v)
{
    return cl_check(clSetKernelArg(k, idx, sizeof v, &v), "clSetKernelArg(int)", b->err, sizeof b->err);
}

int clb_arg_real(dem_backend *b, cl_kernel k, cl_uint idx, double v)
{
    cl_int e;
    if (b->rs == 8) {
        e = clSetKernelArg(k, idx, sizeof v, &v);
    } else {
        float f = (float)v;
        e = clSetKernelArg(k, idx, sizeof f, &f);
    }
    return cl_check(e, "clSetKernelArg(real)", b->err, sizeof b->err);
}

int clb_arg_mem(dem_backend *b, cl_kernel k, cl_uint idx, cl_mem m)
{
    return cl_check(clSetKernelArg(k, idx, sizeof m, &m), "clSetKernelArg(buffer)", b->err, sizeof b->err);
}

int clb_launch(dem_backend *b, kernel_id id, size_t items)
{
    if (items == 0)
        return 0;
    size_t global = items, *local = NULL;
    if (b->local) {
        global = (items + b->local - 1) / b->local * b->local;
        local = &b->local;
    }
    cl_event ev = NULL;
    cl_int e = clEnqueueNDRangeKernel(b->q, b->k[id], 1, NULL, &global, local, 0, NULL, b->profile ? &ev : NULL);
    if (e != CL_SUCCESS) {
        snprintf(b->err, sizeof b->err, "launch of %s (%zu items, local %zu): %s (%d)", kernel_names[id], global,
                 b->local, cl_errname(e), (int)e);
        return 1;
    }
    if (ev) {
        cl_ulong t0 = 0, t1 = 0;
        clWaitForEvents(1, &ev);
        clGetEventProfilingInfo(ev, CL_PROFILING_COMMAND_START, sizeof t0, &t0, NULL);
        clGetEventProfilingInfo(ev, CL_PROFILING_COMMAND_END, sizeof t1, &t1, NULL);
        b->ktime[id] += (double)(t1 - t0) * 1e-9;
        clReleaseEvent(ev);
    }
    return 0;
}

int clb_fill_int(dem_backend *b, cl_mem m, int value, size_t count)
{
    if (count == 0)
        return 0;
    return cl_check(clEnqueueFillBuffer(b->q, m, &value, sizeof value, 0, count * sizeof(int), 0, NULL, NULL),
                    "clEnqueueFillBuffer", b->err, sizeof b->err);
}

cl_mem clb_buffer(dem_backend *b, size_t bytes, const void *init, int *fail)
{
    cl_int e;
    if (*fail)
        return NULL;
    if (bytes == 0)
        bytes = 16; /* OpenCL has no empty buffers */
    cl_mem m = clCreateBuffer(b->ctx, CL_MEM_READ_WRITE | (init ? CL_MEM_COPY_HOST_PTR : 0), bytes, (void *)init, &e);
    if (cl_check(e, "clCreateBuffer", b->err, sizeof b->err)) {
        *fail = 1;
        return NULL;
    }
    if (!init) {
        unsigned char zero = 0;
        e = clEnqueueFillBuffer(b->q, m, &zero, 1, 0, bytes, 0, NULL, NULL);
        if (cl_check(e, "clEnqueueFillBuffer", b->err, sizeof b->err))
            *fail = 1;
    }
    return m;
}

static void rel(cl_mem *m)
{
    if (*m)
        clReleaseMemObject(*m);
    *m = NULL;
}

static void cl_destroy(dem_backend *b)
{
    if (!b)
        return;
    if (b->q)
        clFinish(b->q);
    cl_mem *mems[] = {&b->x, &b->v, &b->w, &b->f, &b->t, &b->radius, &b->invm, &b->invi, &b->x_build, &b->mat,
                      &b->pairmat, &b->wall_int, &b->wall_real, &b->wall_hist, &b->wall_pf, &b->wall_mask, &b->partial,
                      &b->wall_force, &b->cell_of, &b->cell_count, &b->cell_start, &b->cell_fill,
                      &b->cell_particles, &b->block_sum, &b->flags, &b->count[0], &b->count[1], &b->list[0],
                      &b->list[1], &b->hist[0], &b->hist[1], &b->touch[0], &b->touch[1], &b->mirror[0], &b->mirror[1],
                      &b->pair, &b->in_count, &b->in_start, &b->in_block_sum, &b->invvol, &b->trace, &b->stress,
                      &b->mc_fn[0], &b->mc_fn[1], &b->mc_disp[0], &b->mc_disp[1], &b->mc_wall_fn, &b->mc_wall_disp};
    for (size_t k = 0; k < sizeof mems / sizeof mems[0]; k++)
        rel(mems[k]);
    for (int k = 0; k < K__COUNT; k++)
        if (b->k[k])
            clReleaseKernel(b->k[k]);
    if (b->prog)
        clReleaseProgram(b->prog);
    if (b->q)
        clReleaseCommandQueue(b->q);
    if (b->ctx)
        clReleaseContext(b->ctx);
    free(b);
}

/* FNV-1a over the kernel sources and headers: passed as -DDEM_SOURCE_HASH so that a compiler cache keyed on the
 * main source text and options (PoCL's is) never serves a program built from older headers. */
static int source_hash(const char *root, uint64_t *h, char *err, size_t errlen)
{
    *h = 1469598103934665603ull;
    const char *const *lists[2] = {kernel_files, header_files};
    size_t counts[2] = {sizeof kernel_files / sizeof *kernel_files, sizeof header_files / sizeof *header_files};
    for (int l = 0; l < 2; l++)
        for (size_t k = 0; k < counts[l]; k++) {
            char path[4096];
            snprintf(path, sizeof path, "%s/%s", root, lists[l][k]);
            FILE *fp = fopen(path, "rb");
            if (!fp) {
                snprintf(err, errlen, "cannot open kernel source %s (set DEM_SOURCE_DIR to the project folder)", path);
                return 1;
            }
            int c;
            while ((c = fgetc(fp)) != EOF)
                *h = (*h ^ (unsigned char)c) * 1099511628211ull;
            fclose(fp);
        }
    return 0;
}

static int cl_create(dem_backend **out, const dem_setup *s, char *err, size_t errlen)
{
    dem_backend *b = calloc(1, sizeof *b);
    cl_int e;
    int fail = 0;
    if (!b) {
        snprintf(err, errlen, "out of host memory");
        return 1;
    }
    b->rs = s->real_size;
    b->profile = getenv("DEM_PROFILE") != NULL;
    b->local = s->local_size;
    if (cl_device_get(s->device, &b->dev, err, errlen))
        goto fail;
    if (b->rs == 8 && !b->dev.fp64) {
        snprintf(err, errlen, "device %s has no fp64 support (cl_khr_fp64); use fp32", b->dev.device_name);
        goto fail;
    }
    if (b->rs == 4 && !b->dev.fp32_correct_div_sqrt) {
        snprintf(err, errlen,
                 "device %s cannot round fp32 divide and sqrt correctly, so fp32 results could not match the "
                 "reference bit for bit; use fp64",
                 b->dev.device_name);
        goto fail;
    }
    if (b->local && b->local > b->dev.max_wg) {
        snprintf(err, errlen, "work-group size %zu exceeds the device maximum %zu", b->local, b->dev.max_wg);
        goto fail;
    }
    cl_context_properties props[] = {CL_CONTEXT_PLATFORM, (cl_context_properties)b->dev.platform, 0};
    b->ctx = clCreateContext(props, 1, &b->dev.device, NULL, NULL, &e);
    if (cl_check(e, "clCreateContext", err, errlen))
        goto fail;
    b->q = clCreateCommandQueue(b->ctx, b->dev.device, b->profile ? CL_QUEUE_PROFILING_ENABLE : 0, &e);
    if (cl_check(e, "clCreateCommandQueue", err, errlen))
        goto fail;

    uint64_t hash;
    if (source_hash(s->source_dir, &hash, err, errlen))
        goto fail;
    char options[8192];
    snprintf(options, sizeof options,
             "-cl-std=CL1.2 -DDEM_REAL_SIZE=%d -DDEM_EFFECTS=%u -DDEM_SOURCE_HASH=0x%016llxULL -I%s/kernels "
             "-I%s/common %s %s",
             b->rs, s->effects, (unsigned long long)hash, s->source_dir, s->source_dir,
             b->rs == 4 ? "-cl-fp32-correctly-rounded-divide-sqrt" : "",
             s->extra_build_options ? s->extra_build_options : "");
    const char *src = "#include \"binning.cl\"\n#include \"neighbor.cl\"\n#include \"contact_forces.cl\"\n"
                      "#include \"wall_forces.cl\"\n#include \"integrate.cl\"\n#include \"particle_stress.cl\"\n"
                      "#include \"mc_strain.cl\"\n";
    if (cl_build(b->ctx, b->dev.device, src, options, &b->prog, err, errlen))
        goto fail;
    for (int k = 0; k < K__COUNT; k++) {
        b->k[k] = clCreateKernel(b->prog, kernel_names[k], &e);
        if (cl_check(e, kernel_names[k], err, errlen))
            goto fail;
    }
    snprintf(b->desc, sizeof b->desc, "OpenCL %s / %s (%s, driver %s), %s, work-group %s%zu", b->dev.platform_name,
             b->dev.device_name, b->dev.device_version, b->dev.driver_version, b->rs == 8 ? "fp64" : "fp32",
             b->local ? "" : "auto", b->local);

    int n = s->n;
    size_t r = (size_t)b->rs, N = (size_t)n;
    b->n = n;
    b->nmat = s->nmat;
    b->nwalls = s->nwalls;
    b->ncx = s->ncell[0];
    b->ncy = s->ncell[1];
    b->ncz = s->ncell[2];
    b->ncells = b->ncx * b->ncy * b->ncz;
    b->nblocks_scan = (b->ncells + DEM_SCAN_BLOCK - 1) / DEM_SCAN_BLOCK;
    b->nblocks_red = (n + DEM_REDUCE_BLOCK - 1) / DEM_REDUCE_BLOCK;
    b->dt = s->dt;
    b->skin = s->skin;
    b->half_skin2 = s->half_skin2;
    b->inv_cell = s->inv_cell;
    for (int d = 0; d < 3; d++) {
        b->lo[d] = s->lo[d];
        b->g[d] = s->gravity[d];
    }
    b->x = clb_buffer(b, 3 * N * r, s->x, &fail);
    b->v = clb_buffer(b, 3 * N * r, s->v, &fail);
    b->w = clb_buffer(b, 3 * N * r, s->w, &fail);
    b->f = clb_buffer(b, 3 * N * r, NULL, &fail);
    b->t = clb_buffer(b, 3 * N * r, NULL, &fail);
    b->radius = clb_buffer(b, N * r, s->radius, &fail);
    b->invm = clb_buffer(b, N * r, s->invmass, &fail);
    b->invi = clb_buffer(b, N * r, s->invinertia, &fail);
    b->x_build = clb_buffer(b, 3 * N * r, s->x, &fail);
    b->mat = clb_buffer(b, N * sizeof(int), s->mat, &fail);
    b->pairmat = clb_buffer(b, (size_t)PM_STRIDE * s->nmat * s->nmat * r, s->pairmat, &fail);
    b->wall_int = clb_buffer(b, (size_t)WI_STRIDE * s->nwalls * sizeof(int), s->nwalls ? s->wall_int : NULL, &fail);
    b->wall_real = clb_buffer(b, (size_t)W_STRIDE * s->nwalls * r, s->nwalls ? s->wall_real : NULL, &fail);
    b->fx = s->effects;
    b->invvol = clb_buffer(b, N * r, s->invvol, &fail);
    b->trace = clb_buffer(b, dem_field_size(FIELD_STRESS_TRACE, b->fx, N, 0, 0, 0, r), NULL, &fail);
    b->mc_wall_fn = clb_buffer(b, dem_field_size(FIELD_MC_WALL_FORCE, b->fx, N, 0, (size_t)s->nwalls, 0, r), NULL, &fail);
    b->mc_wall_disp = clb_buffer(b, dem_field_size(FIELD_MC_WALL_DISP, b->fx, N, 0, (size_t)s->nwalls, 0, r), NULL, &fail);
    b->wall_hist = clb_buffer(b, dem_field_size(FIELD_WALL_HIST, b->fx, N, 0, (size_t)s->nwalls, 0, r), NULL, &fail);
    b->wall_pf = clb_buffer(b, 3 * N * s->nwalls * r, NULL, &fail);
    b->wall_mask = clb_buffer(b, N * sizeof(unsigned), NULL, &fail);
    b->partial = clb_buffer(b, 3 * (size_t)b->nblocks_red * s->nwalls * r, NULL, &fail);
    b->wall_force = clb_buffer(b, 3 * (size_t)s->nwalls * r, NULL, &fail);
    b->cell_of = clb_buffer(b, N * sizeof(int), NULL, &fail);
    b->cell_count = clb_buffer(b, (size_t)b->ncells * sizeof(int), NULL, &fail);
    b->cell_start = clb_buffer(b, ((size_t)b->ncells + 1) * sizeof(int), NULL, &fail);
    b->cell_fill = clb_buffer(b, (size_t)b->ncells * sizeof(int), NULL, &fail);
    b->cell_particles = clb_buffer(b, N * sizeof(int), NULL, &fail);
    b->block_sum = clb_buffer(b, (size_t)b->nblocks_scan * sizeof(int), NULL, &fail);
    b->flags = clb_buffer(b, FLAG_COUNT * sizeof(int), NULL, &fail);
    for (int k = 0; k < 2; k++) {
        b->maxn[k] = s->maxn;
        b->count[k] = clb_buffer(b, N * sizeof(int), NULL, &fail);
        b->list[k] = clb_buffer(b, N * s->maxn * sizeof(int), NULL, &fail);
        b->hist[k] = clb_buffer(b, dem_field_size(FIELD_HIST, b->fx, N, (size_t)s->maxn, 0, 0, r), NULL, &fail);
        b->touch[k] = clb_buffer(b, N * s->maxn, NULL, &fail);
        b->mirror[k] = clb_buffer(b, N * s->maxn * sizeof(int), NULL, &fail);
        b->mc_fn[k] = clb_buffer(b, dem_field_size(FIELD_MC_FORCE, b->fx, N, (size_t)s->maxn, 0, 0, r), NULL, &fail);
        b->mc_disp[k] = clb_buffer(b, dem_field_size(FIELD_MC_DISP, b->fx, N, (size_t)s->maxn, 0, 0, r), NULL, &fail);
    }
    b->in_count = clb_buffer(b, N * sizeof(int), NULL, &fail);
    b->in_start = clb_buffer(b, (N + 1) * sizeof(int), NULL, &fail);
    b->in_block_sum = clb_buffer(b, (N + DEM_SCAN_BLOCK - 1) / DEM_SCAN_BLOCK * sizeof(int), NULL, &fail);
    b->pair_cap = 0;
    b->pair = NULL;
    if (fail || cl_check(clFinish(b->q), "clFinish after upload", b->err, sizeof b->err)) {
        snprintf(err, errlen, "%s", b->err);
        goto fail;
    }
    *out = b;
    return 0;
fail:
    cl_destroy(b);
    return 1;
}

static const char *cl_error(dem_backend *b) { return b->err; }
static const char *cl_describe(dem_backend *b) { return b->desc; }

/* Non-blocking: the source is static, and the driver's next flag read waits for the queue anyway. */
static int cl_reset_flags(dem_backend *b)
{
    static const int init[FLAG_COUNT] = {0, DEM_NO_PARTICLE, 0, 0, 0};
    return cl_check(clEnqueueWriteBuffer(b->q, b->flags, CL_FALSE, 0, sizeof init, init, 0, NULL, NULL),
                    "write flags", b->err, sizeof b->err);
}

static int cl_set_walls(dem_backend *b, const void *src)
{
    size_t bytes = (size_t)W_STRIDE * b->nwalls * b->rs;
    if (bytes == 0)
        return 0;
    return cl_check(clEnqueueWriteBuffer(b->q, b->wall_real, CL_FALSE, 0, bytes, src, 0, NULL, NULL),
                    "write walls", b->err, sizeof b->err);
}

static int cl_nbr_reserve(dem_backend *b, int maxn)
{
    int s = 1 - b->cur, fail = 0;
    if (b->maxn[s] == maxn)
        return 0;
    rel(&b->list[s]);
    rel(&b->hist[s]);
    rel(&b->touch[s]);
    rel(&b->mirror[s]);
    rel(&b->mc_fn[s]);
    rel(&b->mc_disp[s]);
    b->mc_fn[s] = clb_buffer(b, dem_field_size(FIELD_MC_FORCE, b->fx, (size_t)b->n, (size_t)maxn, 0, 0, (size_t)b->rs),
                             NULL, &fail);
    b->mc_disp[s] = clb_buffer(b, dem_field_size(FIELD_MC_DISP, b->fx, (size_t)b->n, (size_t)maxn, 0, 0, (size_t)b->rs),
                               NULL, &fail);
    b->list[s] = clb_buffer(b, (size_t)b->n * maxn * sizeof(int), NULL, &fail);
    b->hist[s] = clb_buffer(b, dem_field_size(FIELD_HIST, b->fx, (size_t)b->n, (size_t)maxn, 0, 0, (size_t)b->rs), NULL,
                       &fail);
    b->touch[s] = clb_buffer(b, (size_t)b->n * maxn, NULL, &fail);
    b->mirror[s] = clb_buffer(b, (size_t)b->n * maxn * sizeof(int), NULL, &fail);
    b->maxn[s] = maxn;
    return fail;
}

static int cl_nbr_commit(dem_backend *b)
{
    if (clb_nbr_carry(b))
        return 1;
    b->cur = 1 - b->cur;
    int total = 0;
    if (clb_scan(b, b->in_count, b->in_start, b->n, b->in_block_sum) ||
        cl_check(clEnqueueReadBuffer(b->q, b->in_start, CL_TRUE, (size_t)b->n * sizeof(int), sizeof total, &total, 0,
                                     NULL, NULL),
                 "read pair count", b->err, sizeof b->err))
        return 1;
    if ((size_t)total > b->pair_cap || !b->pair) { /* records are rewritten every step before they are read */
        int fail = 0;
        size_t cap = (size_t)total + (size_t)total / 4 + 16;
        rel(&b->pair);
        b->pair = clb_buffer(b, (size_t)PR_STRIDE * cap * b->rs, NULL, &fail);
        if (fail)
            return 1;
        b->pair_cap = cap;
    }
    return cl_check(clEnqueueCopyBuffer(b->q, b->x, b->x_build, 0, 0, 3 * (size_t)b->n * b->rs, 0, NULL, NULL),
                    "copy x_build", b->err, sizeof b->err);
}

static cl_mem field_mem(dem_backend *b, dem_field f, size_t *bytes)
{
    int k = b->cur;
    cl_mem m[FIELD__COUNT] = {b->x, b->v, b->w, b->f, b->t, b->x_build, b->count[k], b->list[k], b->hist[k],
                              b->wall_hist, b->wall_force, b->cell_start, b->cell_particles, b->flags, b->wall_real,
                              b->touch[k], b->wall_mask, b->stress, b->trace, b->mc_fn[k], b->mc_wall_fn,
                              b->mc_disp[k], b->mc_wall_disp};
    *bytes = dem_field_size(f, b->fx, (size_t)b->n, (size_t)b->maxn[k], (size_t)b->nwalls, (size_t)b->ncells, (size_t)b->rs);
    return (int)f >= 0 && f < FIELD__COUNT ? m[f] : NULL;
}

static int cl_read(dem_backend *b, dem_field f, void *dst, size_t bytes)
{
    size_t have;
    cl_mem m = field_mem(b, f, &have);
    if (!m || bytes > have) {
        snprintf(b->err, sizeof b->err, "read of field %d: %zu bytes asked, %zu held", (int)f, bytes, have);
        return 1;
    }
    if (bytes == 0)
        return 0;
    return cl_check(clEnqueueReadBuffer(b->q, m, CL_TRUE, 0, bytes, dst, 0, NULL, NULL), "clEnqueueReadBuffer",
                    b->err, sizeof b->err);
}

static int cl_write(dem_backend *b, dem_field f, const void *src, size_t bytes)
{
    size_t have;
    cl_mem m = field_mem(b, f, &have);
    if (!m || bytes > have) {
        snprintf(b->err, sizeof b->err, "write of field %d: %zu bytes given, %zu held", (int)f, bytes, have);
        return 1;
    }
    if (bytes == 0)
        return 0;
    return cl_check(clEnqueueWriteBuffer(b->q, m, CL_TRUE, 0, bytes, src, 0, NULL, NULL), "clEnqueueWriteBuffer",
                    b->err, sizeof b->err);
}

static int cl_finish(dem_backend *b) { return cl_check(clFinish(b->q), "clFinish", b->err, sizeof b->err); }

static int cl_kernel_times(dem_backend *b, const char ***names, const double **seconds, int *count)
{
    *names = (const char **)kernel_names;
    *seconds = b->ktime;
    *count = b->profile ? K__COUNT : 0;
    return 0;
}

const dem_backend_ops dem_opencl_ops = {
    .name = "opencl",
    .create = cl_create,
    .destroy = cl_destroy,
    .error = cl_error,
    .describe = cl_describe,
    .reset_flags = cl_reset_flags,
    .kick_drift = clb_integrate_kick_drift,
    .bin = clb_bin,
    .nbr_reserve = cl_nbr_reserve,
    .nbr_build = clb_nbr_build,
    .nbr_commit = cl_nbr_commit,
    .contact_forces = clb_contact_forces,
    .wall_reduce = clb_wall_reduce,
    .kick = clb_integrate_kick,
    .stress_trace = clb_stress_trace,
    .stress_tensor = clb_stress_tensor,
    .mc_strain_disp = clb_mc_strain_disp,
    .mc_strain_update = clb_mc_strain_update,
    .set_walls = cl_set_walls,
    .read = cl_read,
    .write = cl_write,
    .finish = cl_finish,
    .kernel_times = cl_kernel_times,
};
