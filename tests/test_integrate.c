/* test_integrate.c - the kernels integrate_kick_drift, integrate_kick, integrate_kick_kick_drift (the two joined:
 * test_joined_kicks) and their reference twins, on every
 * backend x precision: a free particle under gravity follows x0 + v0 t + g t^2 / 2 and v0 + g t (velocity Verlet
 * is exact for a constant force, so only rounding remains: checked to 4 eps per step of the motion's scale), spins
 * at its initial angular velocity (no torque), and a fixed particle stays exactly where it is. With the gravity
 * effect off, the same particle flies straight. OpenCL = the reference bit for bit. The rebuild trigger (moved more
 * than skin/2) is exercised by every moving run (tests/test_neighbor.c checks the rows it produces). Held velocity
 * components (DEM_PARTICLE_HOLD_V*) stay as set. */
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define STEPS 1000
#define DT 1e-5

static const double x0[3] = {0.001, -0.002, 0.003}, v0[3] = {0.4, -0.1, 0.7}, w0[3] = {3, -5, 11};
static const double g[3] = {0.5, 0, -9.81};

static dem_sim *build(void *ctx)
{
    int gravity = *(const int *)ctx;
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0.4});
    int a = dem_add_particle(s, x0, v0, 0.001, m);
    dem_set_particle_omega(s, a, w0);
    int b = dem_add_particle(s, (double[3]){0.02, 0.02, 0.02}, NULL, 0.001, m);
    dem_set_particle_flags(s, b, DEM_PARTICLE_FIXED);
    dem_set_gravity(s, g);
    dem_set_domain(s, (double[3]){-0.05, -0.05, -0.05}, (double[3]){0.05, 0.05, 0.05});
    dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_FRICTION | (gravity ? DEM_EFFECT_GRAVITY : 0));
    dem_set_dt(s, DT);
    return s;
}

static void check(dem_sim *s, const backend_case *bc, void *ctx)
{
    int gravity = *(const int *)ctx;
    double x[6], v[6], w[6], t = STEPS * DT, worst = 0;
    assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
    assert_int_equal(dem_get_field(s, DEM_FIELD_V, v), 0);
    assert_int_equal(dem_get_field(s, DEM_FIELD_W, w), 0);
    for (int k = 0; k < 3; k++) {
        double gk = gravity ? g[k] : 0;
        double xe = x0[k] + v0[k] * t + 0.5 * gk * t * t, ve = v0[k] + gk * t;
        double xs = fabs(x0[k]) + fabs(v0[k]) * t + 0.5 * fabs(g[k]) * t * t;
        double tol_x = 4.0 * STEPS * bc->eps * xs, tol_v = 4.0 * STEPS * bc->eps * (fabs(v0[k]) + fabs(g[k]) * t);
        if (!(fabs(x[k] - xe) <= tol_x && fabs(v[k] - ve) <= tol_v))
            fail_msg("%s: component %d: x %.17g (want %.17g), v %.17g (want %.17g)", bc->name, k, x[k], xe, v[k], ve);
        worst = fmax(worst, fabs(x[k] - xe) / tol_x);
        assert_true(w[k] == (bc->precision == DEM_FP32 ? (double)(float)w0[k] : w0[k])); /* no torque: spin kept */
        assert_true(x[3 + k] == (bc->precision == DEM_FP32 ? (double)(float)0.02 : 0.02)); /* fixed stays */
        assert_true(v[3 + k] == 0);
    }
    printf("  %s, gravity %s: position error %.2g of the rounding bound after %d steps\n", bc->name,
           gravity ? "on" : "off", worst, STEPS);
}

static void test_free_flight(void **st)
{
    (void)st;
    int gravity = 1;
    FOR_EACH_BACKEND(bc)
    backend_run(bc, build, STEPS, check, &gravity);
}

static void test_gravity_off(void **st)
{
    (void)st;
    int gravity = 0;
    FOR_EACH_BACKEND(bc)
    backend_run(bc, build, STEPS, check, &gravity);
}

