/* scene_particles.c - particle groups of a scene: an explicit list, a CSV file, or a generated packing. */
#include "scene_particles.h"
#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

typedef struct {
    scene_origin *o;
    int n, cap;
} origin_list;

static int add_one(dem_sim *s, origin_list *ol, const double x[3], const double v[3], const double *w, double r,
                   int mat, int group, int index, int csv_line)
{
    int id = dem_add_particle(s, x, v, r, mat);
    if (id < 0)
        return -1;
    if (w && dem_set_particle_omega(s, id, w))
        return -1;
    if (ol->n == ol->cap) {
        int cap = ol->cap ? 2 * ol->cap : 1024;
        scene_origin *no = realloc(ol->o, sizeof *no * (size_t)cap);
        if (!no)
            return -1;
        ol->o = no;
        ol->cap = cap;
    }
    ol->o[ol->n++] = (scene_origin){group, index, csv_line, {x[0], x[1], x[2]}, r};
    return id;
}

/* ---- CSV: '#' comment lines, then a header naming the columns, then one sphere per line ---- */

static int csv_fail(const scene *sc, char *err, size_t errlen, int g, const char *file, int line, const char *col,
                    const char *why)
{
    char p[64], inner[1024];
    snprintf(p, sizeof p, "particles[%d].csv", g);
    snprintf(inner, sizeof inner, "%s:%d: %s%s%s", file, line, col ? col : "", col ? ": " : "", why);
    return scene_fail(sc, err, errlen, p, "%s", inner);
}

static int load_csv(const scene *sc, dem_sim *s, origin_list *ol, int g, int mat, char *err, size_t errlen)
{
    const scene_particles *pg = &sc->f->particles[g];
    char file[4096];
    scene_file_path(sc, pg->csv, file, sizeof file);
    char why[256];
    FILE *fp = scene_open_regular(file, why, sizeof why);
    if (!fp) {
        char p[64];
        snprintf(p, sizeof p, "particles[%d].csv", g);
        return scene_fail(sc, err, errlen, p, "cannot open '%s': %s", file, why);
    }
    enum { C_X, C_Y, C_Z, C_R, C_D, C_VX, C_VY, C_VZ, C_RHO, C__N };
    static const char *names[C__N] = {"x", "y", "z", "radius", "diameter", "vx", "vy", "vz", "density"};
    int col[C__N], ncol = 0, line = 0, count = 0, rc = 0, have_header = 0;
    for (int k = 0; k < C__N; k++)
        col[k] = -1;
    char buf[4096];
    double rho = sc->f->materials[mat].density;
    const char *dens = sc->f->particles[g].csv_density;
    if (dens && strcmp(dens, "check") && strcmp(dens, "ignore")) {
        fclose(fp);
        char p[64];
        snprintf(p, sizeof p, "particles[%d].csv_density", g);
        return scene_fail(sc, err, errlen, p, "must be 'check' or 'ignore' (got '%s')", dens);
    }
    int check_density = !dens || !strcmp(dens, "check");
    while (!rc && fgets(buf, sizeof buf, fp)) {
        line++;
        size_t len = strlen(buf);
        if (len == sizeof buf - 1 && buf[len - 1] != '\n') {
            rc = csv_fail(sc, err, errlen, g, file, line, NULL, "line longer than 4095 characters");
            break;
        }
        while (len && (buf[len - 1] == '\n' || buf[len - 1] == '\r'))
            buf[--len] = 0;
        char *t = buf;
        while (*t == ' ' || *t == '\t')
            t++;
        if (!*t || *t == '#')
            continue;
        char *field[64];
        int nf = 0;
        for (char *cur = t; cur && nf < 64;) {
            char *f = strsep(&cur, ",");
            while (*f == ' ')
                f++;
            field[nf++] = f;
        }
        if (!have_header) {
            have_header = 1;
            ncol = nf;
            for (int k = 0; k < nf; k++) {
                char *e = field[k] + strlen(field[k]);
                while (e > field[k] && e[-1] == ' ')
                    *--e = 0;
                for (int q = 0; q < C__N; q++)
                    if (!strcmp(field[k], names[q]))
                        col[q] = k;
            }
            if (col[C_X] < 0 || col[C_Y] < 0 || col[C_Z] < 0 || (col[C_R] < 0 && col[C_D] < 0))
                rc = csv_fail(sc, err, errlen, g, file, line, NULL,
                              "header must name columns x, y, z and radius or diameter");
            continue;
        }
        if (nf != ncol) {
            char why[128];
            snprintf(why, sizeof why, "%d fields, the header has %d", nf, ncol);
            rc = csv_fail(sc, err, errlen, g, file, line, NULL, why);
            break;
        }
        double val[C__N] = {0};
        for (int q = 0; q < C__N && !rc; q++) {
            if (col[q] < 0)
                continue;
            char *end;
            errno = 0;
            val[q] = strtod(field[col[q]], &end);
            while (*end == ' ')
                end++;
            if (end == field[col[q]] || *end || errno || !isfinite(val[q]))
                rc = csv_fail(sc, err, errlen, g, file, line, names[q], "not a finite number");
        }
        if (rc)
            break;
        double r = col[C_R] >= 0 ? val[C_R] : 0.5 * val[C_D];
        if (!(r > 0)) {
            rc = csv_fail(sc, err, errlen, g, file, line, col[C_R] >= 0 ? "radius" : "diameter", "must be > 0 m");
            break;
        }
        if (check_density && col[C_RHO] >= 0 && fabs(val[C_RHO] - rho) > 1e-9 * rho) {
            char why[256];
            snprintf(why, sizeof why, "%g kg/m^3 differs from material '%s' (%g kg/m^3)", val[C_RHO],
                     sc->f->materials[mat].name, rho);
            rc = csv_fail(sc, err, errlen, g, file, line, "density", why);
            break;
        }
        double x[3] = {val[C_X], val[C_Y], val[C_Z]}, v[3] = {val[C_VX], val[C_VY], val[C_VZ]};
        if (add_one(s, ol, x, v, NULL, r, mat, g, count, line) < 0) {
            rc = csv_fail(sc, err, errlen, g, file, line, NULL, dem_error(s));
            break;
        }
        count++;
    }
    if (!rc && ferror(fp))
        rc = csv_fail(sc, err, errlen, g, file, line, NULL, "read error");
    fclose(fp);
    if (!rc && count == 0)
        rc = csv_fail(sc, err, errlen, g, file, line, NULL, "no particles in the file");
    return rc;
}

