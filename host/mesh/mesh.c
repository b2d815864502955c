/* mesh.c - triangulated surfaces for membranes (seed 001 section 2.2): the generated sheet, tube and sphere, and the
 * topology every membrane is built from (its edges, the springs, and its interior edges, the hinges).
 *
 * Orientation: (x_b - x_a) x (x_c - x_a) of every triangle points where a confining pressure pushes (dem_membrane.h,
 * dem_add_triangle): into a tube or a sphere (towards the granulate they hold), along -z for a sheet (onto what lies
 * below it). The generators build the triangles, then turn each one that points the other way.
 * Sizes: the edges come out near the requested length s. A sheet's triangles are equilateral: its length a along x
 * is kept and cut into whole edges e = a / round(a / s), its rows lie e sqrt(3)/2 apart, as many as come nearest to
 * its width b (so the width is b within half a row spacing, centred); its odd rows end in half steps, for straight
 * sides. A tube's rows are s sqrt(3)/2 apart and its vertices s apart around it (both rounded to whole counts: the
 * circumference and the height are kept), so that its triangles are near equilateral; a
 * sphere is the icosahedron split until its mean edge is nearest s, projected on the sphere and smoothed (20
 * Laplacian passes on the sphere). Why smoothed: the split icosphere of 642 vertices alone, inflated to 1 % strain,
 * settled 2.5 % past the membrane law, non-affinely (its radii spread as much as the strain); smoothed, 0.6 %, radii
 * within 0.06 % (tests/test_membrane.c, test_balloon, asserts 2 %). The smoothing makes the triangles locally even
 * though the edges at the twelve five-fold vertices end up shorter (longest / shortest 1.46). */
#include "sim.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MESH_MAX_VERTICES 2000000
#define SPHERE_SMOOTHING 20

static int mesh_alloc(dem_mesh *m, long nv, long nt)
{
    m->nv = 0, m->nt = 0;
    m->x = malloc(sizeof(double) * 3 * (size_t)(nv > 0 ? nv : 1));
    m->tri = malloc(sizeof(int) * 3 * (size_t)(nt > 0 ? nt : 1));
    return m->x && m->tri ? 0 : -1;
}

void dem_mesh_free(dem_mesh *m)
{
    if (!m)
        return;
    free(m->x), free(m->tri);
    m->x = NULL, m->tri = NULL, m->nv = m->nt = 0;
}

static void put_vertex(dem_mesh *m, double x, double y, double z)
{
    double *p = m->x + 3 * m->nv++;
    p[0] = x, p[1] = y, p[2] = z;
}

static void put_triangle(dem_mesh *m, int a, int b, int c)
{
    int *t = m->tri + 3 * m->nt++;
    t[0] = a, t[1] = b, t[2] = c;
}

/* Turns every triangle whose normal has a negative dot product with want(centroid) */
static void orient(dem_mesh *m, const dem_mesh_spec *sp)
{
    for (int k = 0; k < m->nt; k++) {
        int *t = m->tri + 3 * k;
        const double *a = m->x + 3 * t[0], *b = m->x + 3 * t[1], *c = m->x + 3 * t[2];
        double u[3], v[3], n[3], w[3];
        for (int q = 0; q < 3; q++)
            u[q] = b[q] - a[q], v[q] = c[q] - a[q], w[q] = sp->center[q] - (a[q] + b[q] + c[q]) / 3;
        n[0] = u[1] * v[2] - u[2] * v[1], n[1] = u[2] * v[0] - u[0] * v[2], n[2] = u[0] * v[1] - u[1] * v[0];
        if (sp->kind == DEM_MESH_SHEET)
            w[0] = w[1] = 0, w[2] = -1; /* along -z */
        else if (sp->kind == DEM_MESH_TUBE)
            w[2] = 0; /* towards the axis */
        if (n[0] * w[0] + n[1] * w[1] + n[2] * w[2] < 0) {
            int tmp = t[1];
            t[1] = t[2], t[2] = tmp;
        }
    }
}