/* A body's mass apart from its radius (dem_set_particle_mass): a sphere of 4 times its material's mass, at rest, hit
 * head-on by a plain one at v with restitution e (the damping is calibrated on the pair's m*, so e holds) leaves at
 * (1 + e) m_B v / (m_A + m_B) (momentum and restitution), on every backend x precision. */
static dem_sim *build_mass(void *ctx)
{
    (void)ctx;
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0});
    int a = dem_add_particle(s, (double[3]){0, 0, 0}, NULL, 0.001, m);
    dem_add_particle(s, (double[3]){-0.00201, 0, 0}, (double[3]){0.5, 0, 0}, 0.001, m);
    double m0 = 2500 * 4.0 / 3.0 * M_PI * 1e-9;
    assert_int_equal(dem_set_particle_mass(s, a, 4 * m0, 0), 0);
    dem_set_domain(s, (double[3]){-0.02, -0.02, -0.02}, (double[3]){0.02, 0.02, 0.02});
    dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_DAMPING);
    dem_set_dt(s, 2e-7);
    return s;
}

static void check_mass(dem_sim *s, const backend_case *bc, void *ctx)
{
    (void)ctx;
    double v[6];
    assert_int_equal(dem_get_field(s, DEM_FIELD_V, v), 0);
    double want_a = (1 + 0.5) * 1 * 0.5 / (4 + 1), want_b = 0.5 - 4 * want_a; /* momentum: m0 v = 4 m0 v_a + m0 v_b */
    printf("  %s: heavy sphere leaves at %.6f m/s (want %.6f), light one at %.6f m/s (want %.6f)\n", bc->name, v[0],
           want_a, v[3], want_b);
    assert_true(fabs(v[0] / want_a - 1) < 5e-3 && fabs(v[3] - want_b) < 5e-3 * 0.5);
}

static void test_explicit_mass(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    backend_run(bc, build_mass, 2000, check_mass, NULL);
}

/* Held velocity components (DEM_PARTICLE_HOLD_V*): a particle under gravity (0.5, 0.3, -9.81) m/s^2, held along x
 * and z, keeps those velocity components bit for bit and moves at them, while y follows gravity; a second one, held
 * along z only and dropped onto a plane, keeps its vertical velocity through the contact (the wall cannot stop a
 * prescribed motion) and pushes it. */
static dem_sim *build_hold(void *ctx)
{
    (void)ctx;
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0.4});
    int a = dem_add_particle(s, x0, v0, 0.001, m);
    int b = dem_add_particle(s, (double[3]){0.02, 0.02, 0.0012}, (double[3]){0, 0, -0.1}, 0.001, m);
    assert_int_equal(dem_set_particle_flags(s, a, DEM_PARTICLE_HOLD_VX | DEM_PARTICLE_HOLD_VZ), 0);
    assert_int_equal(dem_set_particle_flags(s, b, DEM_PARTICLE_HOLD_VZ), 0);
    dem_wall floor = {DEM_WALL_PLANE, m, {0, 0, 0}, {0, 0, 1}, 0, 0, {{0}}};
    dem_add_wall(s, &floor);
    dem_set_gravity(s, (double[3]){0.5, 0.3, -9.81});
    dem_set_domain(s, (double[3]){-0.05, -0.05, -0.05}, (double[3]){0.05, 0.05, 0.05});
    assert_true(dem_effects(s) & DEM_EFFECT_CONSTRAINTS);
    dem_set_dt(s, DT);
    return s;
}

