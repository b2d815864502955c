/* test_hertz_collision.c - two-sphere head-on Hertz collision without damping or friction against the closed forms
 *   t_c = 2.868 (m*^2 / (r* E*^2 v))^(1/5),  d_max = (15 m* v^2 / (16 E* sqrt(r*)))^(2/5),  F_max = 4/3 E* sqrt(r*) d_max^(3/2)
 * typed in here from the textbook (Johnson, Contact Mechanics, 1985, Sec. 11.4), not taken from the library:
 * t_c within 0.1 % (it is counted in steps of t_c / 2000), d_max and F_max within 0.02 %; for equal and unequal
 * spheres, on PoCL in fp64 and fp32, each bitwise equal to the reference. The library's own dem_hertz_* helpers
 * must give the same closed forms. */
#include "test_util.h"
#include <math.h>
#include <stdio.h>

static void collide(double r1, double r2, double v, dem_precision prec)
{
    dem_material m = {1000, 1e7, 0.3, 1.0, 0.0};
    dem_sim *s = pair_build(&m, r1, r2, v, 1.0 / 2000), *ref = pair_build(&m, r1, r2, v, 1.0 / 2000);
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, prec), rc = cfg_of(DEM_BACKEND_REFERENCE, prec);
    start_or_fail(s, &c);
    start_or_fail(ref, &rc);
    double dt = dem_dt(s), dmax = 0, fpeak = 0, tc = 0;
    int was = 0;
    for (int k = 0; k < 4000; k++) {
        step_or_fail(s, 1);
        step_or_fail(ref, 1);
        double delta = r1 + r2 - pair_distance(s), f[6];
        dem_get_field(s, DEM_FIELD_FORCE, f);
        if (delta > 0) {
            was = 1;
            tc += dt;
        } else if (was) {
            break;
        }
        dmax = fmax(dmax, delta);
        fpeak = fmax(fpeak, fabs(f[0]));
    }
    char msg[256];
    if (state_diff(s, ref, msg, sizeof msg))
        fail_msg("PoCL vs reference: %s", msg);
    double m1 = 4.0 / 3.0 * M_PI * r1 * r1 * r1 * m.density, m2 = 4.0 / 3.0 * M_PI * r2 * r2 * r2 * m.density;
    double ms = m1 * m2 / (m1 + m2), rs = r1 * r2 / (r1 + r2), es = m.young / (2 * (1 - m.poisson * m.poisson));
    double tc0 = 2.868 * pow(ms * ms / (rs * es * es * v), 0.2);
    double d0 = pow(15 * ms * v * v / (16 * es * sqrt(rs)), 0.4);
    double f0 = 4.0 / 3.0 * es * sqrt(rs) * d0 * sqrt(d0);
    assert_true(fabs(dem_hertz_contact_time(ms, rs, es, v) / tc0 - 1) < 1e-12);
    if (r1 == r2) { /* the scene's advice: approach at twice each sphere's speed, the same contact time, 2000 steps */
        dem_sim *t = pair_build(&m, r1, r2, v, 1.0 / 2000);
        dem_contact_advice a;
        assert_int_equal(dem_contact_advice_get(t, &a), 0);
        assert_true(fabs(a.pair_speed - v) < 1e-12 * v && a.wall < 0 && a.wall_speed == 0);
        assert_true(fabs(a.contact_time / tc0 - 1) < 1e-12 && fabs(a.steps - 2000) < 1e-6);
        dem_destroy(t);
    }
    assert_true(fabs(dem_hertz_max_overlap(ms, rs, es, v) / d0 - 1) < 1e-12);
    printf("  r %g/%g m, v %g m/s, %s: t_c %.6g (closed %.6g), d_max %.6g (%.6g), F_max %.6g (%.6g)\n", r1, r2, v,
           prec == DEM_FP64 ? "fp64" : "fp32", tc, tc0, dmax, d0, fpeak, f0);
    assert_true(fabs(tc / tc0 - 1) < 1e-3);
    assert_true(fabs(dmax / d0 - 1) < 2e-4);
    assert_true(fabs(fpeak / f0 - 1) < 2e-4);
    dem_destroy(s);
    dem_destroy(ref);
}

static void test_equal_fp64(void **st) { (void)st; collide(0.01, 0.01, 1.0, DEM_FP64); }
static void test_unequal_fp64(void **st) { (void)st; collide(0.01, 0.004, 0.3, DEM_FP64); }
static void test_equal_fp32(void **st) { (void)st; collide(0.01, 0.01, 1.0, DEM_FP32); }

/* The contact advice counts a wall's speed only where its stages bring it onto the particles: a resting sphere whose
 * top is 9 mm below a plane; the plane moves away at 9 m/s for 1 ms (-9 mm), comes back at 5 m/s for 4 ms ramped over
 * 2 ms from the -9 m/s before (4 ms x 5 m/s - 2 ms x (5 + 9) / 2 = +6 mm: still 12 mm away), then at 0.2 m/s for
 * 0.2 s (+40 mm: it arrives): the advice says 0.2 m/s, not 9 or 5. A servo in the last stage counts its max_speed;
 * 10 ms at 5 m/s (+36 mm) arrives fast. */
static void test_wall_approach(void **st)
{
    (void)st;
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0.4});
    dem_add_particle(s, (double[3]){0, 0, 0}, NULL, 0.001, m);
    dem_wall pl = {DEM_WALL_PLANE, m, {0, 0, 0.01}, {0, 0, -1}, 0, 3, {{0}}};
    pl.stages[0] = (dem_stage){.duration = 1e-3, .velocity = {0, 0, 9}};
    pl.stages[1] = (dem_stage){.duration = 4e-3, .velocity = {0, 0, -5}, .ramp = 2e-3};
    pl.stages[2] = (dem_stage){.duration = 0.2, .velocity = {0, 0, -0.2}};
    assert_true(dem_add_wall(s, &pl) >= 0);
    assert_int_equal(dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_WALLS), 0);
    dem_contact_advice a;
    assert_int_equal(dem_contact_advice_get(s, &a), 0);
    printf("  wall approach %.6g m/s (the slow stage's 0.2: the fast ones stop short or move away)\n", a.wall_speed);
    assert_true(a.wall == 0 && a.wall_speed == 0.2);
    pl.stages[2] = (dem_stage){.duration = 0.2, .force = 1, .gain = 1e-3, .max_speed = 0.05}; /* a servo */
    assert_int_equal(dem_set_wall_motion(s, 0, 3, pl.stages), 0);
    assert_int_equal(dem_contact_advice_get(s, &a), 0);
    assert_true(a.wall_speed == 0.05);
    pl.stages[1].duration = 10e-3;
    assert_int_equal(dem_set_wall_motion(s, 0, 3, pl.stages), 0);
    assert_int_equal(dem_contact_advice_get(s, &a), 0);
    assert_true(a.wall_speed == 5);
    dem_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_equal_fp64),
        cmocka_unit_test(test_unequal_fp64),
        cmocka_unit_test(test_equal_fp32),
        cmocka_unit_test(test_wall_approach),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
