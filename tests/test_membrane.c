/* test_membrane.c - host/mesh/mesh.c (generated sheet, tube, sphere; edges and hinges) and host/mesh/membrane.c
 * (dem_add_membrane): the meshes have the topology of their surface (Euler characteristic, boundary, one hinge per
 * interior edge), near-equilateral triangles of about the requested edge, the documented orientation and the
 * surface's area; a membrane gets the vertex masses of its area, a spring period of k = (sqrt(3)/2) E d, no force
 * at rest (every backend x precision, OpenCL bitwise); bad meshes and parameters are refused with nothing added.
 * (The lattice's moduli: tests/test_springs.c; a sphere under pressure: tests/test_pressure.c.) */
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct {
    double lmin, lmax, lmean, area;
    int chi, wrong_way;
} mesh_stats;

static mesh_stats stats(const dem_mesh *m, const dem_mesh_topo *t, const dem_mesh_spec *sp)
{
    mesh_stats st = {INFINITY, 0, 0, 0, m->nv - t->ne + m->nt, 0};
    for (int e = 0; e < t->ne; e++) {
        const double *a = m->x + 3 * t->edge[2 * e], *b = m->x + 3 * t->edge[2 * e + 1];
        double d = sqrt(pow(a[0] - b[0], 2) + pow(a[1] - b[1], 2) + pow(a[2] - b[2], 2));
        st.lmin = fmin(st.lmin, d), st.lmax = fmax(st.lmax, d), st.lmean += d / t->ne;
    }
    for (int k = 0; k < m->nt; k++) {
        const int *f = m->tri + 3 * k;
        const double *a = m->x + 3 * f[0], *b = m->x + 3 * f[1], *c = m->x + 3 * f[2];
        double u[3], v[3], n[3], w[3];
        for (int q = 0; q < 3; q++)
            u[q] = b[q] - a[q], v[q] = c[q] - a[q], w[q] = sp->center[q] - (a[q] + b[q] + c[q]) / 3;
        n[0] = u[1] * v[2] - u[2] * v[1], n[1] = u[2] * v[0] - u[0] * v[2], n[2] = u[0] * v[1] - u[1] * v[0];
        st.area += 0.5 * sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (sp->kind == DEM_MESH_SHEET)
            w[0] = w[1] = 0, w[2] = -1;
        if (sp->kind == DEM_MESH_TUBE)
            w[2] = 0;
        st.wrong_way += n[0] * w[0] + n[1] * w[1] + n[2] * w[2] <= 0;
    }
    return st;
}

static void check_mesh(const dem_mesh_spec *sp, int chi, double area, double area_tol, int boundary)
{
    dem_mesh m;
    dem_mesh_topo t;
    char err[256];
    if (dem_mesh_make(sp, &m, err, sizeof err) || dem_mesh_topology(&m, &t, err, sizeof err))
        fail_msg("%s", err);
    mesh_stats st = stats(&m, &t, sp);
    static const char *names[] = {"sheet", "tube", "sphere"};
    printf("  %s: %d vertices, %d edges (%d on the boundary), %d triangles, %d hinges; edges %.3g..%.3g of %.3g m; "
           "area %.6g m^2 (surface %.6g); Euler characteristic %d\n", names[sp->kind], m.nv, t.ne, t.nboundary, m.nt,
           t.nhinges, st.lmin, st.lmax, sp->edge, st.area, area, st.chi);
    assert_int_equal(st.chi, chi);
    assert_int_equal(t.nboundary, boundary);
    assert_int_equal(t.nhinges, t.ne - t.nboundary); /* one hinge per interior edge */
    assert_int_equal(st.wrong_way, 0);
    /* the mean edge near s (a sphere splits by halves: within a factor sqrt(2)); near-equilateral (a sheet's odd
     * rows end in half steps, for straight sides: edges of s/2 there) */
    assert_true(st.lmean > sp->edge / sqrt(2) && st.lmean < sp->edge * sqrt(2));
    assert_true(sp->kind == DEM_MESH_SHEET ? st.lmin > 0.49 * sp->edge && st.lmax < 1.1 * sp->edge
                                           : st.lmax < 1.5 * st.lmin);
    assert_true(fabs(st.area / area - 1) <= area_tol);
    for (int h = 0; h < t.nhinges; h++) { /* the hinge's triangles (p1, p3, p4) and (p2, p4, p3) are mesh triangles */
        const int *g = t.hinge + 4 * h;
        int found = 0;
        for (int k = 0; k < m.nt; k++)
            for (int r = 0; r < 3; r++) {
                const int *f = m.tri + 3 * k;
                found += f[r] == g[0] && f[(r + 1) % 3] == g[2] && f[(r + 2) % 3] == g[3];
                found += f[r] == g[1] && f[(r + 1) % 3] == g[3] && f[(r + 2) % 3] == g[2];
            }
        assert_int_equal(found, 2);
    }
    dem_mesh_topo_free(&t);
    dem_mesh_free(&m);
}

