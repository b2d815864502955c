/* test_pressure.c - kernels/pressure.cl (pressure_forces, through the contribution channel of kernels/springs.cl)
 * and its reference twin, on every backend x precision: a triangle under the pressure sigma gives each vertex
 * sigma A n_hat / 3 (seed 001 Eq. 18, current area and normal); a closed octahedron of springs under an inward
 * pressure settles where the springs carry it, at the edge length L of sigma L^2 / 3 = 2 sqrt(2) k (L0 - L) (each
 * vertex: four faces push sigma (sqrt(3)/4) L^2 / 3 each along their inward normals, four springs at 45 degrees
 * push back), and stays symmetric; a closed sphere of springs under internal pressure settles at the membrane law's
 * strain (issue 10, test 3). */
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

static const dem_material gel = {1000, 1e6, 0.3, 0.5, 0};

static dem_sim *build_triangle(void *ctx)
{
    (void)ctx;
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &gel);
    double p[3][3] = {{0.001, -0.002, 0.0005}, {0.021, 0.001, -0.001}, {0.004, 0.018, 0.002}};
    for (int k = 0; k < 3; k++)
        dem_add_particle(s, p[k], NULL, 0.001, m);
    assert_int_equal(dem_add_triangle(s, 0, 1, 2), 0);
    assert_int_equal(dem_set_pressure(s, 2.5e4), 0);
    dem_set_domain(s, (double[3]){-0.05, -0.05, -0.05}, (double[3]){0.05, 0.05, 0.05});
    dem_set_dt(s, 1e-6);
    return s;
}

static void check_triangle(dem_sim *s, const backend_case *bc, void *ctx)
{
    (void)ctx;
    double x[9], f[9];
    assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
    assert_int_equal(dem_get_field(s, DEM_FIELD_FORCE, f), 0);
    double u[3], v[3], cr[3];
    for (int q = 0; q < 3; q++)
        u[q] = x[3 + q] - x[q], v[q] = x[6 + q] - x[q];
    cr[0] = u[1] * v[2] - u[2] * v[1], cr[1] = u[2] * v[0] - u[0] * v[2], cr[2] = u[0] * v[1] - u[1] * v[0];
    double big = 0;
    for (int q = 0; q < 3; q++)
        big = fmax(big, fabs(2.5e4 * cr[q] / 6));
    for (int k = 0; k < 3; k++)
        for (int q = 0; q < 3; q++) {
            double want = 2.5e4 * cr[q] / 6; /* sigma A n_hat / 3 = sigma (u x v) / 6 */
            if (!(fabs(f[3 * k + q] - want) <= 16 * bc->eps * big))
                fail_msg("%s: vertex %d component %d: %.17g N, closed form %.17g N", bc->name, k, q, f[3 * k + q], want);
        }
}

static void test_triangle_load(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    backend_run(bc, build_triangle, 0, check_triangle, NULL);
}

#define A0 0.01
#define K_SPRING 200.0
#define SIGMA 2.0e4

static dem_sim *build_octahedron(void *ctx)
{
    (void)ctx;
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &gel);
    for (int k = 0; k < 6; k++) { /* +x, -x, +y, -y, +z, -z */
        double p[3] = {0, 0, 0};
        p[k / 2] = k % 2 ? -A0 : A0;
        dem_add_particle(s, p, NULL, 0.001, m);
    }
    for (int a = 0; a < 6; a++) /* the 12 edges: every pair on different axes */
        for (int b = a + 1; b < 6; b++)
            if (a / 2 != b / 2)
                assert_true(dem_add_spring(s, a, b, K_SPRING, -1, 0.5) >= 0);
    for (int sx = 0; sx < 2; sx++) /* the 8 faces, ordered so that (x_b - x_a) x (x_c - x_a) points inward */
        for (int sy = 0; sy < 2; sy++)
            for (int sz = 0; sz < 2; sz++) {
                int a = sx, b = 2 + sy, c = 4 + sz;
                double pa[3] = {sx ? -A0 : A0, 0, 0}, pb[3] = {0, sy ? -A0 : A0, 0}, pc[3] = {0, 0, sz ? -A0 : A0};
                double u[3], v[3], n[3], cen[3];
                for (int q = 0; q < 3; q++)
                    u[q] = pb[q] - pa[q], v[q] = pc[q] - pa[q], cen[q] = pa[q] + pb[q] + pc[q];
                n[0] = u[1] * v[2] - u[2] * v[1], n[1] = u[2] * v[0] - u[0] * v[2], n[2] = u[0] * v[1] - u[1] * v[0];
                int outward = n[0] * cen[0] + n[1] * cen[1] + n[2] * cen[2] > 0;
                assert_true(dem_add_triangle(s, a, outward ? c : b, outward ? b : c) >= 0);
            }
    assert_int_equal(dem_set_pressure(s, SIGMA), 0);
    dem_set_domain(s, (double[3]){-0.05, -0.05, -0.05}, (double[3]){0.05, 0.05, 0.05});
    dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_DAMPING | DEM_EFFECT_SPRINGS | DEM_EFFECT_PRESSURE);
    dem_time_scales ts;
    dem_time_scales_get(s, 0, &ts);
    dem_set_dt(s, ts.recommended_dt);
    return s;
}

