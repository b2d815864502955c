/* cl_backend.c - the OpenCL backend: device set-up, the one program holding every kernel, buffers by the registry
 * (common/dem_buffers.h), launches with arguments set from the kernels' lists (common/dem_kernels.h), transfers.
 * The steps themselves are written once for every backend (host/steps/). */
#include "backend.h"
#include "cl_util.h"
#include <dirent.h>
#include <pthread.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

struct dem_backend {
    dem_core core; /* first: DEM_CORE */
    cl_device_info_t dev;
    cl_context ctx;
    cl_command_queue q;
    cl_program prog;
    cl_kernel k[K__COUNT];
    int profile;
    size_t local; /* work-group size, 0 = runtime's choice */
    cl_mem mem[BUF__COUNT];
    cl_mem rows[2][ROW__COUNT];
    char desc[512];
};

#define ERR(b) (b)->core.err, sizeof (b)->core.err

/* the program: one file, which makes every kernel of the list; the folders the source hash walks */
#define PROGRAM_FILE "kernels/program.cl"
static const char *const source_folders[] = {"kernels", "common", "include"};

static cl_mem *slot(dem_backend *b, dem_bufref r)
{
    if (r.table == TABLE_ONE)
        return &b->mem[r.id];
    return &b->rows[r.table == TABLE_CUR ? b->core.cur : 1 - b->core.cur][r.id];
}

static int arg_int(dem_backend *b, cl_kernel k, cl_uint idx, int v)
{
    return cl_check(clSetKernelArg(k, idx, sizeof v, &v), "clSetKernelArg(int)", ERR(b));
}

/* a real argument as float or double by the precision (a plain C cast, as the reference does) */
static int arg_real(dem_backend *b, cl_kernel k, cl_uint idx, double v)
{
    cl_int e;
    if (b->core.rs == 8) {
        e = clSetKernelArg(k, idx, sizeof v, &v);
    } else {
        float f = (float)v;
        e = clSetKernelArg(k, idx, sizeof f, &f);
    }
    return cl_check(e, "clSetKernelArg(real)", ERR(b));
}

static int arg_mem(dem_backend *b, cl_kernel k, cl_uint idx, dem_bufref r)
{
    cl_mem m = *slot(b, r);
    return cl_check(clSetKernelArg(k, idx, sizeof m, &m), "clSetKernelArg(buffer)", ERR(b));
}

/* each kernel's arguments, in its list's order, from their sources */
#define SET_I(src) arg_int(b, k, a++, c->si[SI_##src])
#define SET_R(src) arg_real(b, k, a++, c->sr[SR_##src])
#define SET_BIN(src) arg_mem(b, k, a++, DEM_REF_BIN(c, src))
#define SET_BOUT(src) arg_mem(b, k, a++, DEM_REF_BOUT(c, src))
#define SET_CIN(src) arg_mem(b, k, a++, DEM_REF_CIN(c, src))
#define SET_COUT(src) arg_mem(b, k, a++, DEM_REF_COUT(c, src))
#define SET_NIN(src) arg_mem(b, k, a++, DEM_REF_NIN(c, src))
#define SET_NOUT(src) arg_mem(b, k, a++, DEM_REF_NOUT(c, src))
#define SET_AIN(src) arg_mem(b, k, a++, DEM_REF_AIN(c, src))
#define SET_AOUT(src) arg_mem(b, k, a++, DEM_REF_AOUT(c, src))
#define SET_ARG(kind, type, name, src) || SET_##kind(src)
#define SET_CASE(name)                                                                                               \
    case K_##name:                                                                                                   \
        return 0 DEM_ARGS_##name(SET_ARG, SET_ARG);

static int set_args(dem_backend *b, dem_kernel_id id)
{
    const dem_core *c = &b->core;
    cl_kernel k = b->k[id];
    cl_uint a = 0;
    switch (id) {
        DEM_KERNEL_LIST(SET_CASE)
    default:
        return dem_core_fail(&b->core, "no kernel %d", (int)id);
    }
}