static void test_generated_meshes(void **st)
{
    (void)st;
    /* a sheet: a disc (chi 1), its area exactly a x its width, the rows (ny - 1) e sqrt(3)/2 wide (the
     * width is b within half a row spacing, 0.0606 m for b = 0.06 m, so that the triangles are equilateral; a width
     * of b exactly would not keep them so); boundary = the rim */
    dem_mesh_spec sheet = {DEM_MESH_SHEET, {0.01, -0.02, 0.003}, 0.1, 0.06, 0.01};
    int nx = 11, ny = (int)lround(0.06 / (0.01 * sqrt(3) / 2)) + 1; /* rows of 11 and (odd rows) 12 vertices */
    check_mesh(&sheet, 1, 0.1 * (ny - 1) * 0.01 * sqrt(3) / 2, 1e-12,
               (nx - 1) + ((ny - 1) % 2 ? nx : nx - 1) + 2 * (ny - 1));
    /* a tube: an annulus (chi 0), two rims of na edges; its area a polygon's, below 2 pi r h by (1 - sinc) */
    double r = 0.025, h = 0.1, s = 0.005;
    int na = (int)lround(2 * M_PI * r / s);
    dem_mesh_spec tube = {DEM_MESH_TUBE, {0, 0, 0.05}, r, h, s};
    check_mesh(&tube, 0, 2 * M_PI * r * h, 0.01, 2 * na);
    /* a sphere: chi 2, closed; inscribed polyhedron within 1 % of 4 pi r^2 */
    dem_mesh_spec sphere = {DEM_MESH_SPHERE, {0.1, 0.2, 0.3}, 0.05, 0, 0.008};
    check_mesh(&sphere, 2, 4 * M_PI * 0.05 * 0.05, 0.01, 0);
}

/* A sheet's triangles are equilateral - every angle 60 deg, but the half triangles that end the odd rows
 * (30, 60, 90) - and its length a is kept, its width within half a row spacing of b, about the centre. The sheets
 * of seed 001's friction slide, test_patch_contacts and a 6 x 6 cm sheet at 1 cm (its angles 59.74 deg when the
 * width is b exactly). */