/* Triangulates between two rows of vertices ordered by the coordinate s (lower: l0..l0+nl-1, upper: u0..), a
 * zipper that advances the row whose step makes the shorter new edge (the lower one on a tie). */
static void zip_rows(dem_mesh *m, int l0, int nl, const double *sl, int u0, int nu, const double *su)
{
    int i = 0, k = 0;
    while (i < nl - 1 || k < nu - 1) {
        if (k == nu - 1 || (i < nl - 1 && fabs(sl[i + 1] - su[k]) <= fabs(su[k + 1] - sl[i])))
            put_triangle(m, l0 + i, l0 + i + 1, u0 + k), i++;
        else
            put_triangle(m, l0 + i, u0 + k + 1, u0 + k), k++;
    }
}

/* The grid a generated sheet or tube is made of, in double (dem_membrane.h): n1 vertices along a row (a sheet's even
 * rows; a tube's rings), n2 rows, so that a huge size over a tiny edge is counted, not wrapped (lround and long products
 * overflowed: a tube of radius 1e-30 m and height 5.3e18 m with edges of 1 m came out 2051 vertices); round() as
 * lround. A sheet is equilateral: its length a cut into whole edges dx, its rows dx sqrt(3)/2 apart (both
 * spacings rounded apart would give 59.74 deg for 6 x 6 cm at 1 cm). A tube keeps its circumference and height: dx the
 * chord between neighbours on a ring, dy the height over whole rows. */
int dem_mesh_grid(const dem_mesh_spec *sp, double *n1, double *n2, double *dx, double *dy)
{
    double s = sp->edge;
    if (sp->kind == DEM_MESH_SHEET) {
        *n1 = fmax(2, round(sp->a / s) + 1);
        *dx = sp->a / (*n1 - 1), *dy = *dx * sqrt(3.0) / 2;
        *n2 = fmax(2, round(sp->b / *dy) + 1);
        return 0;
    }
    if (sp->kind == DEM_MESH_TUBE) {
        *n1 = fmax(3, round(2 * M_PI * sp->a / s)), *n2 = fmax(2, round(sp->b / (s * sqrt(3.0) / 2)) + 1);
        *dx = 2 * sp->a * sin(M_PI / *n1), *dy = sp->b / (*n2 - 1);
        return 0;
    }
    return DEM_ERR_ARG;
}

/* The split level of a generated sphere: the one whose mean edge (about 1.05 r / 2^level, the icosahedron's 1.0515 r
 * halved per split) is nearest s; in double (an infinite ratio has no level) */
static double sphere_level(const dem_mesh_spec *sp) { return fmax(0, round(log2(1.0515 * sp->a / sp->edge))); }

double dem_mesh_vertices(const dem_mesh_spec *sp)
{
    int sized = sp->edge > 0 && isfinite(sp->edge) && sp->a > 0 && isfinite(sp->a) &&
                (sp->kind == DEM_MESH_SPHERE || (sp->b > 0 && isfinite(sp->b)));
    if (!sized)
        return NAN;
    double n1, n2, dx, dy;
    switch (sp->kind) {
    case DEM_MESH_SHEET: /* even rows n1 vertices, odd rows n1 + 1 */
        dem_mesh_grid(sp, &n1, &n2, &dx, &dy);
        return n1 * n2 + floor(n2 / 2);
    case DEM_MESH_TUBE:
        dem_mesh_grid(sp, &n1, &n2, &dx, &dy);
        return n1 * n2;
    case DEM_MESH_SPHERE:
        return 10 * pow(4, sphere_level(sp)) + 2;
    }
    return NAN;
}

