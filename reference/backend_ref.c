/* backend_ref.c - the reference backend: host arrays in `real`, each step a serial loop (ref_kernels.h).
 * Compiled once per precision; exports dem_reference_ops_f32 / dem_reference_ops_f64. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "ref_kernels.h"
#include "dem_layout.h"
#include "backend.h"

struct dem_backend {
    unsigned fx; /* effect mask (dem_effects.h), passed to every loop at run time */
    int n, nmat, nwalls, ncells, nblocks_scan, nblocks_red;
    int ncx, ncy, ncz;
    real dt, skin, half_skin2, inv_cell;
    vec3 g, lo;
    real *x, *v, *w, *f, *t, *radius, *invm, *invi, *x_build;
    int *mat;
    real *pairmat, *wall_real, *wall_hist, *wall_pf, *partial, *wall_force;
    unsigned *wall_mask;
    int *wall_int;
    int *cell_of, *cell_count, *cell_start, *cell_fill, *cell_particles, *block_sum;
    int maxn[2];    /* capacity of each row set */
    int *count[2], *list[2];
    real *hist[2];
    unsigned char *touch[2];
    int *mirror[2];
    int *in_count, *in_start, *in_block_sum; /* incoming pairs (lower-id partners) per particle, and their offsets */
    real *pair;                     /* PR_STRIDE reals per incoming pair, written by contact_pairs */
    real *invvol, *trace, *stress;  /* 1/V, MC-stress trace, output tensor */
    real *mc_fn[2], *mc_disp[2];    /* MC-strain per row slot, one per row set */
    real *mc_wall_fn, *mc_wall_disp;
    size_t pair_cap;                /* records allocated */
    int cur;        /* the row set in use; 1-cur is built into */
    int flags[FLAG_COUNT];
    double ktime[16]; /* seconds per step kind, see step_names */
    char err[256];
};

/* Time per step kind, for `make bench` (the reference has no kernels; these are its loops). */
enum { T_KICK_DRIFT, T_BIN, T_NBR_BUILD, T_NBR_CARRY, T_PAIRS, T_CONTACT, T_WALL, T_KICK, T_TRACE, T_TENSOR,
       T_MC_DISP, T_MC_UPDATE, T__COUNT };
static const char *const step_names[T__COUNT] = {"integrate_kick_drift", "binning", "nbr_build", "nbr_carry",
                                                 "contact_pairs", "contact_forces", "wall_reduce",
                                                 "integrate_kick", "stress_trace", "stress_tensor",
                                                 "mc_strain_disp", "mc_strain_update"};
static double wall_now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}
#define TIMED(b, id, stmt)                                                                                           \
    do {                                                                                                             \
        double t0_ = wall_now();                                                                                     \
        stmt;                                                                                                        \
        (b)->ktime[id] += wall_now() - t0_;                                                                          \
    } while (0)

static void *zalloc(size_t n, size_t size) { return calloc(n ? n : 1, size); }

static void ref_destroy(dem_backend *b)
{
    if (!b)
        return;
    void *ptrs[] = {b->x, b->v, b->w, b->f, b->t, b->radius, b->invm, b->invi, b->x_build, b->mat, b->pairmat,
                    b->wall_real, b->wall_hist, b->wall_pf, b->wall_mask, b->partial, b->wall_force, b->wall_int, b->cell_of,
                    b->cell_count, b->cell_start, b->cell_fill, b->cell_particles, b->block_sum, b->count[0],
                    b->count[1], b->list[0], b->list[1], b->hist[0], b->hist[1], b->touch[0], b->touch[1], b->mirror[0], b->mirror[1], b->pair,
                    b->in_count, b->in_start, b->in_block_sum, b->invvol, b->trace, b->stress, b->mc_fn[0],
                    b->mc_fn[1], b->mc_disp[0], b->mc_disp[1], b->mc_wall_fn, b->mc_wall_disp};
    for (size_t k = 0; k < sizeof ptrs / sizeof ptrs[0]; k++)
        free(ptrs[k]);
    free(b);
}