/* ---- generated packings ---- */

/* Largest generated group (the fuzz build lowers it so that one input cannot exhaust memory). */
#ifndef DEM_SCENE_MAX_GENERATED
#define DEM_SCENE_MAX_GENERATED 5000000
#endif
#ifndef DEM_SCENE_MAX_RANDOM
#define DEM_SCENE_MAX_RANDOM 2000000
#endif
/* Random sequential addition's attempt budget: at most DEM_RSA_TRIES_PER_SPHERE candidates for one sphere, and
 * DEM_RSA_ATTEMPTS_PER_SPHERE * count + DEM_RSA_ATTEMPTS_BASE for the whole group: time linear in the count. An
 * attempt costs about 0.08 us on one core (up to 27 cells of a spatial hash, own cell first) while the region is
 * loose, more near jamming (the hash's buckets are shared by more spheres): a group of 200 000 is placed or refused
 * within about 0.4 s (measured 0.30-0.38 s for refusals at 27-41 % on this 2-core VM); the budget reaches about
 * 27 % of a box's volume with equal spheres at that count (more for fewer spheres, where the base dominates).
 * dem check reports each group's time and volume share ("fill"). A placement is a pure function of the scene: the budget counts attempts, never time. Denser
 * packings: place loosely and let gravity or a moving wall compact them (docs/scenes.md). */
#define DEM_RSA_TRIES_PER_SPHERE 20000L
#define DEM_RSA_ATTEMPTS_PER_SPHERE 16L
#define DEM_RSA_ATTEMPTS_BASE 100000L