static int make_sheet(const dem_mesh_spec *sp, dem_mesh *m, char *err, size_t errlen)
{
    double s = sp->edge, lx = sp->a, n1, n2, dx, dy; /* equilateral (dem_mesh_grid) */
    dem_mesh_grid(sp, &n1, &n2, &dx, &dy);
    if (!(n1 * n2 + n2 <= MESH_MAX_VERTICES)) /* counted in double before anything becomes an integer */
        return snprintf(err, errlen, "a sheet of %g x %g m with edges of %g m has more than %d vertices", lx, sp->b, s,
                        MESH_MAX_VERTICES), DEM_ERR_ARG;
    long nx = (long)n1, ny = (long)n2;
    double ly = dy * (double)(ny - 1); /* within dy / 2 of b */
    if (mesh_alloc(m, nx * ny + ny, 2 * (nx + 1) * ny))
        return snprintf(err, errlen, "out of host memory"), DEM_ERR_NOMEM;
    double x0 = sp->center[0] - lx / 2, y0 = sp->center[1] - ly / 2;
    double *sprev = malloc(sizeof(double) * (size_t)(nx + 1)), *scur = malloc(sizeof(double) * (size_t)(nx + 1));
    if (!sprev || !scur)
        return free(sprev), free(scur), snprintf(err, errlen, "out of host memory"), DEM_ERR_NOMEM;
    int prev0 = 0, nprev = 0;
    for (long j = 0; j < ny; j++) { /* even rows: nx vertices dx apart; odd rows: the ends and the midpoints */
        int first = m->nv, count = 0;
        double y = y0 + dy * (double)j;
        if (j % 2 == 0)
            for (long i = 0; i < nx; i++)
                scur[count++] = x0 + dx * (double)i;
        else {
            scur[count++] = x0;
            for (long i = 0; i + 1 < nx; i++)
                scur[count++] = x0 + dx * ((double)i + 0.5);
            scur[count++] = x0 + lx;
        }
        for (int i = 0; i < count; i++)
            put_vertex(m, scur[i], y, sp->center[2]);
        if (j > 0)
            zip_rows(m, prev0, nprev, sprev, first, count, scur);
        double *t = sprev;
        sprev = scur, scur = t, prev0 = first, nprev = count;
    }
    free(sprev), free(scur);
    return 0;
}

static int make_tube(const dem_mesh_spec *sp, dem_mesh *m, char *err, size_t errlen)
{
    double s = sp->edge, r = sp->a, h = sp->b, n1, n2, dx, dy;
    dem_mesh_grid(sp, &n1, &n2, &dx, &dy);
    if (!(n1 * n2 <= MESH_MAX_VERTICES)) /* counted in double before anything becomes an integer */
        return snprintf(err, errlen, "a tube of radius %g m and height %g m with edges of %g m has more than %d "
                        "vertices", r, h, s, MESH_MAX_VERTICES), DEM_ERR_ARG;
    long na = (long)n1, nr = (long)n2;
    if (mesh_alloc(m, na * nr, 2 * na * (nr - 1)))
        return snprintf(err, errlen, "out of host memory"), DEM_ERR_NOMEM;
    for (long j = 0; j < nr; j++) /* ring j: na vertices, odd rings turned by half a step */
        for (long k = 0; k < na; k++) {
            double phi = 2 * M_PI * ((double)k + 0.5 * (double)(j % 2)) / (double)na;
            put_vertex(m, sp->center[0] + r * cos(phi), sp->center[1] + r * sin(phi),
                       sp->center[2] - h / 2 + h * (double)j / (double)(nr - 1));
        }
    for (long j = 0; j + 1 < nr; j++) {
        int a0 = (int)(j * na), b0 = (int)((j + 1) * na);
        for (long k = 0; k < na; k++) {
            int k1 = (int)((k + 1) % na), kk = (int)k;
            if (j % 2 == 0) /* b_k lies between a_k and a_k+1 */
                put_triangle(m, a0 + kk, a0 + k1, b0 + kk), put_triangle(m, b0 + kk, a0 + k1, b0 + k1);
            else /* a_k lies between b_k and b_k+1 */
                put_triangle(m, a0 + kk, a0 + k1, b0 + k1), put_triangle(m, a0 + kk, b0 + k1, b0 + kk);
        }
    }
    return 0;
}