static int cl_launch(dem_backend *b, dem_kernel_id id)
{
    size_t items = dem_kernel_items(&b->core, id);
    if (items == 0)
        return 0;
    if (set_args(b, id))
        return 1;
    size_t global = items, *local = NULL;
    if (b->local) {
        global = (items + b->local - 1) / b->local * b->local;
        local = &b->local;
    }
    cl_event ev = NULL;
    cl_int e = clEnqueueNDRangeKernel(b->q, b->k[id], 1, NULL, &global, local, 0, NULL, b->profile ? &ev : NULL);
    if (e != CL_SUCCESS)
        return dem_core_fail(&b->core, "launch of %s (%zu items, local %zu): %s (%d)", dem_kernel_names[id], global,
                             b->local, cl_errname(e), (int)e);
    if (ev) {
        cl_ulong t0 = 0, t1 = 0;
        e = clWaitForEvents(1, &ev);
        if (e == CL_SUCCESS)
            e = clGetEventProfilingInfo(ev, CL_PROFILING_COMMAND_START, sizeof t0, &t0, NULL);
        if (e == CL_SUCCESS)
            e = clGetEventProfilingInfo(ev, CL_PROFILING_COMMAND_END, sizeof t1, &t1, NULL);
        clReleaseEvent(ev);
        if (cl_check(e, "kernel profiling", ERR(b)))
            return 1;
        b->core.ktime[id] += (double)(t1 - t0) * 1e-9;
    }
    return 0;
}

static int cl_alloc(dem_backend *b, dem_table table, int set, int id, size_t bytes, const void *init)
{
    cl_mem *m = table == TABLE_ONE ? &b->mem[id] : &b->rows[set][id];
    if (*m)
        clReleaseMemObject(*m);
    *m = NULL;
    size_t have = bytes ? bytes : 16; /* OpenCL has no empty buffers */
    cl_int e;
    *m = clCreateBuffer(b->ctx, CL_MEM_READ_WRITE | (init ? CL_MEM_COPY_HOST_PTR : 0), have, (void *)init, &e);
    if (cl_check(e, "clCreateBuffer", ERR(b)))
        return 1;
    if (!init) {
        unsigned char zero = 0;
        if (cl_check(clEnqueueFillBuffer(b->q, *m, &zero, 1, 0, have, 0, NULL, NULL), "clEnqueueFillBuffer", ERR(b)))
            return 1;
    }
    if (table == TABLE_ONE)
        b->core.bytes[id] = bytes;
    else
        b->core.row_bytes[set][id] = bytes;
    return 0;
}

static int cl_fill_int(dem_backend *b, dem_bufref r, int value, size_t count)
{
    if (count == 0)
        return 0;
    return cl_check(clEnqueueFillBuffer(b->q, *slot(b, r), &value, sizeof value, 0, count * sizeof(int), 0, NULL,
                                        NULL),
                    "clEnqueueFillBuffer", ERR(b));
}

static int cl_copy(dem_backend *b, dem_bufref from, dem_bufref to, size_t bytes)
{
    if (bytes == 0)
        return 0;
    return cl_check(clEnqueueCopyBuffer(b->q, *slot(b, from), *slot(b, to), 0, 0, bytes, 0, NULL, NULL),
                    "clEnqueueCopyBuffer", ERR(b));
}

static int cl_read(dem_backend *b, dem_bufref r, size_t offset, void *dst, size_t bytes, int blocking)
{
    if (bytes == 0)
        return 0;
    return cl_check(clEnqueueReadBuffer(b->q, *slot(b, r), blocking ? CL_TRUE : CL_FALSE, offset, bytes, dst, 0, NULL,
                                        NULL),
                    "clEnqueueReadBuffer", ERR(b));
}

static int cl_write(dem_backend *b, dem_bufref r, size_t offset, const void *src, size_t bytes, int blocking)
{
    if (bytes == 0)
        return 0;
    return cl_check(clEnqueueWriteBuffer(b->q, *slot(b, r), blocking ? CL_TRUE : CL_FALSE, offset, bytes, src, 0,
                                         NULL, NULL),
                    "clEnqueueWriteBuffer", ERR(b));
}