static void check_octahedron(dem_sim *s, const backend_case *bc, void *ctx)
{
    (void)ctx;
    step_or_fail(s, 20000); /* many periods at damping ratio 0.5: settled */
    double x[18];
    assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
    double L0 = A0 * sqrt(2.0), c2 = 2 * sqrt(2.0) * K_SPRING, a3 = SIGMA / 3;
    double L = (-c2 + sqrt(c2 * c2 + 4 * a3 * c2 * L0)) / (2 * a3); /* a3 L^2 + c2 L - c2 L0 = 0 */
    double worst = 0;
    for (int a = 0; a < 6; a++)
        for (int b = a + 1; b < 6; b++) {
            if (a / 2 == b / 2)
                continue;
            double d = sqrt(pow(x[3 * a] - x[3 * b], 2) + pow(x[3 * a + 1] - x[3 * b + 1], 2) +
                            pow(x[3 * a + 2] - x[3 * b + 2], 2));
            worst = fmax(worst, fabs(d / L - 1));
        }
    printf("  %s: edge %.9g m under %.3g Pa (rest %.6g m, closed form %.9g m), worst relative %.2g\n", bc->name,
           sqrt(pow(x[0] - x[6], 2) + pow(x[1] - x[7], 2) + pow(x[2] - x[8], 2)), SIGMA, L0, L, worst);
    assert_true(L < 0.95 * L0); /* it did shrink */
    assert_true(worst < (bc->precision == DEM_FP64 ? 1e-8 : 1e-5));
}

static void test_octahedron_equilibrium(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    backend_run(bc, build_octahedron, 0, check_octahedron, NULL);
}

/* A closed sphere membrane under internal pressure (issue 10, test 3): an icosphere (the icosahedron split three
 * times, 642 vertices, 1920 springs, 1280 triangles turned outward) of radius R0 on springs of stiffness k is a
 * membrane of 2D Young's modulus E2D = 2k/sqrt(3) and Poisson's ratio 1/3 (tests/test_springs.c, sheet); under the
 * pressure p it carries the equibiaxial tension p R / 2 and settles at the strain p R (1 - nu) / (2 E2D), R the
 * settled radius; the bound: 2 %. The mesh matters: the icosphere as split (edges within 19 % of each other)
 * settles 2.5 % past the membrane law, non-affinely (radii spread over 0.6 % of R0, as much as the strain); 20 passes
 * of Laplacian smoothing on the sphere make the triangles locally even (though the edges at the 12 five-fold
 * vertices get shorter, 1.46 between extremes) and put it 0.6 % past, radii within 0.06 %. A mesh generator for
 * scenes should smooth the same way. */
#define ICO_R0 0.05
#define ICO_K 100.0
#define ICO_STRAIN 0.01
#ifndef ICO_ROUNDS
#define ICO_ROUNDS 3
#endif
#ifndef ICO_SMOOTH
#define ICO_SMOOTH 20
#endif

typedef struct {
    int nv, nf, ne;
    double v[642][3];
    int f[1280][3], e[1920][2];
} icosphere;