typedef struct {
    int a, b, mid;
} edge_mid;

static int cmp_edge_mid(const void *p, const void *q)
{
    const edge_mid *x = p, *y = q;
    return x->a != y->a ? (x->a > y->a) - (x->a < y->a) : (x->b > y->b) - (x->b < y->b);
}

/* One split of every triangle of m into four, each edge's new vertex at its midpoint on the unit sphere; ft and em
 * hold 3 nt entries of the split mesh */
static void split_once(dem_mesh *m, int *ft, edge_mid *em)
{
    int ne = 0; /* every edge once, with a new vertex at its midpoint on the sphere */
    for (int k = 0; k < m->nt; k++)
        for (int j = 0; j < 3; j++) {
            int a = m->tri[3 * k + j], b = m->tri[3 * k + (j + 1) % 3];
            if (a < b)
                em[ne].a = a, em[ne].b = b, em[ne].mid = -1, ne++;
        }
    qsort(em, (size_t)ne, sizeof *em, cmp_edge_mid);
    for (int e = 0; e < ne; e++) {
        const double *xa = m->x + 3 * em[e].a, *xb = m->x + 3 * em[e].b;
        double c[3], n = 0;
        for (int q = 0; q < 3; q++)
            c[q] = xa[q] + xb[q], n += c[q] * c[q];
        em[e].mid = m->nv;
        put_vertex(m, c[0] / sqrt(n), c[1] / sqrt(n), c[2] / sqrt(n));
    }
    int nf = 0;
    for (int k = 0; k < m->nt; k++) {
        int v[3], mid[3];
        for (int j = 0; j < 3; j++)
            v[j] = m->tri[3 * k + j];
        for (int j = 0; j < 3; j++) {
            int a = v[j], b = v[(j + 1) % 3];
            edge_mid key = {a < b ? a : b, a < b ? b : a, 0};
            mid[j] = ((edge_mid *)bsearch(&key, em, (size_t)ne, sizeof *em, cmp_edge_mid))->mid;
        }
        int sub[4][3] = {{v[0], mid[0], mid[2]}, {v[1], mid[1], mid[0]}, {v[2], mid[2], mid[1]},
                         {mid[0], mid[1], mid[2]}};
        memcpy(ft + 3 * nf, sub, sizeof sub), nf += 4;
    }
    memcpy(m->tri, ft, sizeof(int) * 3 * (size_t)nf), m->nt = nf;
}

/* Smoothing of a split unit sphere (level > 0): every vertex to the mean of its neighbours (each edge seen from both
 * triangles), back on the sphere, SPHERE_SMOOTHING times; -1 when out of memory */
static int smooth_sphere(dem_mesh *m, int level)
{
    double *acc = malloc(sizeof(double) * 3 * (size_t)m->nv);
    int *deg = malloc(sizeof(int) * (size_t)m->nv);
    if (!acc || !deg)
        return free(acc), free(deg), -1;
    for (int it = 0; it < SPHERE_SMOOTHING && level > 0; it++) {
        memset(acc, 0, sizeof(double) * 3 * (size_t)m->nv), memset(deg, 0, sizeof(int) * (size_t)m->nv);
        for (int k = 0; k < m->nt; k++)
            for (int j = 0; j < 3; j++) {
                int a = m->tri[3 * k + j], b = m->tri[3 * k + (j + 1) % 3];
                for (int q = 0; q < 3; q++)
                    acc[3 * a + q] += m->x[3 * b + q];
                deg[a]++;
            }
        for (int i = 0; i < m->nv; i++) {
            double n = 0;
            for (int q = 0; q < 3; q++)
                n += acc[3 * i + q] * acc[3 * i + q];
            for (int q = 0; q < 3; q++)
                m->x[3 * i + q] = acc[3 * i + q] / sqrt(n);
        }
    }
    free(acc), free(deg);
    return 0;
}