static void test_sheet_angles(void **st)
{
    (void)st;
    static const double cases[][3] = {{0.06, 0.06, 0.01}, {0.024, 0.012, 0.00133}, {0.03, 0.03, 0.001},
                                      {0.1, 0.06, 0.01}, {0.05, 0.02, 0.007}};
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        dem_mesh_spec sp = {DEM_MESH_SHEET, {0.01, -0.02, 0.003}, cases[c][0], cases[c][1], cases[c][2]};
        dem_mesh m;
        char err[256];
        assert_int_equal(dem_mesh_make(&sp, &m, err, sizeof err), 0);
        double worst = 0, lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        int halves = 0;
        for (int i = 0; i < m.nv; i++)
            for (int d = 0; d < 3; d++)
                lo[d] = fmin(lo[d], m.x[3 * i + d]), hi[d] = fmax(hi[d], m.x[3 * i + d]);
        for (int k = 0; k < m.nt; k++) {
            double ang[3];
            for (int r = 0; r < 3; r++) { /* the angle at vertex r */
                const double *a = m.x + 3 * m.tri[3 * k + r], *b = m.x + 3 * m.tri[3 * k + (r + 1) % 3],
                             *q = m.x + 3 * m.tri[3 * k + (r + 2) % 3];
                double u[3], v[3];
                for (int d = 0; d < 3; d++)
                    u[d] = b[d] - a[d], v[d] = q[d] - a[d];
                ang[r] = acos((u[0] * v[0] + u[1] * v[1] + u[2] * v[2]) /
                              sqrt((u[0] * u[0] + u[1] * u[1] + u[2] * u[2]) * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]))) *
                         180 / M_PI;
            }
            double amax = fmax(ang[0], fmax(ang[1], ang[2]));
            int half = amax > 75; /* a right triangle at a side: 30, 60, 90 */
            halves += half;
            for (int r = 0; r < 3; r++) {
                double want = !half ? 60 : ang[r] > 75 ? 90 : ang[r] > 45 ? 60 : 30;
                worst = fmax(worst, fabs(ang[r] - want));
            }
        }
        double e = cases[c][0] / (double)lround(cases[c][0] / cases[c][2]), dy = e * sqrt(3) / 2;
        printf("  sheet %g x %g m, edge %g m: %d triangles (%d halves at the sides), angles within %.2g deg of 60 (30, "
               "90); %g x %g m\n", cases[c][0], cases[c][1], cases[c][2], m.nt, halves, worst, hi[0] - lo[0],
               hi[1] - lo[1]);
        assert_true(worst < 1e-9);
        assert_true(fabs(hi[0] - lo[0] - cases[c][0]) < 1e-12);          /* the length kept */
        assert_true(fabs(hi[1] - lo[1] - cases[c][1]) <= 0.5 * dy + 1e-12); /* the width nearest b */
        assert_true(fabs(fmod((hi[1] - lo[1]) / dy + 0.5, 1.0) - 0.5) < 1e-9); /* whole rows */
        assert_true(fabs(0.5 * (lo[1] + hi[1]) - sp.center[1]) < 1e-12 && fabs(0.5 * (lo[0] + hi[0]) - sp.center[0]) < 1e-12);
        dem_mesh_free(&m);
    }
}

static const dem_membrane rubber = {1.25e6, 1.0 / 3, 3e-4, 1000, 0.5, 1.2, 0.3, 1e-4, 1e-6, 0.001};

/* A simulation holding one generated sphere membrane of radius r and edge length `edge` in a 10 cm box, at the
 * recommended time step (set again after anything that changes it) */
static dem_sim *sphere_sim(double r, double edge, const dem_membrane *mm, dem_membrane_info *info)
{
    dem_sim *s = dem_create();
    dem_mesh m;
    char err[256];
    dem_mesh_spec sp = {DEM_MESH_SPHERE, {0, 0, 0}, r, 0, edge};
    if (dem_mesh_make(&sp, &m, err, sizeof err))
        fail_msg("%s", err);
    if (dem_add_membrane(s, &m, mm, info))
        fail_msg("%s", dem_error(s));
    dem_mesh_free(&m);
    dem_set_domain(s, (double[3]){-0.05, -0.05, -0.05}, (double[3]){0.05, 0.05, 0.05});
    dem_time_scales ts;
    dem_time_scales_get(s, 0, &ts);
    dem_set_dt(s, ts.recommended_dt);
    return s;
}

static dem_sim *build_sphere(void *ctx) { return sphere_sim(0.03, 0.006, &rubber, ctx); }
/* the same with vertex spheres that overlap their neighbours (radius 4 mm, edges near 6 mm), as MSS_particle uses */
static dem_sim *build_fat_sphere(void *ctx)
{
    dem_membrane fat = rubber;
    fat.vertex_radius = 0.004;
    return sphere_sim(0.03, 0.006, &fat, ctx);
}