static real *dup_real(const void *src, size_t count)
{
    real *p = zalloc(count, sizeof(real));
    if (p && src && count)
        memcpy(p, src, count * sizeof(real));
    return p;
}

static int ref_create(dem_backend **out, const dem_setup *s, char *err, size_t errlen)
{
    if (s->real_size != (int)sizeof(real)) {
        snprintf(err, errlen, "reference backend built for %zu-byte reals, setup has %d", sizeof(real), s->real_size);
        return 1;
    }
    dem_backend *b = calloc(1, sizeof *b);
    if (!b)
        goto nomem;
    int n = s->n;
    b->n = n;
    b->nmat = s->nmat;
    b->nwalls = s->nwalls;
    b->ncx = s->ncell[0];
    b->ncy = s->ncell[1];
    b->ncz = s->ncell[2];
    b->ncells = b->ncx * b->ncy * b->ncz;
    b->nblocks_scan = (b->ncells + DEM_SCAN_BLOCK - 1) / DEM_SCAN_BLOCK;
    b->nblocks_red = (n + DEM_REDUCE_BLOCK - 1) / DEM_REDUCE_BLOCK;
    b->dt = (real)s->dt;
    b->skin = (real)s->skin;
    b->half_skin2 = (real)s->half_skin2;
    b->inv_cell = (real)s->inv_cell;
    b->g = v3((real)s->gravity[0], (real)s->gravity[1], (real)s->gravity[2]);
    b->lo = v3((real)s->lo[0], (real)s->lo[1], (real)s->lo[2]);
    b->x = dup_real(s->x, 3 * (size_t)n);
    b->v = dup_real(s->v, 3 * (size_t)n);
    b->w = dup_real(s->w, 3 * (size_t)n);
    b->f = zalloc(3 * (size_t)n, sizeof(real));
    b->t = zalloc(3 * (size_t)n, sizeof(real));
    b->radius = dup_real(s->radius, (size_t)n);
    b->invm = dup_real(s->invmass, (size_t)n);
    b->invi = dup_real(s->invinertia, (size_t)n);
    b->x_build = dup_real(s->x, 3 * (size_t)n);
    b->mat = zalloc((size_t)n, sizeof(int));
    b->pairmat = dup_real(s->pairmat, (size_t)PM_STRIDE * s->nmat * s->nmat);
    b->wall_real = dup_real(s->wall_real, (size_t)W_STRIDE * s->nwalls);
    b->wall_int = zalloc((size_t)WI_STRIDE * s->nwalls, sizeof(int));
    b->fx = s->effects;
    b->invvol = dup_real(s->invvol, (size_t)n);
    b->trace = zalloc(dem_field_size(FIELD_STRESS_TRACE, b->fx, (size_t)n, 0, 0, 0, 1), sizeof(real));
    b->mc_wall_fn = zalloc(dem_field_size(FIELD_MC_WALL_FORCE, b->fx, (size_t)n, 0, (size_t)s->nwalls, 0, 1),
                           sizeof(real));
    b->mc_wall_disp = zalloc(dem_field_size(FIELD_MC_WALL_DISP, b->fx, (size_t)n, 0, (size_t)s->nwalls, 0, 1),
                             sizeof(real));
    b->wall_hist = zalloc(dem_field_size(FIELD_WALL_HIST, b->fx, (size_t)n, 0, (size_t)s->nwalls, 0, 1), sizeof(real));
    b->wall_pf = zalloc(3 * (size_t)n * s->nwalls, sizeof(real));
    b->wall_mask = zalloc((size_t)n, sizeof(unsigned));
    b->partial = zalloc(3 * (size_t)b->nblocks_red * s->nwalls, sizeof(real));
    b->wall_force = zalloc(3 * (size_t)s->nwalls, sizeof(real));
    b->cell_of = zalloc((size_t)n, sizeof(int));
    b->cell_count = zalloc((size_t)b->ncells, sizeof(int));
    b->cell_start = zalloc((size_t)b->ncells + 1, sizeof(int));
    b->cell_fill = zalloc((size_t)b->ncells, sizeof(int));
    b->cell_particles = zalloc((size_t)n, sizeof(int));
    b->block_sum = zalloc((size_t)b->nblocks_scan, sizeof(int));
    for (int k = 0; k < 2; k++) {
        b->maxn[k] = s->maxn;
        b->count[k] = zalloc((size_t)n, sizeof(int));
        b->list[k] = zalloc((size_t)n * s->maxn, sizeof(int));
        b->hist[k] = zalloc(dem_field_size(FIELD_HIST, b->fx, (size_t)n, (size_t)s->maxn, 0, 0, 1), sizeof(real));
        b->touch[k] = zalloc((size_t)n * s->maxn, 1);
        b->mirror[k] = zalloc((size_t)n * s->maxn, sizeof(int));
        b->mc_fn[k] = zalloc(dem_field_size(FIELD_MC_FORCE, b->fx, (size_t)n, (size_t)s->maxn, 0, 0, 1), sizeof(real));
        b->mc_disp[k] = zalloc(dem_field_size(FIELD_MC_DISP, b->fx, (size_t)n, (size_t)s->maxn, 0, 0, 1), sizeof(real));
    }
    b->in_count = zalloc((size_t)n, sizeof(int));
    b->in_start = zalloc((size_t)n + 1, sizeof(int));
    b->in_block_sum = zalloc((size_t)(n + DEM_SCAN_BLOCK - 1) / DEM_SCAN_BLOCK, sizeof(int));
    b->pair_cap = 0;
    b->pair = NULL;
    if (!b->x || !b->v || !b->w || !b->f || !b->t || !b->radius || !b->invm || !b->invi || !b->x_build || !b->mat ||
        !b->pairmat || !b->wall_real || !b->wall_int || !b->wall_hist || !b->wall_pf || !b->wall_mask || !b->partial ||
        !b->wall_force || !b->cell_of || !b->cell_count || !b->cell_start || !b->cell_fill || !b->cell_particles ||
        !b->block_sum || !b->count[0] || !b->count[1] || !b->list[0] || !b->list[1] || !b->hist[0] || !b->hist[1] || !b->touch[0] || !b->touch[1] ||
        !b->mirror[0] || !b->mirror[1] || !b->in_count || !b->in_start || !b->in_block_sum || !b->invvol ||
        !b->trace || !b->mc_wall_fn || !b->mc_wall_disp || !b->mc_fn[0] || !b->mc_fn[1] || !b->mc_disp[0] ||
        !b->mc_disp[1])
        goto nomem;
    memcpy(b->mat, s->mat, (size_t)n * sizeof(int));
    if (s->nwalls)
        memcpy(b->wall_int, s->wall_int, (size_t)WI_STRIDE * s->nwalls * sizeof(int));
    *out = b;
    return 0;
nomem:
    ref_destroy(b);
    snprintf(err, errlen, "reference backend: out of host memory for %d particles", s->n);
    return 1;
}