static int cl_finish(dem_backend *b) { return cl_check(clFinish(b->q), "clFinish", ERR(b)); }

static int cl_map(dem_backend *b, dem_bufref r, size_t bytes, const void **host)
{
    cl_int e;
    *host = clEnqueueMapBuffer(b->q, *slot(b, r), CL_TRUE, CL_MAP_READ, 0, bytes ? bytes : 1, 0, NULL, NULL, &e);
    return cl_check(e, "clEnqueueMapBuffer", ERR(b));
}

static int cl_unmap(dem_backend *b, dem_bufref r, const void *host)
{
    return cl_check(clEnqueueUnmapMemObject(b->q, *slot(b, r), (void *)host, 0, NULL, NULL), "clEnqueueUnmapMemObject",
                    ERR(b));
}

static void cl_destroy(dem_backend *b)
{
    if (!b)
        return;
    if (b->q)
        clFinish(b->q); /* nothing to report any more: the backend goes */
    for (int id = 0; id < BUF__COUNT; id++)
        if (b->mem[id])
            clReleaseMemObject(b->mem[id]);
    for (int set = 0; set < 2; set++)
        for (int id = 0; id < ROW__COUNT; id++)
            if (b->rows[set][id])
                clReleaseMemObject(b->rows[set][id]);
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

/* A test build (-DDEM_TEST_LAWS) builds its kernels with the test-only laws too (common/laws/laws.h) */
#ifdef DEM_TEST_LAWS
#define DEM_TEST_LAW_OPTION " -DDEM_TEST_LAWS"
#else
#define DEM_TEST_LAW_OPTION ""
#endif

static void fnv1a(uint64_t *h, const unsigned char *p, size_t n)
{
    for (size_t k = 0; k < n; k++)
        *h = (*h ^ p[k]) * 1099511628211ull;
}

static int by_name(const void *a, const void *b) { return strcmp(*(char *const *)a, *(char *const *)b); }

/* FNV-1a over every file under the source folder's rel, in name order (subfolders walked, at most 8 deep: a link
 * to a folder above would never end), each as its path from the source folder and its bytes. */
static int hash_folder(const char *root, const char *rel, int depth, uint64_t *h, char *err, size_t errlen)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", root, rel);
    DIR *d = depth <= 8 ? opendir(path) : NULL;
    if (!d) {
        snprintf(err, errlen, "cannot open the kernel source folder %s/ (%s)", path,
                 depth <= 8 ? "set DEM_SOURCE_DIR to the project folder" : "folders nested too deep");
        return 1;
    }
    char **names = NULL;
    size_t count = 0;
    int rc = 0;
    for (struct dirent *e; !rc && (e = readdir(d));) {
        if (!strcmp(e->d_name, ".") || !strcmp(e->d_name, ".."))
            continue;
        char **grown = realloc(names, (count + 1) * sizeof *names);
        if (grown)
            names = grown;
        if (grown && (names[count] = strdup(e->d_name)))
            count++;
        else
            rc = snprintf(err, errlen, "out of host memory reading %s", path) > 0;
    }
    closedir(d);
    if (!rc && count)
        qsort(names, count, sizeof *names, by_name);
    for (size_t k = 0; !rc && k < count; k++) {
        char sub[4096];
        struct stat st;
        snprintf(sub, sizeof sub, "%s/%s", rel, names[k]);
        snprintf(path, sizeof path, "%s/%s", root, sub);
        if (stat(path, &st) == 0 && S_ISDIR(st.st_mode)) {
            rc = hash_folder(root, sub, depth + 1, h, err, errlen);
            continue;
        }
        FILE *fp = fopen(path, "rb");
        if (!fp) {
            rc = snprintf(err, errlen, "cannot read kernel source %s", path) > 0;
            continue;
        }
        unsigned char buf[16384];
        fnv1a(h, (const unsigned char *)sub, strlen(sub) + 1);
        for (size_t got; (got = fread(buf, 1, sizeof buf, fp)) > 0;)
            fnv1a(h, buf, got);
        fclose(fp);
    }
    for (size_t k = 0; k < count; k++)
        free(names[k]);
    free(names);
    return rc;
}