/* At rest (springs at their rest lengths, hinges at their rest angles, no pressure) a membrane exerts nothing, and
 * stays put for 200 steps. */
static void check_rest(dem_sim *s, const backend_case *bc, void *ctx)
{
    const dem_membrane_info *info = ctx;
    assert_int_equal(dem_spring_count(s), info->nsprings);
    assert_int_equal(dem_hinge_count(s), info->nhinges);
    assert_int_equal(dem_triangle_count(s), info->ntriangles);
    int n = info->nvertices;
    double *f = malloc(sizeof(double) * 3 * (size_t)n), *x0 = malloc(sizeof(double) * 3 * (size_t)n), worst = 0;
    double *x = malloc(sizeof(double) * 3 * (size_t)n), k = sqrt(3.0) / 2 * rubber.young * rubber.thickness;
    assert_int_equal(dem_get_field(s, DEM_FIELD_FORCE, f), 0);
    assert_int_equal(dem_get_field(s, DEM_FIELD_X, x0), 0);
    for (int i = 0; i < 3 * n; i++)
        worst = fmax(worst, fabs(f[i]));
    step_or_fail(s, 200);
    assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
    double moved = 0;
    for (int i = 0; i < 3 * n; i++)
        moved = fmax(moved, fabs(x[i] - x0[i]));
    printf("  %s: largest force at rest %.2g N (k s eps = %.2g N), largest move in 200 steps %.2g m\n", bc->name,
           worst, k * 0.006 * bc->eps, moved);
    /* rest lengths and angles are the initial ones, rounded once in the run precision */
    assert_true(worst <= 64 * k * 0.006 * bc->eps);
    assert_true(moved <= 1e3 * bc->eps * 0.03);
    free(f), free(x0), free(x);
}

static void test_membrane_at_rest(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    { /* vertices that overlap their neighbours do not touch them: still nothing moves */
        dem_membrane_info info;
        backend_run(bc, build_fat_sphere, 0, check_rest, &info);
    }
    FOR_EACH_BACKEND(bc)
    {
        dem_membrane_info info;
        backend_run(bc, build_sphere, 0, check_rest, &info);
    }
}

/* The membrane's numbers: springs of (sqrt(3)/2) E d, vertex masses that add up to rho d A, hinge counts. */
static void test_membrane_parameters(void **st)
{
    (void)st;
    dem_membrane_info info;
    dem_sim *s = build_sphere(&info);
    assert_int_equal(info.first_particle, 0);
    assert_int_equal(info.nhinges, info.nsprings); /* closed: every edge a hinge */
    assert_int_equal(info.nvertices - info.nsprings + info.ntriangles, 2);
    double total = 0;
    for (int i = 0; i < info.nvertices; i++)
        total += dem_particle_mass(s, i);
    printf("  sphere membrane: %d vertices, mass %.6g kg (rho d A = %.6g kg), area %.6g m^2\n", info.nvertices, total,
           info.mass, info.area);
    assert_true(fabs(total / (rubber.density * rubber.thickness * info.area) - 1) < 1e-12);
    dem_time_scales ts;
    assert_int_equal(dem_time_scales_get(s, 0, &ts), 0);
    double mmin = INFINITY, k = sqrt(3.0) / 2 * rubber.young * rubber.thickness;
    for (int i = 0; i < info.nvertices; i++)
        mmin = fmin(mmin, dem_particle_mass(s, i));
    /* the shortest spring period: m_eff of a spring at the lightest vertex is between mmin / 2 and mmin */
    printf("  shortest spring period %.4g s, between %.4g s and %.4g s\n", ts.spring_period,
           2 * M_PI * sqrt(0.5 * mmin / k), 2 * M_PI * sqrt(mmin / k));
    assert_true(ts.spring_period >= 2 * M_PI * sqrt(0.5 * mmin / k) * (1 - 1e-12));
    assert_true(ts.spring_period <= 2 * M_PI * sqrt(mmin / k) * (1 + 1e-12));
    dem_destroy(s);
}

