/* scene_overlaps.c - initial overlaps: a scene whose particles start deep inside each other or inside a wall would
 * explode on the first step, so it is refused with the particles and the wall named. */
#include "scene_particles.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void describe(const scene *sc, const scene_origin *o, char *buf, size_t len)
{
    const scene_particles *pg = &sc->f->particles[o->group];
    if (o->csv_line)
        snprintf(buf, len, "particles[%d] (%s line %d)", o->group, pg->csv, o->csv_line);
    else if (pg->spheres_count)
        snprintf(buf, len, "particles[%d].spheres[%d]", o->group, o->index);
    else
        snprintf(buf, len, "particles[%d] (generated sphere %d)", o->group, o->index);
}

/* Overlap of a sphere with wall k of the scene (a box: its deepest plane); <= 0 when apart. */
static double wall_overlap(const scene_wall *w, const double *x, double r)
{
    if (!strcmp(w->type, "box")) {
        double worst = -INFINITY;
        for (int d = 0; d < 3; d++) {
            worst = fmax(worst, r - (x[d] - w->lo[d]));
            worst = fmax(worst, r - (w->hi[d] - x[d]));
        }
        return worst;
    }
    const double *nr = !strcmp(w->type, "plane") ? w->normal : w->axis;
    double nn = sqrt(nr[0] * nr[0] + nr[1] * nr[1] + nr[2] * nr[2]);
    dem_wall dw = {.kind = !strcmp(w->type, "plane") ? DEM_WALL_PLANE : DEM_WALL_CYLINDER, .radius = w->radius,
                   .height = w->height};
    if (w->cup && dw.kind == DEM_WALL_PLANE) /* a sphere sitting in a concave punch's cup, below its land */
        dw.cup_radius = w->cup->radius, dw.cup_depth = w->cup->depth;
    for (int d = 0; d < 3; d++)
        dw.normal[d] = nr[d] / nn;
    return dem_wall_overlap(&dw, w->point, x, r, NULL); /* the kernels' geometry (a finite die's rim and faces) */
}

typedef struct {
    long long cell;
    int id;
} cell_entry;

static int cmp_cell(const void *a, const void *b)
{
    const cell_entry *x = a, *y = b;
    return x->cell < y->cell ? -1 : x->cell > y->cell ? 1 : x->id - y->id;
}

int scene_check_overlaps(const scene *sc, dem_sim *s, const scene_origin *o, int n, char *err, size_t errlen)
{
    double tol = scene_has(sc->loc, "overlap_tolerance") ? sc->f->overlap_tolerance : 0.01;
    if (!(tol >= 0) || !(tol < 1))
        return scene_fail(sc, err, errlen, "overlap_tolerance", "must be in [0, 1) (fraction of the radius)");
    char who[512], p[64];
    for (unsigned k = 0; k < sc->f->walls_count; k++)
        for (int i = 0; i < n; i++) {
            double ov = wall_overlap(&sc->f->walls[k], o[i].x, o[i].r);
            if (ov > tol * o[i].r) { /* at the sphere's line (a listed sphere's own, else its group's): the wall's
                                         * is named in the message */
                describe(sc, &o[i], who, sizeof who);
                if (sc->f->particles[o[i].group].spheres_count)
                    snprintf(p, sizeof p, "particles[%d].spheres[%d]", o[i].group, o[i].index);
                else
                    snprintf(p, sizeof p, "particles[%d]", o[i].group);
                char wall[64];
                snprintf(wall, sizeof wall, "walls[%u]", k);
                const char *name = sc->f->walls[k].name;
                return scene_fail(sc, err, errlen, p,
                                  "%s (radius %g m at %g, %g, %g) overlaps wall %s%s%s%s (line %d) by %.3g %% of its "
                                  "radius (tolerance %g %%)", who, o[i].r, o[i].x[0], o[i].x[1], o[i].x[2], wall,
                                  name ? " '" : "", name ? name : "", name ? "'" : "", scene_line(sc->loc, wall),
                                  100 * ov / o[i].r, 100 * tol);
            }
        }
    /* particle pairs: sort into cubic cells of edge 2 r_max, compare with the 27 neighbouring cells */
    double rmax = 0, lo[3] = {INFINITY, INFINITY, INFINITY};
    for (int i = 0; i < n; i++) {
        rmax = fmax(rmax, o[i].r);
        for (int d = 0; d < 3; d++)
            lo[d] = fmin(lo[d], o[i].x[d]);
    }
    double h = 2 * rmax;
    const long long M = 1 << 20;
    cell_entry *c = malloc(sizeof *c * (size_t)(n > 0 ? n : 1));
    if (!c)
        return scene_fail(sc, err, errlen, "particles", "out of memory");
    for (int i = 0; i < n; i++) {
        long long q[3];
        for (int d = 0; d < 3; d++) { /* cells beyond the key range share the last one (exact, just slower) */
            double t = floor((o[i].x[d] - lo[d]) / h);
            q[d] = !(t >= 0) ? 1 : t > (double)(M - 3) ? M - 2 : (long long)t + 1;
        }
        c[i] = (cell_entry){(q[2] * M + q[1]) * M + q[0], i};
    }
    qsort(c, (size_t)n, sizeof *c, cmp_cell);
    int rc = 0;
    for (int a = 0; a < n && !rc; a++) {
        int i = c[a].id;
        long long q0 = c[a].cell;
        for (int dz = -1; dz <= 1 && !rc; dz++)
            for (int dy = -1; dy <= 1 && !rc; dy++)
                for (int dx = -1; dx <= 1 && !rc; dx++) {
                    long long key = q0 + ((long long)dz * M + dy) * M + dx;
                    int lo_i = 0, hi_i = n; /* first entry with cell >= key */
                    while (lo_i < hi_i) {
                        int mid = (lo_i + hi_i) / 2;
                        if (c[mid].cell < key)
                            lo_i = mid + 1;
                        else
                            hi_i = mid;
                    }
                    for (int b = lo_i; b < n && c[b].cell == key && !rc; b++) {
                        int j = c[b].id;
                        if (j <= i)
                            continue;
                        double dd[3] = {o[i].x[0] - o[j].x[0], o[i].x[1] - o[j].x[1], o[i].x[2] - o[j].x[2]};
                        double ov = o[i].r + o[j].r - sqrt(dd[0] * dd[0] + dd[1] * dd[1] + dd[2] * dd[2]);
                        double rs = fmin(o[i].r, o[j].r);
                        if (ov > tol * rs) {
                            char who2[512];
                            describe(sc, &o[i], who, sizeof who);
                            describe(sc, &o[j], who2, sizeof who2);
                            if (sc->f->particles[o[j].group].spheres_count)
                                snprintf(p, sizeof p, "particles[%d].spheres[%d]", o[j].group, o[j].index);
                            else
                                snprintf(p, sizeof p, "particles[%d]", o[j].group);
                            rc = scene_fail(sc, err, errlen, p,
                                            "%s and %s overlap by %.3g %% of the smaller radius (tolerance %g %%)",
                                            who, who2, 100 * ov / rs, 100 * tol);
                        }
                    }
                }
    }
    free(c);
    return rc;
}