/* The program is built from kernels/program.cl with -DDEM_SOURCE_HASH=<hash of every file of its folders> appended to
 * the options: a compiler cache keyed on the main source text and options (PoCL's is) never serves a program built
 * from older headers. Every folder, not a list of headers: the program can include only what they hold (they are its
 * -I folders and the kernel file's own), so a new header cannot be left out of the hash (docs/design.md "The OpenCL
 * program is made from the kernel list"). The program's one line includes the file by its full path: the compiler
 * looks a file up in the working directory before the -I folders whatever the brackets (PoCL 3.1: a binning.cl where
 * dem ran was built instead of ours), and for a header a kernel file includes, there before the -I folders too; so
 * the kernel file names every header by its path from its own folder (../common/), where it is looked up first
 * (docs/design.md "Kernel sources are read at run time"). */
static int cl_program_build(dem_backend *b, const dem_setup *s, char *err, size_t errlen)
{
    const char *dir = s->source_dir;
    if (strpbrk(dir, "\"\n\\ ")) {
        snprintf(err, errlen, "the kernel source folder '%s' holds a space, quote, backslash or line break, which the "
                 "OpenCL build options and #include cannot name (set DEM_SOURCE_DIR to a plain path)", dir);
        return 1;
    }
    uint64_t hash = 1469598103934665603ull;
    for (size_t k = 0; k < sizeof source_folders / sizeof *source_folders; k++)
        if (hash_folder(dir, source_folders[k], 0, &hash, err, errlen))
            return 1;
    char options[8192], src[4200];
    int at = cl_build_options(options, sizeof options, dir, s->real_size);
    if (at < 0) {
        snprintf(err, errlen, "the kernel source folder '%s' is too long a path", dir);
        return 1;
    }
    snprintf(options + at, sizeof options - (size_t)at, " -DDEM_EFFECTS=%u -DDEM_SOURCE_HASH=0x%016llxULL %s%s",
             s->effects, (unsigned long long)hash, s->extra_build_options ? s->extra_build_options : "",
             DEM_TEST_LAW_OPTION);
    int w = snprintf(src, sizeof src, "#include \"%s/%s\"\n", dir, PROGRAM_FILE);
    if (w < 0 || (size_t)w >= sizeof src) {
        snprintf(err, errlen, "the kernel source folder '%s' is too long a path", dir);
        return 1;
    }
    if (cl_build(b->ctx, b->dev.device, src, options, &b->prog, err, errlen))
        return 1;
    snprintf(b->core.build, sizeof b->core.build, "OpenCL C built by %s (driver %s) with: %s", b->dev.device_name,
             b->dev.driver_version, options);
    cl_int e;
    for (int k = 0; k < K__COUNT; k++) {
        b->k[k] = clCreateKernel(b->prog, dem_kernel_names[k], &e);
        if (cl_check(e, dem_kernel_names[k], err, errlen))
            return 1;
    }
    return 0;
}