/* The generated sphere as a balloon: under the internal pressure p (a negative confining pressure: the triangles point
 * inward) it settles at the membrane law's strain p R (1 - 1/3) / (2 E d) (seed 001's balloon check, here through the
 * library's mesh and dem_add_membrane; no hinges, so that only the stretching law is measured). */
#define BALLOON_R 0.03
#define BALLOON_STRAIN 0.01

static double balloon_pressure(void)
{
    return BALLOON_STRAIN * 2 * rubber.young * rubber.thickness / (BALLOON_R * (1 + BALLOON_STRAIN) * (2.0 / 3));
}

static dem_sim *build_balloon(void *ctx)
{
    dem_membrane mm = rubber;
    mm.kel = mm.kdiss = 0;
    dem_sim *s = sphere_sim(BALLOON_R, 0.004, &mm, ctx);
    assert_int_equal(dem_set_pressure(s, -balloon_pressure()), 0);
    return s;
}

static void check_balloon(dem_sim *s, const backend_case *bc, void *ctx)
{
    const dem_membrane_info *info = ctx;
    int n = info->nvertices;
    double *x = malloc(sizeof(double) * 3 * (size_t)n), prev = 0, drift = 0, mean = 0, lo = INFINITY, hi = 0;
    for (int round = 0; round < 6; round++) { /* settled: the mean radius no longer moves */
        step_or_fail(s, 4000);
        assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
        mean = 0, lo = INFINITY, hi = 0;
        for (int i = 0; i < n; i++) {
            double r = sqrt(x[3 * i] * x[3 * i] + x[3 * i + 1] * x[3 * i + 1] + x[3 * i + 2] * x[3 * i + 2]);
            mean += r / n, lo = fmin(lo, r), hi = fmax(hi, r);
        }
        drift = fabs(mean - prev) / BALLOON_R, prev = mean;
    }
    free(x);
    double strain = mean / BALLOON_R - 1;
    printf("  %s: %d vertices, p %.4g Pa: strain %.5f (membrane law %.5f, relative %.2g), radii %.6f..%.6f m, "
           "last drift %.1g\n", bc->name, n, balloon_pressure(), strain, BALLOON_STRAIN, strain / BALLOON_STRAIN - 1,
           lo, hi, drift);
    assert_true(drift < (bc->precision == DEM_FP64 ? 1e-6 : 4e-6));
    assert_true(fabs(strain / BALLOON_STRAIN - 1) < 0.02);
}

static void test_balloon(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    {
        dem_membrane_info info;
        backend_run(bc, build_balloon, 0, check_balloon, &info);
    }
}

/* Restart: a membrane under a confining pressure (crumpling: springs, hinges and pressure all at work) saved after
 * 300 steps and restored into a fresh run (started from the mesh, so rest lengths and angles are the mesh's)
 * continues bit for bit. */
static dem_sim *build_squeezed(void)
{
    dem_membrane_info info;
    dem_sim *s = build_sphere(&info);
    assert_int_equal(dem_set_pressure(s, 2000), 0);
    return s;
}

static void test_restart_bitwise(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    {
        dem_config c = cfg_of(bc->backend, bc->precision);
        dem_sim *a = build_squeezed(), *b = build_squeezed();
        restart_check(a, b, &c, 300, 300, bc->name);
        double *x = malloc(sizeof(double) * 3 * (size_t)dem_count(a));
        assert_int_equal(dem_get_field(a, DEM_FIELD_X, x), 0); /* the first vertex moved: the run did something */
        assert_true(fabs(sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]) - 0.03) > 1e-6);
        free(x);
        dem_destroy(a);
        dem_destroy(b);
    }
}

/* Riders: a tube membrane whose end rings ride on two plane walls (dem_attach_to_wall), the top wall moving down,
 * pausing, and moving up. Every rider's velocity is its wall's, and its z stays within a rounding or two of its wall's
 * displacement, in fp32 too (placed, not integrated: common/riders.h); the bottom ring stays; the rings lie on their
 * walls and exert no force on them (a rider does not touch its wall); OpenCL equals the reference. */