static uint64_t rng_next(uint64_t *st) /* splitmix64: reproducible on every platform */
{
    uint64_t z = (*st += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}
static double rng_unit(uint64_t *st) { return (double)(rng_next(st) >> 11) * (1.0 / 9007199254740992.0); }

typedef struct {
    int cyl;
    double lo[3], hi[3];           /* box, or the cylinder's bounding box */
    double base[3], axis[3], R, H; /* cylinder */
} region;

/* Spatial hash of the spheres placed so far, for random sequential addition: cubic cells of the largest diameter, so
 * a sphere can only overlap spheres of the 27 cells around its own; each candidate looks there instead of at every
 * sphere placed (O(n) per candidate made a refusal at the largest count take 14 s). The accept/reject decision is
 * the same as against every sphere (it is a conjunction of the same pairwise tests), so packings are unchanged. */
typedef struct {
    double cell;
    long long nb;   /* buckets, a power of two */
    int *head;      /* [nb]: first sphere of the bucket, -1 if none */
    int *next;      /* [cap]: next sphere in the same bucket */
    int cap;
} sphere_hash;

static long long cell_of(double v, double cell)
{
    double c = floor(v / cell);
    if (c != c) /* nan (regions are finite, so only from a bug): one cell, never an undefined conversion */
        return 0;
    return c < -1e9 ? -1000000000LL : c > 1e9 ? 1000000000LL : (long long)c;
}

static long long bucket_of(const sphere_hash *h, long long ix, long long iy, long long iz)
{
    unsigned long long k = (unsigned long long)ix * 73856093ull ^ (unsigned long long)iy * 19349663ull ^
                           (unsigned long long)iz * 83492791ull;
    return (long long)(k & (unsigned long long)(h->nb - 1));
}

static int hash_insert(sphere_hash *h, const scene_origin *o, int j)
{
    if (j >= h->cap) {
        int cap = h->cap ? 2 * h->cap : 1024;
        while (cap <= j)
            cap *= 2;
        int *nx = realloc(h->next, sizeof(int) * (size_t)cap);
        if (!nx)
            return -1;
        h->next = nx, h->cap = cap;
    }
    const double *x = o[j].x;
    long long b = bucket_of(h, cell_of(x[0], h->cell), cell_of(x[1], h->cell), cell_of(x[2], h->cell));
    h->next[j] = h->head[b];
    h->head[b] = j;
    return 0;
}

/* Does a sphere of radius r at x stay clear of every sphere in the hash? */
static int hash_clear(const sphere_hash *h, const scene_origin *o, const double *x, double r)
{
    long long c[3];
    for (int d = 0; d < 3; d++)
        c[d] = cell_of(x[d], h->cell);
    static const int off[3] = {0, -1, 1}; /* own cell first: a rejection usually comes from there */
    for (int a = 0; a < 3; a++)
        for (int b = 0; b < 3; b++)
            for (int e = 0; e < 3; e++)
                for (int j = h->head[bucket_of(h, c[0] + off[a], c[1] + off[b], c[2] + off[e])]; j >= 0;
                     j = h->next[j]) {
                    const double *y = o[j].x;
                    double dx = x[0] - y[0], dy = x[1] - y[1], dz = x[2] - y[2], rs = r + o[j].r;
                    if (dx * dx + dy * dy + dz * dz < rs * rs)
                        return 0;
                }
    return 1;
}

static int cmp_desc(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? 1 : x > y ? -1 : 0;
}

static double region_volume(const region *rg)
{
    if (rg->cyl)
        return M_PI * rg->R * rg->R * rg->H;
    return (rg->hi[0] - rg->lo[0]) * (rg->hi[1] - rg->lo[1]) * (rg->hi[2] - rg->lo[2]);
}

/* Is a sphere of radius r at x wholly inside the region? */
static int inside(const region *rg, const double *x, double r)
{
    if (!rg->cyl) {
        for (int d = 0; d < 3; d++)
            if (x[d] - r < rg->lo[d] || x[d] + r > rg->hi[d])
                return 0;
        return 1;
    }
    double d[3] = {x[0] - rg->base[0], x[1] - rg->base[1], x[2] - rg->base[2]};
    double h = d[0] * rg->axis[0] + d[1] * rg->axis[1] + d[2] * rg->axis[2];
    double rad[3] = {d[0] - h * rg->axis[0], d[1] - h * rg->axis[1], d[2] - h * rg->axis[2]};
    double rho = sqrt(rad[0] * rad[0] + rad[1] * rad[1] + rad[2] * rad[2]);
    return h - r >= 0 && h + r <= rg->H && rho + r <= rg->R;
}

static int make_region(const scene *sc, int g, const scene_generate *gen, region *rg, char *err, size_t errlen)
{
    char p[96];
    memset(rg, 0, sizeof *rg);
    if (!strcmp(gen->shape, "box")) {
        for (int d = 0; d < 3; d++)
            if (!(gen->region.hi[d] > gen->region.lo[d]) || !isfinite(gen->region.lo[d]) ||
                !isfinite(gen->region.hi[d])) { /* an infinite bound puts spheres at inf or nan */
                snprintf(p, sizeof p, "particles[%d].generate.region", g);
                return scene_fail(sc, err, errlen, p, "a box region needs finite lo < hi on every axis");
            }
        memcpy(rg->lo, gen->region.lo, sizeof rg->lo);
        memcpy(rg->hi, gen->region.hi, sizeof rg->hi);
        return 0;
    }
    if (strcmp(gen->shape, "cylinder")) {
        snprintf(p, sizeof p, "particles[%d].generate.shape", g);
        return scene_fail(sc, err, errlen, p, "shape must be box or cylinder (got '%s')", gen->shape);
    }
    const double *a = gen->region.axis;
    double an = sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    const double *b = gen->region.base;
    if (!(an > 0) || !isfinite(an) || !(gen->region.radius > 0) || !(gen->region.height > 0) ||
        !isfinite(gen->region.radius) || !isfinite(gen->region.height) || !isfinite(b[0] + b[1] + b[2])) {
        snprintf(p, sizeof p, "particles[%d].generate.region", g);
        return scene_fail(sc, err, errlen, p, "a cylinder region needs a finite base, a finite non-zero axis, and "
                                              "finite radius > 0 and height > 0");
    }
    rg->cyl = 1;
    rg->R = gen->region.radius;
    rg->H = gen->region.height;
    for (int d = 0; d < 3; d++) {
        rg->axis[d] = a[d] / an;
        rg->base[d] = gen->region.base[d];
    }
    for (int d = 0; d < 3; d++) { /* bounding box of the two end discs */
        double top = rg->base[d] + rg->H * rg->axis[d], ext = rg->R * sqrt(fmax(0, 1 - rg->axis[d] * rg->axis[d]));
        rg->lo[d] = fmin(rg->base[d], top) - ext;
        rg->hi[d] = fmax(rg->base[d], top) + ext;
    }
    return 0;
}

/* Listed sizes: each radius's share of the n spheres (by number, or by volume: number share ~ f / r^3), rounded down,
 * the spheres left over going to the largest remainders (the earlier size on a tie). No random draw. */
static int listed_radii(const scene *sc, int g, const scene_generate *gen, int n, double *r, char *err, size_t errlen)
{
    char p[96];
    unsigned k, m = gen->sizes_count;
    int by_volume = 0;
    if (gen->fractions) {
        by_volume = !strcmp(gen->fractions, "volume");
        if (!by_volume && strcmp(gen->fractions, "number")) {
            snprintf(p, sizeof p, "particles[%d].generate.fractions", g);
            return scene_fail(sc, err, errlen, p, "fractions must be number or volume (got '%s')", gen->fractions);
        }
    }
    double sum = 0, q[64], norm = 0;
    for (k = 0; k < m; k++) {
        snprintf(p, sizeof p, "particles[%d].generate.sizes[%u]", g, k);
        if (!(gen->sizes[k].radius > 0) || !isfinite(gen->sizes[k].radius) || !(gen->sizes[k].fraction >= 0) ||
            !(gen->sizes[k].fraction <= 1))
            return scene_fail(sc, err, errlen, p, "each size needs radius > 0 m and 0 <= fraction <= 1");
        sum += gen->sizes[k].fraction;
        double rr = gen->sizes[k].radius;
        q[k] = by_volume ? gen->sizes[k].fraction / (rr * rr * rr) : gen->sizes[k].fraction;
        if (!isfinite(q[k]))
            return scene_fail(sc, err, errlen, p, "radius %g m is too small to weigh by volume", rr);
        norm += q[k];
    }
    snprintf(p, sizeof p, "particles[%d].generate.sizes", g);
    if (!(fabs(sum - 1) <= 1e-3))
        return scene_fail(sc, err, errlen, p, "the fractions must add up to 1 (got %.6g)", sum);
    if (!(norm > 0) || !isfinite(norm))
        return scene_fail(sc, err, errlen, p, "the radii are too far apart to weigh by volume");
    long cnt[64], given = 0;
    double rem[64];
    for (k = 0; k < m; k++) {
        double want = q[k] / norm * n;
        cnt[k] = (long)floor(want);
        rem[k] = want - (double)cnt[k];
        given += cnt[k];
    }
    for (; given < n; given++) { /* the largest remainder first, the earlier size on a tie */
        unsigned best = 0;
        for (k = 1; k < m; k++)
            if (rem[k] > rem[best])
                best = k;
        cnt[best]++;
        rem[best] = -1;
    }
    int i = 0;
    for (k = 0; k < m; k++)
        for (long c = 0; c < cnt[k] && i < n; c++)
            r[i++] = gen->sizes[k].radius;
    return 0;
}

/* Lognormal radii (median, sigma of ln r), truncated to [rmin, rmax] by drawing again. The draw uses the C library's
 * log, exp and cos (Box-Muller): the same scene gives the same radii with the same C library. */
static int lognormal_radii(const scene *sc, int g, const scene_generate *gen, double rmin, double rmax, int n,
                           double *r, uint64_t *st, char *err, size_t errlen)
{
    char p[96];
    double med = gen->lognormal->median, sig = gen->lognormal->sigma;
    snprintf(p, sizeof p, "particles[%d].generate.lognormal", g);
    if (!(med > 0) || !isfinite(med) || !(sig >= 0) || !(sig <= 3))
        return scene_fail(sc, err, errlen, p, "a lognormal needs median > 0 m and 0 <= sigma <= 3");
    /* the share of the distribution inside the bounds: below 1 % the draws would mostly be thrown away */
    double share = sig > 0 ? 0.5 * (erf(log(rmax / med) / (sig * sqrt(2.0))) - erf(log(rmin / med) / (sig * sqrt(2.0))))
                           : (med >= rmin && med <= rmax);
    if (!(share >= 0.01))
        return scene_fail(sc, err, errlen, p, "only %.3g %% of this lognormal lies within radius_min %g m and radius_max "
                          "%g m (want at least 1 %%)", 100 * share, rmin, rmax);
    /* at least 1 % of the draws land (above): 1000 per sphere is a bound no proper case reaches */
    long draws = 0, max_draws = 1000L * n + 1000000L;
    int i = 0;
    for (; i < n && draws < max_draws; draws++) {
        double u1 = rng_unit(st), u2 = rng_unit(st);
        double z = sqrt(-2 * log(u1 > 0 ? u1 : 1e-300)) * cos(2 * M_PI * u2);
        double v = med * exp(sig * z);
        if (v >= rmin && v <= rmax)
            r[i++] = v;
    }
    if (i < n)
        return scene_fail(sc, err, errlen, p, "%ld draws of this lognormal gave too few radii within radius_min %g m and "
                          "radius_max %g m", max_draws, rmin, rmax);
    return 0;
}

static int generate(const scene *sc, dem_sim *s, origin_list *ol, int g, int mat, char *fill, size_t fill_len,
                    char *err, size_t errlen)
{
    const scene_generate *gen = sc->f->particles[g].generate;
    char p[96];
    region rg;
    if (make_region(sc, g, gen, &rg, err, errlen))
        return 1;
    double rmin = gen->radius, rmax = gen->radius;
    snprintf(p, sizeof p, "particles[%d].generate.radius", g);
    int has_r = scene_has(sc->loc, p);
    if ((has_r != 0) + (gen->lognormal != NULL) + (gen->sizes_count > 0) > 1) {
        snprintf(p, sizeof p, "particles[%d].generate", g);
        return scene_fail(sc, err, errlen, p, "give one of radius, radius_min/radius_max, lognormal or sizes");
    }
    if (gen->fractions && !gen->sizes_count) {
        snprintf(p, sizeof p, "particles[%d].generate.fractions", g);
        return scene_fail(sc, err, errlen, p, "fractions weigh listed sizes: give sizes too");
    }
    if ((gen->lognormal || gen->sizes_count) && strcmp(gen->kind, "random")) {
        snprintf(p, sizeof p, "particles[%d].generate.%s", g, gen->lognormal ? "lognormal" : "sizes");
        return scene_fail(sc, err, errlen, p, "size distributions are for kind: random");
    }
    if (gen->sizes_count) { /* the listed radii bound the group */
        rmin = INFINITY, rmax = 0;
        for (unsigned k = 0; k < gen->sizes_count; k++) {
            rmin = fmin(rmin, gen->sizes[k].radius);
            rmax = fmax(rmax, gen->sizes[k].radius);
        }
        snprintf(p, sizeof p, "particles[%d].generate.radius_min", g);
        if (scene_has(sc->loc, p) || (snprintf(p, sizeof p, "particles[%d].generate.radius_max", g), scene_has(sc->loc, p)))
            return scene_fail(sc, err, errlen, p, "listed sizes give their own radii: no radius_min or radius_max");
    } else if (!has_r) {
        rmin = gen->radius_min;
        rmax = gen->radius_max;
        if (!(rmin > 0) || !(rmax >= rmin) || !isfinite(rmax)) {
            snprintf(p, sizeof p, "particles[%d].generate.radius_min", g);
            return scene_fail(sc, err, errlen, p, gen->lognormal ? "a lognormal needs its bounds: 0 < radius_min <= "
                                                                   "radius_max [m]"
                                                                 : "give radius, or 0 < radius_min <= radius_max [m]");
        }
    } else if (!(rmin > 0) || !isfinite(rmin)) {
        return scene_fail(sc, err, errlen, p, "radius must be > 0 m");
    }
    if (!(gen->speed >= 0) || !isfinite(gen->speed)) {
        snprintf(p, sizeof p, "particles[%d].generate.speed", g);
        return scene_fail(sc, err, errlen, p, "speed must be >= 0 m/s");
    }
    uint64_t st = 0x5eed0000ull + gen->seed;
    int random = !strcmp(gen->kind, "random");
    if (!random && strcmp(gen->kind, "lattice")) {
        snprintf(p, sizeof p, "particles[%d].generate.kind", g);
        return scene_fail(sc, err, errlen, p, "kind must be random or lattice (got '%s')", gen->kind);
    }
    int placed = 0;
    if (random) {
        snprintf(p, sizeof p, "particles[%d].generate.count", g);
        if (gen->count < 1 || gen->count > DEM_SCENE_MAX_RANDOM)
            return scene_fail(sc, err, errlen, p, "a random packing needs 1 <= count <= %d", DEM_SCENE_MAX_RANDOM);
        /* random sequential addition, largest first, clear of every sphere placed before (all groups) */
        struct timespec t0, t1;
        clock_gettime(CLOCK_MONOTONIC, &t0);
        int n = (int)gen->count;
        double *r = malloc(sizeof(double) * n);
        if (!r)
            return scene_fail(sc, err, errlen, p, "out of memory");
        if (gen->sizes_count) {
            if (listed_radii(sc, g, gen, n, r, err, errlen)) {
                free(r);
                return 1;
            }
        } else if (gen->lognormal) {
            if (lognormal_radii(sc, g, gen, rmin, rmax, n, r, &st, err, errlen)) {
                free(r);
                return 1;
            }
        } else {
            for (int i = 0; i < n; i++)
                r[i] = rmin + (rmax - rmin) * rng_unit(&st);
        }
        /* descending radii; equal radii are equal bits, so any sort gives the same array */
        qsort(r, (size_t)n, sizeof *r, cmp_desc);
        /* a region the spheres cannot fit is refused at once: random sequential addition jams at 38.4 % of the
         * volume for equal spheres, a little more for mixed sizes; above 42 % the attempts would only burn time */
        double vol = 0;
        for (int i = 0; i < n; i++)
            vol += 4.0 / 3.0 * M_PI * r[i] * r[i] * r[i];
        if (!(vol <= 0.42 * region_volume(&rg))) {
            free(r);
            return scene_fail(sc, err, errlen, p,
                              "%d spheres fill %.0f %% of the region: a random loose packing jams near 38 %% (try kind: "
                              "lattice, fewer or smaller spheres, or a larger region)",
                              n, 100 * vol / region_volume(&rg));
        }
        double big = r[0];
        for (int j = 0; j < ol->n; j++)
            big = ol->o[j].r > big ? ol->o[j].r : big;
        sphere_hash h = {2 * big, 1, NULL, NULL, 0};
        while (h.nb < 2LL * (ol->n + n))
            h.nb *= 2;
        h.head = malloc(sizeof(int) * (size_t)h.nb);
        int hfail = !h.head;
        for (long long b = 0; !hfail && b < h.nb; b++)
            h.head[b] = -1;
        for (int j = 0; j < ol->n && !hfail; j++) /* every sphere placed so far, earlier groups too */
            hfail = hash_insert(&h, ol->o, j);
        /* each sphere gets a bounded number of tries, and the group a bounded total, so a refusal comes quickly */
        long attempts = 0, max_attempts = DEM_RSA_ATTEMPTS_PER_SPHERE * n + DEM_RSA_ATTEMPTS_BASE, tries = 0,
             max_tries = DEM_RSA_TRIES_PER_SPHERE;
        for (int i = 0; !hfail && i < n && attempts < max_attempts && tries < max_tries; attempts++, tries++) {
            double x[3];
            for (int d = 0; d < 3; d++)
                x[d] = rg.lo[d] + (rg.hi[d] - rg.lo[d]) * rng_unit(&st);
            if (!inside(&rg, x, r[i]))
                continue;
            if (!hash_clear(&h, ol->o, x, r[i]))
                continue;
            double v[3];
            for (int d = 0; d < 3; d++)
                v[d] = gen->speed * (2 * rng_unit(&st) - 1);
            if (add_one(s, ol, x, v, NULL, r[i], mat, g, i, 0) < 0) {
                free(r), free(h.head), free(h.next);
                return scene_fail(sc, err, errlen, p, "%s", dem_error(s));
            }
            hfail = hash_insert(&h, ol->o, ol->n - 1);
            i++;
            placed = i;
            tries = -1; /* the next sphere starts its own count */
        }
        double vplaced = 0;
        for (int i = 0; i < placed; i++)
            vplaced += 4.0 / 3.0 * M_PI * r[i] * r[i] * r[i];
        clock_gettime(CLOCK_MONOTONIC, &t1);
        size_t o = strlen(fill);
        if (o < fill_len)
            snprintf(fill + o, fill_len - o, "%sgroup %d: %d spheres (radius %.4g to %.4g m) fill %.1f %% of the region's "
                     "volume, placed in %.2f s (%ld attempts)", o ? "\n               " : "", g, placed, r[n - 1], r[0],
                     100 * vplaced / region_volume(&rg), (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec),
                     attempts);
        free(r), free(h.head), free(h.next);
        if (hfail)
            return scene_fail(sc, err, errlen, p, "out of memory");
        if (placed < n) {
            char why[96];
            if (tries >= max_tries)
                snprintf(why, sizeof why, "no place for sphere %d in %ld tries", placed + 1, max_tries);
            else
                snprintf(why, sizeof why, "the budget of %ld attempts (%ld per sphere + %ld) is spent", max_attempts,
                         DEM_RSA_ATTEMPTS_PER_SPHERE, DEM_RSA_ATTEMPTS_BASE);
            return scene_fail(sc, err, errlen, p,
                              "could place only %d of %d spheres without overlap (%.1f %% of the region filled; %s): "
                              "random placement is for loose packings (place fewer or smaller spheres in a larger "
                              "region and let gravity or a wall compact them, or use kind: lattice)",
                              placed, n, 100 * vplaced / region_volume(&rg), why);
        }
        return 0;
    }
    double a = gen->spacing > 0 ? gen->spacing : 2 * rmax;
    snprintf(p, sizeof p, "particles[%d].generate.spacing", g);
    if (a < 2 * rmax)
        return scene_fail(sc, err, errlen, p, "lattice spacing %g m is below the largest diameter %g m", a, 2 * rmax);
    int nx[3];
    double sites = 1;
    for (int d = 0; d < 3; d++) {
        double c = floor((rg.hi[d] - rg.lo[d] - 2 * rmax) / a) + 1;
        nx[d] = c > 0 && c < 1e7 ? (int)c : 0;
        sites *= c > 0 ? c : 0;
    }
    if (!(sites <= DEM_SCENE_MAX_GENERATED) && !(gen->count && gen->count <= DEM_SCENE_MAX_GENERATED)) {
        snprintf(p, sizeof p, "particles[%d].generate.region", g);
        return scene_fail(sc, err, errlen, p, "the lattice has %.3g sites, more than %d: give count or a smaller "
                          "region", sites, DEM_SCENE_MAX_GENERATED);
    }
    int full = 0;      /* count reached, or the cap on visited sites */
    long visited = 0;  /* sites looked at: a huge region whose shape rejects most sites must still end (make fuzz) */
    for (int k = 0; k < nx[2] && !full; k++)
        for (int j = 0; j < nx[1] && !full; j++)
            for (int i = 0; i < nx[0] && !full; i++) {
                if ((gen->count && placed >= (int)gen->count) || visited++ >= DEM_SCENE_MAX_GENERATED) {
                    full = 1;
                    break;
                }
                double x[3] = {rg.lo[0] + rmax + i * a, rg.lo[1] + rmax + j * a, rg.lo[2] + rmax + k * a};
                double r = rmin + (rmax - rmin) * rng_unit(&st);
                if (!inside(&rg, x, rmax))
                    continue;
                double v[3];
                for (int d = 0; d < 3; d++)
                    v[d] = gen->speed * (2 * rng_unit(&st) - 1);
                if (add_one(s, ol, x, v, NULL, r, mat, g, placed, 0) < 0)
                    return scene_fail(sc, err, errlen, p, "%s", dem_error(s));
                placed++;
            }
    if (placed == 0 || (gen->count && placed < (int)gen->count)) {
        snprintf(p, sizeof p, "particles[%d].generate", g);
        return scene_fail(sc, err, errlen, p, "the lattice holds only %d spheres%s in the %ld sites looked at", placed,
                          gen->count ? " (fewer than count)" : "", visited);
    }
    return 0;
}

/* The group's constraints (hold, fixed_rotation) on its particles first .. ol->n - 1 */
static int constrain(const scene *sc, dem_sim *s, unsigned g, int first, int last, char *err, size_t errlen)
{
    const scene_particles *pg = &sc->f->particles[g];
    unsigned flags = pg->fixed_rotation ? DEM_PARTICLE_NO_ROTATION : 0;
    for (unsigned k = 0; k < pg->hold_count; k++) {
        const char *a = pg->hold[k];
        unsigned bit = !strcmp(a, "x") ? DEM_PARTICLE_HOLD_VX : !strcmp(a, "y") ? DEM_PARTICLE_HOLD_VY
                     : !strcmp(a, "z") ? DEM_PARTICLE_HOLD_VZ : 0;
        char p[96];
        snprintf(p, sizeof p, "particles[%u].hold[%u]", g, k);
        if (!bit)
            return scene_fail(sc, err, errlen, p, "'%s' is not an axis (x, y or z)", a);
        if (flags & bit)
            return scene_fail(sc, err, errlen, p, "axis '%s' is listed twice", a);
        flags |= bit;
    }
    for (int i = first; flags && i < last; i++)
        dem_set_particle_flags(s, i, flags);
    return 0;
}

int scene_add_particles(const scene *sc, dem_sim *s, scene_origin **origin, char *fill, size_t fill_len, char *err,
                        size_t errlen)
{
    origin_list ol = {NULL, 0, 0};
    if (fill_len)
        fill[0] = 0;
    int rc = 0;
    for (unsigned g = 0; g < sc->f->particles_count && !rc; g++) {
        const scene_particles *pg = &sc->f->particles[g];
        int first = dem_count(s);
        char p[96];
        snprintf(p, sizeof p, "particles[%u].material", g);
        int mat = scene_material_id(sc, pg->material);
        if (mat < 0) {
            char hint[300];
            rc = scene_fail(sc, err, errlen, p, "unknown material '%s'%s", pg->material,
                            scene_material_hint(sc, pg->material, hint, sizeof hint));
            break;
        }
        int kinds = (pg->spheres_count > 0) + (pg->csv != NULL) + (pg->generate != NULL);
        if (kinds != 1) {
            snprintf(p, sizeof p, "particles[%u]", g);
            rc = scene_fail(sc, err, errlen, p, "give exactly one of spheres, csv or generate");
            break;
        }
        if (pg->csv) {
            rc = load_csv(sc, s, &ol, (int)g, mat, err, errlen);
        } else if (pg->generate) {
            rc = generate(sc, s, &ol, (int)g, mat, fill, fill_len, err, errlen);
        } else {
            for (unsigned i = 0; i < pg->spheres_count && !rc; i++) {
                const scene_sphere *q = &pg->spheres[i];
                snprintf(p, sizeof p, "particles[%u].spheres[%u].radius", g, i);
                if (!(q->radius > 0) || !isfinite(q->radius))
                    rc = scene_fail(sc, err, errlen, p, "radius must be > 0 m (got %g)", q->radius);
                else if (add_one(s, &ol, q->x, q->v, q->w, q->radius, mat, (int)g, (int)i, 0) < 0) {
                    snprintf(p, sizeof p, "particles[%u].spheres[%u]", g, i);
                    rc = scene_fail(sc, err, errlen, p, "%s", dem_error(s));
                }
            }
        }
        if (!rc)
            rc = constrain(sc, s, g, first, dem_count(s), err, errlen);
    }
    const char *order = scene_particle_order(sc);
    if (!rc && strcmp(order, "input") && strcmp(order, "spatial"))
        rc = scene_fail(sc, err, errlen, "particle_order", "particle_order must be input or spatial (got '%s')", order);
    if (!rc && !strcmp(order, "spatial")) { /* before the membranes add their vertices, springs and hinges */
        scene_origin *sorted = malloc(sizeof *sorted * (size_t)(ol.n ? ol.n : 1));
        if (!sorted || dem_sort_particles(s))
            rc = scene_fail(sc, err, errlen, "particle_order", "%s", sorted ? dem_error(s) : "out of host memory");
        for (int i = 0; !rc && i < ol.n; i++) /* the origins follow their particles */
            sorted[i] = ol.o[dem_particle_source(s, i)];
        if (!rc) {
            free(ol.o);
            ol.o = sorted;
        } else
            free(sorted);
    }
    if (rc) {
        free(ol.o);
        return rc;
    }
    *origin = ol.o;
    return 0;
}
