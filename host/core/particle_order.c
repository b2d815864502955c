/* particle_order.c - dem_sort_particles: the particles in the order of a Morton (Z-order) curve through their
 * positions, so that neighbours in space are neighbours in memory.
 *
 * Why: every kernel reads its partners' positions, velocities and histories by particle id. A packing that arrives in
 * another code's order, or a random packing (generated in random order), scatters those reads over the whole arrays;
 * on a poured bed of 1e5 spheres in random order PoCL ran 2.4x slower than on the same bed sorted (docs/design.md).
 * The sort is a pure function of the positions (21 bits per axis over their bounding box, ties by the earlier id),
 * so a run and its restart, the reference and every device, see the same order; two files listing the same
 * particles in different orders give the same run as long as no two particles share a key (they do not unless
 * closer than 2^-21 of the box). It moves particles, not results: sums follow the particle ids, so a sorted
 * run differs from an unsorted one in the rounding of its sums only. */
#include "sim.h"
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    uint64_t key;
    int id;
} keyed;

static uint64_t spread21(uint64_t v) /* bits b of v to bits 3b */
{
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffull;
    v = (v | v << 16) & 0x1f0000ff0000ffull;
    v = (v | v << 8) & 0x100f00f00f00f00full;
    v = (v | v << 4) & 0x10c30c30c30c30c3ull;
    v = (v | v << 2) & 0x1249249249249249ull;
    return v;
}

static int by_key(const void *a, const void *b)
{
    const keyed *p = a, *q = b;
    return p->key < q->key ? -1 : p->key > q->key ? 1 : (p->id > q->id) - (p->id < q->id);
}

/* permute n items of size bytes by the sorted order (new item k = old item o[k].id), through tmp (size * n bytes) */
static void permute(void *base, size_t size, const keyed *o, int n, unsigned char *tmp)
{
    unsigned char *b = base;
    for (int k = 0; k < n; k++)
        memcpy(tmp + size * (size_t)k, b + size * (size_t)o[k].id, size);
    memcpy(b, tmp, size * (size_t)n);
}

/* The order of n positions x (3 doubles each) along a Morton curve through their bounding box (21 bits per axis,
 * ties by the earlier index), into o[k].id: the index of the k-th. */
static void morton_keys(const double *x, int n, keyed *o)
{
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int i = 0; i < n; i++)
        for (int d = 0; d < 3; d++) {
            lo[d] = fmin(lo[d], x[3 * i + d]);
            hi[d] = fmax(hi[d], x[3 * i + d]);
        }
    for (int i = 0; i < n; i++) {
        uint64_t key = 0;
        for (int d = 0; d < 3; d++) {
            double span = hi[d] - lo[d], u = span > 0 ? (x[3 * i + d] - lo[d]) / span : 0;
            uint64_t q = (uint64_t)(u * 2097151.0); /* 0 .. 2^21 - 1 */
            key |= spread21(q) << d;
        }
        o[i] = (keyed){key, i};
    }
    qsort(o, (size_t)n, sizeof *o, by_key);
}

int sim_morton_order(const double *x, int n, int *perm)
{
    keyed *o = malloc(sizeof *o * (size_t)(n ? n : 1));
    if (!o)
        return -1;
    morton_keys(x, n, o);
    for (int k = 0; k < n; k++)
        perm[k] = o[k].id;
    free(o);
    return 0;
}

int dem_sort_particles(dem_sim *s)
{
    if (s->run.started || s->split_started)
        return sim_fail(s, DEM_ERR_STATE, "dem_sort_particles: before dem_start");
    if (s->mesh.nsprings || s->mesh.ntri || s->mesh.nhinges || s->mesh.npatch || s->mesh.natt)
        return sim_fail(s, DEM_ERR_STATE, "dem_sort_particles: before any spring, triangle, hinge, patch or attachment "
                                          "refers to particles by id (sort first, then add membranes)");
    int n = s->n;
    if (n < 2)
        return 0;
    keyed *o = malloc(sizeof *o * (size_t)n);
    int *src = malloc(sizeof(int) * (size_t)n);
    unsigned char *tmp = malloc(3 * sizeof(double) * (size_t)n); /* every allocation first: nothing moves unless all */
    if (!o || !src || !tmp) {
        free(o), free(src), free(tmp);
        return sim_fail(s, DEM_ERR_NOMEM, "out of host memory");
    }
    morton_keys(s->x, n, o);
    for (int k = 0; k < n; k++) /* where each particle came from, through earlier sorts too */
        src[k] = s->order.source && o[k].id < s->order.source_n ? s->order.source[o[k].id] : o[k].id;
    permute(s->x, 3 * sizeof(double), o, n, tmp);
    permute(s->v, 3 * sizeof(double), o, n, tmp);
    permute(s->w, 3 * sizeof(double), o, n, tmp);
    permute(s->radius, sizeof(double), o, n, tmp);
    permute(s->mat, sizeof(int), o, n, tmp);
    permute(s->pflags, sizeof(unsigned), o, n, tmp);
    permute(s->body, 2 * sizeof(double), o, n, tmp);
    free(o), free(tmp);
    free(s->order.source);
    s->order.source = src;
    s->order.source_n = n;
    return 0;
}

int dem_particle_source(const dem_sim *s, int i)
{
    if (i < 0 || i >= s->n)
        return DEM_ERR_ARG;
    return s->order.source && i < s->order.source_n ? s->order.source[i] : i;
}

static int by_double(const void *a, const void *b)
{
    double p = *(const double *)a, q = *(const double *)b;
    return (p > q) - (p < q);
}

/* How scattered the particles' order is: the median, over consecutive particles i and i + 1, of their distance over
 * the sum of their radii (1 or less when each particle's successor touches it, as along a lattice row or a sorted
 * packing; tens for a packing generated at random or taken over from a code that orders by something else). */
double dem_order_scatter(const dem_sim *s)
{
    int n = s->n;
    if (n < 2)
        return 0;
    double *d = malloc(sizeof(double) * (size_t)(n - 1));
    if (!d)
        return 0;
    for (int i = 0; i + 1 < n; i++) {
        double q = 0;
        for (int k = 0; k < 3; k++)
            q += (s->x[3 * i + 3 + k] - s->x[3 * i + k]) * (s->x[3 * i + 3 + k] - s->x[3 * i + k]);
        double rr = s->radius[i] + s->radius[i + 1];
        d[i] = rr > 0 ? sqrt(q) / rr : 0;
    }
    qsort(d, (size_t)(n - 1), sizeof *d, by_double);
    double m = d[(n - 1) / 2];
    free(d);
    return m;
}

/* The spacing of representable coordinates at the largest coordinate magnitude of the set-up (particles' initial
 * positions, wall points), in precision p: how finely positions, and so overlaps, are resolved there. *largest gets
 * that magnitude. */
double dem_position_resolution(const dem_sim *s, dem_precision p, double *largest)
{
    double m = 0;
    for (int i = 0; i < 3 * s->n; i++)
        m = fmax(m, fabs(s->x[i]));
    for (int k = 0; k < s->nwalls; k++)
        for (int d = 0; d < 3; d++)
            m = fmax(m, fabs(s->walls[k].point[d]));
    if (largest)
        *largest = m;
    if (p == DEM_FP32) {
        float f = (float)m;
        return (double)nextafterf(f, INFINITY) - (double)f;
    }
    return nextafter(m, INFINITY) - m;
}