static int cl_create_held(dem_backend **out, const dem_setup *s, char *err, size_t errlen)
{
    dem_backend *b = calloc(1, sizeof *b);
    cl_int e;
    if (!b) {
        snprintf(err, errlen, "out of host memory");
        return 1;
    }
    dem_core_init(&b->core, s);
    b->profile = b->core.timed = getenv("DEM_PROFILE") != NULL;
    b->local = s->local_size;
    if (cl_device_get(s->device, &b->dev, err, errlen))
        goto fail;
    if (s->real_size == 8 && !b->dev.fp64) {
        snprintf(err, errlen, "device %s has no fp64 support (cl_khr_fp64); use fp32", b->dev.device_name);
        goto fail;
    }
    if (s->real_size == 4 && !b->dev.fp32_correct_div_sqrt) {
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
    if (cl_check(e, "clCreateCommandQueue", err, errlen) || cl_program_build(b, s, err, errlen))
        goto fail;
    snprintf(b->desc, sizeof b->desc, "OpenCL %s / %s (%s, driver %s), %s, work-group %s%zu", b->dev.platform_name,
             b->dev.device_name, b->dev.device_version, b->dev.driver_version, s->real_size == 8 ? "fp64" : "fp32",
             b->local ? "" : "auto", b->local);
    if (dem_buffers_create(&dem_opencl_ops, b, s) || cl_check(clFinish(b->q), "clFinish after upload", ERR(b))) {
        snprintf(err, errlen, "%s", b->core.err);
        goto fail;
    }
    *out = b;
    return 0;
fail:
    cl_destroy(b);
    return 1;
}

/* The backend made with the stop signals (SIGINT, SIGTERM, SIGHUP) held on the calling thread, and so on the threads
 * the OpenCL runtime starts meanwhile, which inherit its mask; the caller's mask is restored after, and a signal
 * that came meanwhile is delivered then. A signal during the program's build makes PoCL's in-process compiler (LLVM)
 * delete its temporary files and fail the build ("unable to rename temporary ..."): measured, a SIGINT 0.2 s into
 * `dem run tests/scenes/tablet_small.yaml` ended it as a device error (exit 69); held, the run stops before its first
 * step as the caller's handler decides. */
static int cl_create(dem_backend **out, const dem_setup *s, char *err, size_t errlen)
{
    sigset_t hold, old;
    sigemptyset(&hold);
    sigaddset(&hold, SIGINT), sigaddset(&hold, SIGTERM), sigaddset(&hold, SIGHUP);
    pthread_sigmask(SIG_BLOCK, &hold, &old);
    int rc = cl_create_held(out, s, err, errlen);
    pthread_sigmask(SIG_SETMASK, &old, NULL);
    return rc;
}

static const char *cl_describe(dem_backend *b) { return b->desc; }

static void cl_swap(dem_backend *b, int id1, int id2)
{
    cl_mem m = b->mem[id1];
    size_t n = b->core.bytes[id1];
    b->mem[id1] = b->mem[id2], b->core.bytes[id1] = b->core.bytes[id2];
    b->mem[id2] = m, b->core.bytes[id2] = n;
}

const dem_backend_ops dem_opencl_ops = {
    .name = "opencl",
    .create = cl_create,
    .destroy = cl_destroy,
    .describe = cl_describe,
    .alloc = cl_alloc,
    .launch = cl_launch,
    .fill_int = cl_fill_int,
    .copy = cl_copy,
    .read = cl_read,
    .write = cl_write,
    .finish = cl_finish,
    .map = cl_map,
    .unmap = cl_unmap,
    .swap = cl_swap,
};

/* the public device queries (dem.h): OpenCL's, so they live here and the driver (host/core/) holds no OpenCL call */
int dem_device_count(void) { return cl_device_count(); }

int dem_device_name(int k, char *buf, size_t len)
{
    cl_device_info_t info;
    char err[256];
    if (cl_device_get(k, &info, err, sizeof err)) {
        snprintf(buf, len, "%s", err);
        return DEM_ERR_DEVICE;
    }
    snprintf(buf, len, "%s / %s (%s)%s", info.platform_name, info.device_name, info.device_version,
             info.fp64 ? ", fp64" : "");
    return 0;
}

int dem_device_describe(int k, char *buf, size_t len)
{
    cl_device_info_t info;
    char err[256];
    if (cl_device_get(k, &info, err, sizeof err)) {
        snprintf(buf, len, "%s", err);
        return DEM_ERR_DEVICE;
    }
    snprintf(buf, len, "%u compute units at %u MHz, %.3g GiB global memory, work-groups up to %zu, driver %s",
             (unsigned)info.compute_units, (unsigned)info.clock_mhz, (double)info.global_mem / 1073741824.0,
             info.max_wg, info.driver_version);
    return 0;
}