static int make_sphere(const dem_mesh_spec *sp, dem_mesh *m, char *err, size_t errlen)
{
    double r = sp->a, s = sp->edge, t = (1 + sqrt(5.0)) / 2;
    double lv = sphere_level(sp);
    if (!(lv <= 8))
        return snprintf(err, errlen, "a sphere of radius %g m with edges of %g m needs more than %d vertices (8 "
                        "splits of the icosahedron)", r, s, 10 * (1 << 16) + 2), DEM_ERR_ARG;
    int level = (int)lv;
    long nv = 10L * (1L << (2 * level)) + 2, nt = 20L * (1L << (2 * level));
    if (mesh_alloc(m, nv, nt))
        return snprintf(err, errlen, "out of host memory"), DEM_ERR_NOMEM;
    const double ico[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                               {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    static const int f0[20][3] = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                  {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                  {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    for (int i = 0; i < 12; i++) /* on the unit sphere */
        put_vertex(m, ico[i][0] / sqrt(1 + t * t), ico[i][1] / sqrt(1 + t * t), ico[i][2] / sqrt(1 + t * t));
    for (int k = 0; k < 20; k++)
        put_triangle(m, f0[k][0], f0[k][1], f0[k][2]);
    int *ft = malloc(sizeof(int) * 3 * (size_t)nt);
    edge_mid *em = malloc(sizeof(edge_mid) * 3 * (size_t)nt);
    if (!ft || !em)
        return free(ft), free(em), dem_mesh_free(m), snprintf(err, errlen, "out of host memory"), DEM_ERR_NOMEM;
    for (int l = 0; l < level; l++)
        split_once(m, ft, em);
    free(ft), free(em);
    if (smooth_sphere(m, level))
        return dem_mesh_free(m), snprintf(err, errlen, "out of host memory"), DEM_ERR_NOMEM;
    for (int i = 0; i < m->nv; i++)
        for (int q = 0; q < 3; q++)
            m->x[3 * i + q] = sp->center[q] + r * m->x[3 * i + q];
    return 0;
}

int dem_mesh_make(const dem_mesh_spec *sp, dem_mesh *m, char *err, size_t errlen)
{
    memset(m, 0, sizeof *m);
    int finite = isfinite(sp->center[0]) && isfinite(sp->center[1]) && isfinite(sp->center[2]);
    if (!finite || !(sp->edge > 0) || !isfinite(sp->edge))
        return snprintf(err, errlen, "edge length must be > 0 and the centre finite (got edge %g m)", sp->edge),
               DEM_ERR_ARG;
    if (!(sp->a > 0) || !isfinite(sp->a) || (sp->kind != DEM_MESH_SPHERE && (!(sp->b > 0) || !isfinite(sp->b))))
        return snprintf(err, errlen, "the sizes must be > 0 and finite (got %g m, %g m)", sp->a, sp->b), DEM_ERR_ARG;
    int rc;
    switch (sp->kind) {
    case DEM_MESH_SHEET: rc = make_sheet(sp, m, err, errlen); break;
    case DEM_MESH_TUBE: rc = make_tube(sp, m, err, errlen); break;
    case DEM_MESH_SPHERE: rc = make_sphere(sp, m, err, errlen); break;
    default: return snprintf(err, errlen, "unknown mesh kind %d", (int)sp->kind), DEM_ERR_ARG;
    }
    if (rc)
        return dem_mesh_free(m), rc;
    orient(m, sp);
    return 0;
}

typedef struct {
    int lo, hi, a, b, c, tri; /* the half-edge a -> b of triangle tri, c its third vertex */
} half_edge;

static int cmp_half(const void *p, const void *q)
{
    const half_edge *x = p, *y = q;
    if (x->lo != y->lo)
        return (x->lo > y->lo) - (x->lo < y->lo);
    if (x->hi != y->hi)
        return (x->hi > y->hi) - (x->hi < y->hi);
    return (x->tri > y->tri) - (x->tri < y->tri);
}

int dem_mesh_topology(const dem_mesh *m, dem_mesh_topo *t, char *err, size_t errlen)
{
    memset(t, 0, sizeof *t);
    for (int k = 0; k < m->nt; k++)
        for (int j = 0; j < 3; j++) {
            int a = m->tri[3 * k + j], b = m->tri[3 * k + (j + 1) % 3];
            if (a < 0 || a >= m->nv || a == b || a == m->tri[3 * k + (j + 2) % 3])
                return snprintf(err, errlen, "triangle %d: vertices %d, %d, %d (three different vertices of 0..%d)",
                                k, m->tri[3 * k], m->tri[3 * k + 1], m->tri[3 * k + 2], m->nv - 1), DEM_ERR_ARG;
        }
    size_t nh = 3 * (size_t)(m->nt > 0 ? m->nt : 0); /* (nt < 0 is no mesh: the loop above ran none) */
    half_edge *h = malloc(sizeof *h * (nh ? nh : 1));
    t->edge = malloc(sizeof(int) * 2 * (nh ? nh : 1));
    t->hinge = malloc(sizeof(int) * 4 * (nh ? nh : 1));
    if (!h || !t->edge || !t->hinge)
        return free(h), dem_mesh_topo_free(t), snprintf(err, errlen, "out of host memory"), DEM_ERR_NOMEM;
    for (int k = 0; k < m->nt; k++)
        for (int j = 0; j < 3; j++) {
            half_edge *e = h + 3 * k + j;
            e->a = m->tri[3 * k + j], e->b = m->tri[3 * k + (j + 1) % 3], e->c = m->tri[3 * k + (j + 2) % 3];
            e->lo = e->a < e->b ? e->a : e->b, e->hi = e->a < e->b ? e->b : e->a, e->tri = k;
        }
    qsort(h, nh, sizeof *h, cmp_half);
    for (size_t i = 0; i < nh;) {
        size_t j = i + 1;
        while (j < nh && h[j].lo == h[i].lo && h[j].hi == h[i].hi)
            j++;
        if (j - i > 2)
            return snprintf(err, errlen, "edge %d-%d is shared by %d triangles (a membrane is a surface: two at most)",
                            h[i].lo, h[i].hi, (int)(j - i)), free(h), dem_mesh_topo_free(t), DEM_ERR_ARG;
        t->edge[2 * t->ne] = h[i].lo, t->edge[2 * t->ne + 1] = h[i].hi, t->ne++;
        if (j - i == 2) {
            if (h[i].a == h[i + 1].a)
                return snprintf(err, errlen, "triangles %d and %d are turned opposite ways across their edge %d-%d "
                                "(a membrane's triangles must all be ordered the same way round)", h[i].tri,
                                h[i + 1].tri, h[i].lo, h[i].hi), free(h), dem_mesh_topo_free(t), DEM_ERR_ARG;
            int *g = t->hinge + 4 * t->nhinges++; /* (p1, p3, p4) = (c, a, b) is triangle i turned; (p2, p4, p3) */
            g[0] = h[i].c, g[1] = h[i + 1].c, g[2] = h[i].a, g[3] = h[i].b;
        } else
            t->nboundary++;
        i = j;
    }
    free(h);
    return 0;
}

void dem_mesh_topo_free(dem_mesh_topo *t)
{
    if (!t)
        return;
    free(t->edge), free(t->hinge);
    t->edge = t->hinge = NULL, t->ne = t->nhinges = t->nboundary = 0;
}