static void check_hold(dem_sim *s, const backend_case *bc, void *ctx)
{
    (void)ctx;
    double x[6], v[6], f[3], t = STEPS * DT;
    assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
    assert_int_equal(dem_get_field(s, DEM_FIELD_V, v), 0);
    double r0 = bc->precision == DEM_FP32 ? (double)(float)v0[0] : v0[0];
    double r2 = bc->precision == DEM_FP32 ? (double)(float)v0[2] : v0[2];
    double rb = bc->precision == DEM_FP32 ? (double)(float)-0.1 : -0.1;
    assert_true(v[0] == r0 && v[2] == r2 && v[5] == rb); /* held: not a bit changed */
    assert_true(fabs(v[1] - (v0[1] + 0.3 * t)) <= 4.0 * STEPS * bc->eps); /* free: gravity */
    assert_true(fabs(x[2] - (x0[2] + v0[2] * t)) <= 4.0 * STEPS * bc->eps * 0.01);
    dem_wall_force(s, 0, f);
    printf("  %s: held components unchanged, free ones follow gravity; the held sphere pushes into the floor with "
           "%.3g N after %d steps (it moved down %.3g mm)\n", bc->name, -f[2], STEPS, 1e3 * (0.0012 - x[5]));
    assert_true(f[2] < 0); /* the floor does feel it */
}

static void test_hold(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    backend_run(bc, build_hold, STEPS, check_hold, NULL);
}

/* The second kick of a step joined to the next step's first (integrate_kick_kick_drift, host/core/step_loop.c): a
 * dense, frictional packing under gravity with a moving lid stepped 300 times in one dem_step call (joined: every
 * step but the last) has, on every backend and precision, the bits of the same run stepped one step per call (never
 * joined: each call's last step kicks alone), and PoCL's have the reference's. The joined run's last step must have
 * begun with the joined launch and the other's not, so that the comparison is of the two paths. */
static void test_joined_kicks(void **st)
{
    (void)st;
    packing_opts o;
    packing_defaults(&o);
    o.side = 6; /* 216 + 125 spheres */
    for (int p = 0; p < 2; p++) {
        dem_precision prec = p ? DEM_FP32 : DEM_FP64;
        dem_sim *runs[4]; /* reference joined, PoCL joined, reference one step a call, PoCL one step a call */
        for (int k = 0; k < 4; k++) {
            runs[k] = packing_build(&o);
            dem_config c = cfg_of(k % 2 ? DEM_BACKEND_OPENCL : DEM_BACKEND_REFERENCE, prec);
            start_or_fail(runs[k], &c);
        }
        int n = dem_count(runs[0]);
        double *xa = malloc(sizeof(double) * 3 * (size_t)n), *xb = malloc(sizeof(double) * 3 * (size_t)n);
        assert_int_equal(dem_get_field(runs[0], DEM_FIELD_X, xa), 0);
        for (int k = 0; k < 2; k++)
            assert_int_equal(dem_step(runs[k], 300), 0);
        for (int t = 0; t < 300; t++)
            for (int k = 2; k < 4; k++)
                assert_int_equal(dem_step(runs[k], 1), 0);
        for (int k = 0; k < 4; k++) {
            assert_int_equal(dem_kernel_launched(runs[k], 0, "integrate_kick_kick_drift"), k < 2);
            assert_int_equal(dem_kernel_launched(runs[k], 0, "integrate_kick_drift"), k >= 2);
            assert_false(dem_kernel_launched(runs[k], 0, "integrate_kick_kick")); /* a whole name, not a part */
        }
        assert_int_equal(dem_get_field(runs[0], DEM_FIELD_X, xb), 0);
        assert_true(memcmp(xa, xb, sizeof(double) * 3 * (size_t)n)); /* it moved */
        free(xa), free(xb);
        char msg[512];
        dem_sim *others[3] = {runs[0], runs[1], runs[3]};
        int d = state_diff_each(runs[2], others, 3, msg, sizeof msg);
        if (d >= 0)
            fail_msg("%s: joined kicks: %s", prec == DEM_FP32 ? "fp32" : "fp64", msg);
        printf("  %s: 300 steps in one call (kicks joined) = 300 calls of one step, reference and PoCL\n",
               prec == DEM_FP32 ? "fp32" : "fp64");
        for (int k = 0; k < 4; k++)
            dem_destroy(runs[k]);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hold),
        cmocka_unit_test(test_free_flight),
        cmocka_unit_test(test_gravity_off),
        cmocka_unit_test(test_explicit_mass),
        cmocka_unit_test(test_joined_kicks),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