#define TUBE_DT 2e-6

typedef struct {
    int nv, na;              /* vertices; riders per ring */
    int ring[2][256];        /* bottom, top */
    double z0[2][256];
} riders;

static dem_sim *build_riders(void *ctx)
{
    riders *rd = ctx;
    dem_sim *s = dem_create();
    dem_mesh m;
    char err[256];
    dem_mesh_spec sp = {DEM_MESH_TUBE, {0, 0, 0.05}, 0.02, 0.06, 0.006};
    if (dem_mesh_make(&sp, &m, err, sizeof err))
        fail_msg("%s", err);
    dem_membrane_info info;
    if (dem_add_membrane(s, &m, &rubber, &info))
        fail_msg("%s", dem_error(s));
    int steel = dem_add_material(s, &(dem_material){7800, INFINITY, 0.3, 0.5, 0.3});
    /* the rings lie on the walls: each vertex overlaps its wall by its radius, and touches it not at all */
    dem_wall lo = {DEM_WALL_PLANE, steel, {0, 0, 0.02}, {0, 0, 1}, 0, 0, {{0}}};
    dem_wall hi = {DEM_WALL_PLANE, steel, {0, 0, 0.08}, {0, 0, -1}, 0, 3,
                   {{200 * TUBE_DT, {0, 0, -0.5}}, {100 * TUBE_DT, {0, 0, 0}}, {100 * TUBE_DT, {0, 0, 1.0}}}};
    int wl = dem_add_wall(s, &lo), wh = dem_add_wall(s, &hi);
    rd->nv = info.nvertices;
    int count[2] = {0, 0};
    for (int i = 0; i < m.nv; i++) {
        double z = m.x[3 * i + 2];
        int side = fabs(z - 0.02) < 1e-12 ? 0 : fabs(z - 0.08) < 1e-12 ? 1 : -1;
        if (side < 0)
            continue;
        assert_true(count[side] < 256);
        rd->ring[side][count[side]] = i, rd->z0[side][count[side]++] = z;
        assert_int_equal(dem_attach_to_wall(s, i, side ? wh : wl), 0);
    }
    assert_int_equal(count[0], count[1]);
    rd->na = count[0];
    assert_int_equal(dem_attach_to_wall(s, rd->ring[0][0], wh), DEM_ERR_ARG); /* one wall per rider */
    dem_mesh_free(&m);
    dem_set_domain(s, (double[3]){-0.05, -0.05, 0}, (double[3]){0.05, 0.05, 0.1});
    dem_set_dt(s, TUBE_DT);
    return s;
}

static void check_riders(dem_sim *s, const backend_case *bc, void *ctx)
{
    riders *rd = ctx;
    static const long phase[3] = {200, 100, 100};
    static const double vz[3] = {-0.5, 0, 1.0};
    double *x = malloc(sizeof(double) * 3 * (size_t)rd->nv), *v = malloc(sizeof(double) * 3 * (size_t)rd->nv);
    double p0[3], p[3];
    dem_wall_position(s, 1, p0);
    assert_int_equal(dem_get_field(s, DEM_FIELD_V, v), 0); /* at the start too: the first stage's velocity */
    for (int k = 0; k < rd->na; k++)
        assert_true(v[3 * rd->ring[1][k] + 2] == vz[0] && v[3 * rd->ring[0][k] + 2] == 0);
    for (int ph = 0; ph < 3; ph++) {
        step_or_fail(s, phase[ph] - 1); /* the last step of the phase still moves at its velocity: look before it */
        assert_int_equal(dem_get_field(s, DEM_FIELD_V, v), 0);
        step_or_fail(s, 1);
        assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
        dem_wall_position(s, 1, p);
        double worst = 0;
        for (int k = 0; k < rd->na; k++) {
            int b = rd->ring[0][k], t = rd->ring[1][k];
            assert_true(fabs(x[3 * b + 2] - rd->z0[0][k]) <= 2 * 0.1 * bc->eps);
            assert_true(v[3 * t + 2] == vz[ph] && v[3 * t] == 0 && v[3 * b + 2] == 0);
            worst = fmax(worst, fabs((x[3 * t + 2] - rd->z0[1][k]) - (p[2] - p0[2])));
        }
        printf("  %s, phase %d: top wall moved %.6g mm, its riders within %.2g m of it\n", bc->name, ph,
               1e3 * (p[2] - p0[2]), worst);
        assert_true(worst <= 4 * 0.1 * bc->eps); /* a rounding or two of coordinates near 0.1 m, at any step */
        double f0[3], f1[3]; /* riders do not push the walls they ride on */
        dem_wall_force(s, 0, f0), dem_wall_force(s, 1, f1);
        assert_true(f0[0] == 0 && f0[1] == 0 && f0[2] == 0 && f1[0] == 0 && f1[1] == 0 && f1[2] == 0);
        dem_energy_t en;
        assert_int_equal(dem_energy(s, &en), 0);
        assert_int_equal(en.wall_contacts, 0);
        double want = ph < 2 ? -2e-4 : 0; /* down 0.2 mm, hold, up 0.2 mm */
        assert_true(fabs(p[2] - p0[2] - want) < 1e-12);
    }
    free(x), free(v);
}