static int ico_midpoint(icosphere *m, int a, int b, int (*mid)[3], int *nmid)
{
    for (int k = 0; k < *nmid; k++)
        if ((mid[k][0] == a && mid[k][1] == b) || (mid[k][0] == b && mid[k][1] == a))
            return mid[k][2];
    double *c = m->v[m->nv], r = 0;
    for (int q = 0; q < 3; q++)
        c[q] = 0.5 * (m->v[a][q] + m->v[b][q]), r += c[q] * c[q];
    for (int q = 0; q < 3; q++)
        c[q] /= sqrt(r);
    mid[*nmid][0] = a, mid[*nmid][1] = b, mid[*nmid][2] = m->nv;
    ++*nmid;
    return m->nv++;
}

static void ico_build(icosphere *m)
{
    double t = (1 + sqrt(5.0)) / 2, p[12][3] = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                                 {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
    static const int f0[20][3] = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                  {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                  {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
    static int mid[1920][3], f[1280][3];
    m->nv = 12, m->nf = 20;
    for (int i = 0; i < 12; i++)
        for (int q = 0; q < 3; q++)
            m->v[i][q] = p[i][q] / sqrt(1 + t * t);
    memcpy(m->f, f0, sizeof f0);
    for (int level = 0; level < 3; level++) {
        int nmid = 0, nf = 0;
        for (int k = 0; k < m->nf; k++) {
            int a = m->f[k][0], b = m->f[k][1], c = m->f[k][2];
            int ab = ico_midpoint(m, a, b, mid, &nmid), bc = ico_midpoint(m, b, c, mid, &nmid);
            int ca = ico_midpoint(m, c, a, mid, &nmid);
            int sub[4][3] = {{a, ab, ca}, {b, bc, ab}, {c, ca, bc}, {ab, bc, ca}};
            memcpy(f[nf], sub, sizeof sub), nf += 4;
        }
        memcpy(m->f, f, sizeof(int[3]) * (size_t)nf), m->nf = nf;
        if (level == 2) { /* the last level's midpoint pairs are the edges that were split; collect all edges anew */
            m->ne = 0;
            for (int k = 0; k < nf; k++)
                for (int j = 0; j < 3; j++) {
                    int a = m->f[k][j], b = m->f[k][(j + 1) % 3];
                    if (a < b) /* every edge is shared by two triangles, once as (a, b) and once as (b, a) */
                        m->e[m->ne][0] = a, m->e[m->ne][1] = b, m->ne++;
                }
        }
    }
    assert_int_equal(m->nv, 642);
    assert_int_equal(m->ne, 1920);
    for (int it = 0; it < ICO_SMOOTH; it++) { /* Laplacian smoothing on the sphere: evens out the edges */
        static double acc[642][3];
        static int deg[642];
        memset(acc, 0, sizeof acc), memset(deg, 0, sizeof deg);
        for (int k = 0; k < m->ne; k++)
            for (int side = 0; side < 2; side++) {
                int a = m->e[k][side], b = m->e[k][1 - side];
                for (int q = 0; q < 3; q++)
                    acc[a][q] += m->v[b][q];
                deg[a]++;
            }
        for (int i = 0; i < m->nv; i++) {
            double r = 0;
            for (int q = 0; q < 3; q++)
                m->v[i][q] = acc[i][q] / deg[i], r += m->v[i][q] * m->v[i][q];
            for (int q = 0; q < 3; q++)
                m->v[i][q] /= sqrt(r);
        }
    }
    double lmin = INFINITY, lmax = 0;
    for (int k = 0; k < m->ne; k++) {
        double d = 0;
        for (int q = 0; q < 3; q++)
            d += pow(m->v[m->e[k][0]][q] - m->v[m->e[k][1]][q], 2);
        lmin = fmin(lmin, sqrt(d)), lmax = fmax(lmax, sqrt(d));
    }
    printf("  icosphere: %d vertices, %d edges, longest / shortest edge %.3f\n", m->nv, m->ne, lmax / lmin);
}

static icosphere ico;

static double ico_tension_pressure(void) /* p with p R (1 - nu) / (2 E2D) = ICO_STRAIN at R = R0 (1 + strain) */
{
    double e2d = 2 * ICO_K / sqrt(3.0);
    return ICO_STRAIN * 2 * e2d / (ICO_R0 * (1 + ICO_STRAIN) * (1 - 1.0 / 3));
}

static dem_sim *build_balloon(void *ctx)
{
    (void)ctx;
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &gel);
    for (int i = 0; i < ico.nv; i++) {
        double p[3] = {ICO_R0 * ico.v[i][0], ICO_R0 * ico.v[i][1], ICO_R0 * ico.v[i][2]};
        dem_add_particle(s, p, NULL, 0.0005, m);
    }
    for (int k = 0; k < ico.ne; k++)
        assert_true(dem_add_spring(s, ico.e[k][0], ico.e[k][1], ICO_K, -1, 0.5) >= 0);
    for (int k = 0; k < ico.nf; k++) {
        const int *f = ico.f[k];
        double u[3], v[3], n[3], c[3];
        for (int q = 0; q < 3; q++)
            u[q] = ico.v[f[1]][q] - ico.v[f[0]][q], v[q] = ico.v[f[2]][q] - ico.v[f[0]][q],
            c[q] = ico.v[f[0]][q] + ico.v[f[1]][q] + ico.v[f[2]][q];
        n[0] = u[1] * v[2] - u[2] * v[1], n[1] = u[2] * v[0] - u[0] * v[2], n[2] = u[0] * v[1] - u[1] * v[0];
        int outward = n[0] * c[0] + n[1] * c[1] + n[2] * c[2] > 0; /* turned outward: the pressure inflates */
        assert_true(dem_add_triangle(s, f[0], outward ? f[1] : f[2], outward ? f[2] : f[1]) >= 0);
    }
    assert_int_equal(dem_set_pressure(s, ico_tension_pressure()), 0);
    dem_set_domain(s, (double[3]){-0.1, -0.1, -0.1}, (double[3]){0.1, 0.1, 0.1});
    dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_DAMPING | DEM_EFFECT_SPRINGS | DEM_EFFECT_PRESSURE);
    dem_time_scales ts;
    dem_time_scales_get(s, 0, &ts);
    dem_set_dt(s, ts.recommended_dt);
    return s;
}

static void check_balloon(dem_sim *s, const backend_case *bc, void *ctx)
{
    (void)ctx;
    static double x[3 * 642];
    double rmin = INFINITY, rmax = 0, rsum = 0, prev = 0, drift = 0;
    for (int round = 0; round < ICO_ROUNDS; round++) { /* settled: the mean radius no longer moves */
        step_or_fail(s, 4000);
        assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
        rsum = 0, rmin = INFINITY, rmax = 0;
        for (int i = 0; i < ico.nv; i++) {
            double r = sqrt(x[3 * i] * x[3 * i] + x[3 * i + 1] * x[3 * i + 1] + x[3 * i + 2] * x[3 * i + 2]);
            rsum += r, rmin = fmin(rmin, r), rmax = fmax(rmax, r);
        }
        drift = fabs(rsum / ico.nv - prev) / ICO_R0, prev = rsum / ico.nv;
    }
    double strain = prev / ICO_R0 - 1;
    printf("  %s: p %.4g Pa, strain %.5f (membrane law %.5f, relative %.2g), radii %.5f..%.5f m, last drift %.1g\n",
           bc->name, ico_tension_pressure(), strain, ICO_STRAIN, strain / ICO_STRAIN - 1, rmin, rmax, drift);
    assert_true(drift < (bc->precision == DEM_FP64 ? 1e-6 : 4e-6)); /* 1e-4 (4e-4) of the strain over 4000 steps */
    assert_true(fabs(strain / ICO_STRAIN - 1) < 0.02);
}

static void test_balloon_radius(void **st)
{
    (void)st;
    ico_build(&ico);
    FOR_EACH_BACKEND(bc)
    backend_run(bc, build_balloon, 0, check_balloon, NULL);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_triangle_load),
        cmocka_unit_test(test_octahedron_equilibrium),
        cmocka_unit_test(test_balloon_radius),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
