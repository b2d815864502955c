/* test_pressure.c - the kernel pressure_forces (through the contribution channel, channel_gather)
 * and its reference twin, on every backend x precision: a triangle under the pressure sigma gives each vertex
 * sigma A n_hat / 3 (seed 001 Eq. 18, current area and normal); a closed octahedron of springs under an inward
 * pressure settles where the springs carry it, at the edge length L of sigma L^2 / 3 = 2 sqrt(2) k (L0 - L) (each
 * vertex: four faces push sigma (sqrt(3)/4) L^2 / 3 each along their inward normals, four springs at 45 degrees
 * push back), and stays symmetric; a pressure schedule ramps and holds. */
#include "test_util.h"
#include <math.h>
#include <stdio.h>

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

/* The triangle's three vertex forces are sigma A n_hat / 3 = sigma (u x v) / 6 (u, v its edges from vertex 0), to
 * `ulps` unit roundoffs of the load under the largest pressure `scale` of the test */
static void assert_load(dem_sim *s, const backend_case *bc, double sigma, double scale, double ulps)
{
    double x[9], f[9];
    assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
    assert_int_equal(dem_get_field(s, DEM_FIELD_FORCE, f), 0);
    double u[3], v[3], cr[3];
    for (int q = 0; q < 3; q++)
        u[q] = x[3 + q] - x[q], v[q] = x[6 + q] - x[q];
    cr[0] = u[1] * v[2] - u[2] * v[1], cr[1] = u[2] * v[0] - u[0] * v[2], cr[2] = u[0] * v[1] - u[1] * v[0];
    double big = 0;
    for (int q = 0; q < 3; q++)
        big = fmax(big, fabs(scale * cr[q] / 6));
    for (int k = 0; k < 3; k++)
        for (int q = 0; q < 3; q++) {
            double want = sigma * cr[q] / 6;
            if (!(fabs(f[3 * k + q] - want) <= ulps * bc->eps * big))
                fail_msg("%s: step %ld, vertex %d component %d: %.17g N, sigma A n_hat / 3 = %.17g N", bc->name,
                         dem_step_index(s), k, q, f[3 * k + q], want);
        }
}

static void check_triangle(dem_sim *s, const backend_case *bc, void *ctx)
{
    (void)ctx;
    assert_load(s, bc, 2.5e4, 2.5e4, 16);
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

/* A pressure schedule: ramp 0 -> 1e4 Pa over 100 steps, then -> -2e4 Pa over 100 steps, then hold. The loads at
 * steps 0, 50, 100, 150, 250 are sigma(t) A n_hat / 3 with sigma(t) of the schedule at the positions' time. */
#define SCHED_DT 1e-6

static dem_sim *build_schedule(void *ctx)
{
    dem_sim *s = build_triangle(ctx);
    assert_int_equal(dem_set_pressure(s, 0), 0);
    dem_pressure_stage st[2] = {{100 * SCHED_DT, 1e4}, {100 * SCHED_DT, -2e4}};
    assert_int_equal(dem_set_pressure_stages(s, 2, st), 0);
    for (int k = 0; k < 3; k++) /* heavy vertices: the triangle barely moves */
        dem_set_particle_mass(s, k, 1e3, 0);
    dem_set_dt(s, SCHED_DT);
    return s;
}

static void check_schedule(dem_sim *s, const backend_case *bc, void *ctx)
{
    (void)ctx;
    static const long at[5] = {0, 50, 100, 150, 250};
    static const double want_sigma[5] = {0, 5e3, 1e4, -5e3, -2e4};
    for (int q = 0; q < 5; q++) {
        step_or_fail(s, at[q] - dem_step_index(s));
        double sigma = dem_pressure(s);
        if (!(fabs(sigma - want_sigma[q]) <= 1e-9 * 2e4))
            fail_msg("%s: step %ld: pressure %.17g Pa, schedule %.17g Pa", bc->name, at[q], sigma, want_sigma[q]);
        assert_load(s, bc, want_sigma[q], 2e4, 32);
    }
}

static void test_pressure_schedule(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    backend_run(bc, build_schedule, 0, check_schedule, NULL);
    dem_sim *s = dem_create();
    assert_int_equal(dem_set_pressure_stages(s, 1, &(dem_pressure_stage){-1, 0}), DEM_ERR_ARG);
    assert_int_equal(dem_set_pressure_stages(s, 1, &(dem_pressure_stage){1, NAN}), DEM_ERR_ARG);
    assert_int_equal(dem_set_pressure_stages(s, DEM_MAX_STAGES + 1, NULL), DEM_ERR_ARG);
    dem_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_triangle_load),
        cmocka_unit_test(test_octahedron_equilibrium),
        cmocka_unit_test(test_pressure_schedule),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