static void test_riders(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    {
        riders rd;
        backend_run(bc, build_riders, 0, check_riders, &rd);
    }
}

/* Refusals leave the simulation as it was. */
static void test_membrane_refusals(void **st)
{
    (void)st;
    dem_sim *s = dem_create();
    int mat = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0});
    dem_add_particle(s, (double[3]){0.2, 0.2, 0.2}, NULL, 0.001, mat);
    dem_mesh m;
    char err[256];
    dem_mesh_spec sp = {DEM_MESH_SHEET, {0, 0, 0}, 0.05, 0.05, 0.01};
    assert_int_equal(dem_mesh_make(&sp, &m, err, sizeof err), 0);
    dem_membrane bad = rubber;
    bad.vertex_radius = 0.006; /* more than half the edge */
    assert_int_equal(dem_add_membrane(s, &m, &bad, NULL), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "vertex_radius"));
    bad = rubber, bad.thickness = 0;
    assert_int_equal(dem_add_membrane(s, &m, &bad, NULL), DEM_ERR_ARG);
    bad = rubber, bad.kel = -1;
    assert_int_equal(dem_add_membrane(s, &m, &bad, NULL), DEM_ERR_ARG);
    int t = m.tri[1]; /* one triangle turned the other way */
    m.tri[1] = m.tri[2], m.tri[2] = t;
    assert_int_equal(dem_add_membrane(s, &m, &rubber, NULL), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "turned opposite ways"));
    m.tri[2] = m.tri[1]; /* a degenerate triangle */
    assert_int_equal(dem_add_membrane(s, &m, &rubber, NULL), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "three different vertices"));
    assert_int_equal(dem_count(s), 1);
    assert_int_equal(dem_spring_count(s) + dem_triangle_count(s) + dem_hinge_count(s), 0);
    dem_mesh_free(&m);
    dem_mesh_spec huge = {DEM_MESH_SPHERE, {0, 0, 0}, 1, 0, 1e-5};
    assert_int_equal(dem_mesh_make(&huge, &m, err, sizeof err), DEM_ERR_ARG);
    assert_non_null(strstr(err, "needs more than"));
    dem_mesh_spec neg = {DEM_MESH_TUBE, {0, 0, 0}, 0.01, -1, 0.001};
    assert_int_equal(dem_mesh_make(&neg, &m, err, sizeof err), DEM_ERR_ARG);
    dem_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_generated_meshes),
        cmocka_unit_test(test_sheet_angles),
        cmocka_unit_test(test_membrane_at_rest),
        cmocka_unit_test(test_membrane_parameters),
        cmocka_unit_test(test_balloon),
        cmocka_unit_test(test_restart_bitwise),
        cmocka_unit_test(test_riders),
        cmocka_unit_test(test_membrane_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