static const char *ref_error(dem_backend *b) { return b->err; }
static const char *ref_describe(dem_backend *b)
{
    (void)b;
    return sizeof(real) == 8 ? "reference (serial C, fp64)" : "reference (serial C, fp32)";
}

static int ref_reset_flags(dem_backend *b)
{
    b->flags[FLAG_REBUILD] = 0;
    b->flags[FLAG_OUT_OF_DOMAIN] = DEM_NO_PARTICLE;
    b->flags[FLAG_NBR_NEEDED] = 0;
    b->flags[FLAG_ASYMMETRIC] = 0;
    b->flags[FLAG_MC_PENDING] = 0;
    return 0;
}

static int ref_kick_drift(dem_backend *b)
{
    TIMED(b, T_KICK_DRIFT,
          REF(ref_integrate_kick_drift)(b->fx, b->n, b->dt, b->g, b->half_skin2, b->x, b->v, b->w, b->f, b->t, b->invm,
                                        b->invi, b->x_build, b->flags));
    return 0;
}

static int ref_bin(dem_backend *b)
{
    double t0 = wall_now();
    memset(b->cell_count, 0, (size_t)b->ncells * sizeof(int));
    memset(b->cell_fill, 0, (size_t)b->ncells * sizeof(int));
    REF(ref_bin_index)(b->n, b->lo, b->inv_cell, b->ncx, b->ncy, b->ncz, b->x, b->cell_of, b->cell_count, b->flags);
    REF(ref_scan)(b->ncells, b->cell_count, b->block_sum, b->cell_start);
    REF(ref_bin_scatter)(b->n, b->cell_of, b->cell_start, b->cell_fill, b->cell_particles);
    REF(ref_bin_sort)(b->ncells, b->cell_start, b->cell_particles);
    b->ktime[T_BIN] += wall_now() - t0;
    return 0;
}

static int ref_nbr_reserve(dem_backend *b, int maxn)
{
    int k = 1 - b->cur;
    if (b->maxn[k] == maxn)
        return 0;
    int *list = zalloc((size_t)b->n * maxn, sizeof(int));
    real *hist = zalloc(dem_field_size(FIELD_HIST, b->fx, (size_t)b->n, (size_t)maxn, 0, 0, 1), sizeof(real));
    unsigned char *touch = zalloc((size_t)b->n * maxn, 1);
    int *mirror = zalloc((size_t)b->n * maxn, sizeof(int));
    real *mc_fn = zalloc(dem_field_size(FIELD_MC_FORCE, b->fx, (size_t)b->n, (size_t)maxn, 0, 0, 1), sizeof(real));
    real *mc_disp = zalloc(dem_field_size(FIELD_MC_DISP, b->fx, (size_t)b->n, (size_t)maxn, 0, 0, 1), sizeof(real));
    if (!list || !hist || !touch || !mirror || !mc_fn || !mc_disp) {
        free(list);
        free(hist);
        free(touch);
        free(mirror);
        free(mc_fn);
        free(mc_disp);
        snprintf(b->err, sizeof b->err, "out of host memory for neighbour rows of %d", maxn);
        return 1;
    }
    free(b->list[k]);
    free(b->hist[k]);
    free(b->touch[k]);
    free(b->mirror[k]);
    free(b->mc_fn[k]);
    free(b->mc_disp[k]);
    b->mc_fn[k] = mc_fn;
    b->mc_disp[k] = mc_disp;
    b->list[k] = list;
    b->hist[k] = hist;
    b->touch[k] = touch;
    b->mirror[k] = mirror;
    b->maxn[k] = maxn;
    return 0;
}

static int ref_nbr_build(dem_backend *b)
{
    int k = 1 - b->cur;
    TIMED(b, T_NBR_BUILD,
          REF(ref_nbr_build)(b->n, b->maxn[k], b->skin, b->ncx, b->ncy, b->ncz, b->x, b->radius, b->cell_of,
                             b->cell_start, b->cell_particles, b->count[k], b->list[k], b->in_count, b->flags));
    return 0;
}

static int ref_nbr_commit(dem_backend *b)
{
    int k = 1 - b->cur, o = b->cur;
    TIMED(b, T_NBR_CARRY,
          REF(ref_nbr_carry)(b->fx, b->n, b->maxn[k], b->maxn[o], b->count[k], b->list[k], b->count[o], b->list[o],
                             b->hist[o], b->touch[o], b->hist[k], b->touch[k], b->mirror[k],
                             b->flags, b->mc_fn[o], b->mc_fn[k]));
    b->cur = k;
    REF(ref_scan)(b->n, b->in_count, b->in_block_sum, b->in_start);
    size_t need = (size_t)b->in_start[b->n];
    if (need > b->pair_cap || !b->pair) { /* records are rewritten every step before they are read: no copy */
        size_t cap = need + need / 4 + 16;
        real *pr = zalloc((size_t)PR_STRIDE * cap, sizeof(real));
        if (!pr) {
            snprintf(b->err, sizeof b->err, "out of host memory for %zu pair records", cap);
            return 1;
        }
        free(b->pair);
        b->pair = pr;
        b->pair_cap = cap;
    }
    memcpy(b->x_build, b->x, 3 * (size_t)b->n * sizeof(real));
    return 0;
}

static int ref_contact_forces(dem_backend *b)
{
    int k = b->cur;
    TIMED(b, T_PAIRS,
          REF(ref_contact_pairs)(b->fx, b->n, b->maxn[k], b->nmat, b->dt, b->x, b->v, b->w, b->radius, b->invm, b->mat,
                                 b->pairmat, b->count[k], b->list[k], b->mirror[k], b->hist[k], b->touch[k],
                                 b->in_start, b->pair, b->f, b->t, b->trace, b->invvol, b->mc_disp[k], b->mc_fn[k]));
    TIMED(b, T_CONTACT,
          REF(ref_contact_forces)(b->fx, b->n, b->maxn[k], b->nmat, b->dt, b->x, b->v, b->w, b->radius, b->invm, b->mat,
                                  b->pairmat, b->count[k], b->list[k], b->mirror[k], b->touch[k], b->in_start, b->pair, b->f, b->t, b->nwalls, b->wall_int, b->wall_real,
                                  b->wall_hist, b->wall_pf, b->wall_mask, b->trace, b->invvol, b->mc_wall_disp,
                                  b->mc_wall_fn));
    return 0;
}

static int ref_stress_trace(dem_backend *b)
{
    int k = b->cur;
    TIMED(b, T_TRACE,
          REF(ref_stress_trace)(b->fx, b->n, b->maxn[k], b->nmat, b->x, b->radius, b->invvol, b->mat, b->pairmat,
                                b->count[k], b->list[k], b->nwalls, b->wall_int, b->wall_real, b->trace));
    return 0;
}

static int ref_stress_tensor(dem_backend *b)
{
    int k = b->cur;
    if (!b->stress && !(b->stress = zalloc((size_t)ST_STRIDE * b->n, sizeof(real)))) {
        snprintf(b->err, sizeof b->err, "out of host memory for the stress tensors");
        return 1;
    }
    TIMED(b, T_TENSOR,
          REF(ref_stress_tensor)(b->fx, b->n, b->maxn[k], b->nmat, b->x, b->radius, b->invvol, b->mat, b->pairmat,
                                 b->count[k], b->list[k], b->nwalls, b->wall_int, b->wall_real, b->stress));
    return 0;
}

static int ref_mc_strain_disp(dem_backend *b)
{
    int k = b->cur;
    TIMED(b, T_MC_DISP,
          REF(ref_mc_strain_disp)(b->fx, b->n, b->maxn[k], b->nmat, b->x, b->radius, b->mat, b->pairmat, b->count[k],
                                  b->list[k], b->nwalls, b->wall_int, b->wall_real, b->mc_fn[k], b->mc_wall_fn,
                                  b->mc_disp[k], b->mc_wall_disp));
    return 0;
}

static int ref_mc_strain_update(dem_backend *b, double tol)
{
    int k = b->cur;
    TIMED(b, T_MC_UPDATE,
          REF(ref_mc_strain_update)(b->fx, b->n, b->maxn[k], b->nmat, (real)tol, b->x, b->radius, b->mat, b->pairmat,
                                    b->count[k], b->list[k], b->mirror[k], b->nwalls, b->wall_int, b->wall_real,
                                    b->mc_disp[k], b->mc_wall_disp, b->mc_fn[k], b->mc_wall_fn, b->flags));
    return 0;
}

static int ref_wall_reduce(dem_backend *b)
{
    double t0 = wall_now();
    REF(ref_wall_reduce)(b->n, b->nwalls, b->nblocks_red, b->wall_pf, b->wall_mask, b->partial, b->wall_force);
    b->ktime[T_WALL] += wall_now() - t0;
    return 0;
}

static int ref_kick(dem_backend *b)
{
    TIMED(b, T_KICK, REF(ref_integrate_kick)(b->fx, b->n, b->dt, b->g, b->v, b->w, b->f, b->t, b->invm, b->invi));
    return 0;
}

/* Where each field lives and how large it is. */
static void *field_ptr(dem_backend *b, dem_field f, size_t *bytes)
{
    int k = b->cur;
    void *p[FIELD__COUNT] = {b->x, b->v, b->w, b->f, b->t, b->x_build, b->count[k], b->list[k], b->hist[k],
                             b->wall_hist, b->wall_force, b->cell_start, b->cell_particles, b->flags, b->wall_real,
                             b->touch[k], b->wall_mask, b->stress, b->trace, b->mc_fn[k], b->mc_wall_fn,
                             b->mc_disp[k], b->mc_wall_disp};
    *bytes = dem_field_size(f, b->fx, (size_t)b->n, (size_t)b->maxn[k], (size_t)b->nwalls, (size_t)b->ncells, sizeof(real));
    return (int)f >= 0 && f < FIELD__COUNT ? p[f] : NULL;
}

static int ref_read(dem_backend *b, dem_field f, void *dst, size_t bytes)
{
    size_t have;
    void *p = field_ptr(b, f, &have);
    if (!p || bytes > have) {
        snprintf(b->err, sizeof b->err, "read of field %d: %zu bytes asked, %zu held", (int)f, bytes, have);
        return 1;
    }
    memcpy(dst, p, bytes);
    return 0;
}

static int ref_write(dem_backend *b, dem_field f, const void *src, size_t bytes)
{
    size_t have;
    void *p = field_ptr(b, f, &have);
    if (!p || bytes > have) {
        snprintf(b->err, sizeof b->err, "write of field %d: %zu bytes given, %zu held", (int)f, bytes, have);
        return 1;
    }
    memcpy(p, src, bytes);
    return 0;
}

static int ref_finish(dem_backend *b) { (void)b; return 0; }

static int ref_set_walls(dem_backend *b, const void *src)
{
    memcpy(b->wall_real, src, (size_t)W_STRIDE * b->nwalls * sizeof(real));
    return 0;
}

static int ref_kernel_times(dem_backend *b, const char ***names, const double **seconds, int *count)
{
    *names = (const char **)step_names;
    *seconds = b->ktime;
    *count = T__COUNT;
    return 0;
}

const dem_backend_ops REF(dem_reference_ops) = {
    .name = sizeof(real) == 8 ? "reference-fp64" : "reference-fp32",
    .create = ref_create,
    .destroy = ref_destroy,
    .error = ref_error,
    .describe = ref_describe,
    .reset_flags = ref_reset_flags,
    .kick_drift = ref_kick_drift,
    .bin = ref_bin,
    .nbr_reserve = ref_nbr_reserve,
    .nbr_build = ref_nbr_build,
    .nbr_commit = ref_nbr_commit,
    .contact_forces = ref_contact_forces,
    .wall_reduce = ref_wall_reduce,
    .kick = ref_kick,
    .stress_trace = ref_stress_trace,
    .stress_tensor = ref_stress_tensor,
    .mc_strain_disp = ref_mc_strain_disp,
    .mc_strain_update = ref_mc_strain_update,
    .set_walls = ref_set_walls,
    .read = ref_read,
    .write = ref_write,
    .finish = ref_finish,
    .kernel_times = ref_kernel_times,
};
