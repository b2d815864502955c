/* test_rolling.c - rolling resistance of constant torque (common/rolling.h, DEM_EFFECT_ROLLING; Ai et al. 2011,
 * model A), against closed forms typed in here:
 *   - a sphere rolling without slip on a plane under gravity (friction ample) slows at
 *     a = mu_r g R arm / (2/5 R^2 + arm^2)   (arm = R - delta, the contact's lever; 5/7 mu_r g as delta -> 0),
 *     from m a = F_t and I dw/dt = -arm F_t - mu_r R m g with v = w arm; reference and PoCL, fp64, bit for bit;
 *   - two equal spheres pressed together and spinning oppositely about the same axis roll on each other without
 *     slip: after a step the torques are -+mu_r (R/2) F_n along the axis (F_n Hertz's at the overlap), equal and
 *     opposite, with no friction torque;
 *   - rolling without friction is refused (no spins without it). */
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

#define R 0.005
#define RHO 2500.0
#define YOUNG 1e7
#define NU 0.3
#define MU_R 0.05
#define G 9.81

static double estar_same(void) { return YOUNG / (2 * (1 - NU * NU)); }

static dem_sim *rolling_sphere(double v0, double d0)
{
    dem_sim *s = dem_create();
    dem_material m = {RHO, YOUNG, NU, 0.5, 0.8, 0, 0, 0, MU_R};
    int id = dem_add_material(s, &m);
    double arm = R - d0;
    dem_add_particle(s, (double[3]){0, 0, arm}, (double[3]){v0, 0, 0}, R, id);
    dem_wall floor = {.kind = DEM_WALL_PLANE, .material = id, .point = {0, 0, 0}, .normal = {0, 0, 1}};
    assert_true(dem_add_wall(s, &floor) >= 0);
    dem_set_gravity(s, (double[3]){0, 0, -G});
    dem_set_domain(s, (double[3]){-0.01, -0.02, -0.01}, (double[3]){0.1, 0.02, 0.02});
    assert_int_equal(dem_set_effects(s, DEM_EFFECT_CLASSICAL | DEM_EFFECT_ROLLING), 0);
    dem_time_scales ts;
    dem_time_scales_get(s, 0, &ts);
    dem_set_dt(s, 0.2 * ts.rayleigh_time);
    return s;
}

/* spin of a rolling start: v = w arm with w along +y for motion along +x over a floor below */
static void set_spin(dem_sim *s, double w)
{
    dem_state st;
    assert_int_equal(dem_state_get(s, &st), 0);
    dem_state_array *a = dem_state_find(&st, "w");
    assert_non_null(a);
    ((double *)a->data)[1] = w;
    assert_int_equal(dem_state_set(s, &st), 0);
    dem_state_free(&st);
}

static void test_sphere_on_plane(void **st)
{
    (void)st;
    double m = RHO * 4.0 / 3.0 * M_PI * R * R * R, es = estar_same(); /* the floor of the same material */
    double d0 = pow(m * G / (4.0 / 3.0 * es * sqrt(R)), 2.0 / 3.0), arm = R - d0, v0 = 0.1;
    double a_expect = MU_R * G * R * arm / (0.4 * R * R + arm * arm);
    dem_sim *cl = rolling_sphere(v0, d0), *ref = rolling_sphere(v0, d0);
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, DEM_FP64), rc = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    start_or_fail(cl, &c);
    start_or_fail(ref, &rc);
    set_spin(cl, v0 / arm);
    set_spin(ref, v0 / arm);
    double dt = dem_dt(ref);
    long n1 = lround(0.02 / dt), n2 = lround(0.1 / dt);
    double v1[3], v2[3], w2[3];
    twins_step(cl, ref, n1, "rolling sphere, PoCL vs reference");
    assert_int_equal(dem_get_field(ref, DEM_FIELD_V, v1), 0);
    twins_step(cl, ref, n2 - n1, "rolling sphere, PoCL vs reference");
    assert_int_equal(dem_get_field(ref, DEM_FIELD_V, v2), 0);
    assert_int_equal(dem_get_field(ref, DEM_FIELD_W, w2), 0);
    double a = -(v2[0] - v1[0]) / ((double)(n2 - n1) * dt);
    printf("  rolling sphere: slows at %.6g m/s^2 (closed form %.6g; 5/7 mu_r g = %.6g), slip %.3g m/s at the end\n", a,
           a_expect, 5.0 / 7.0 * MU_R * G, v2[0] - w2[1] * arm);
    assert_true(fabs(a / a_expect - 1) < 2e-3);
    assert_true(fabs(v2[0] - w2[1] * arm) < 1e-4 * v0); /* still rolling, not sliding */
    dem_destroy(cl);
    dem_destroy(ref);
}

static dem_sim *rolling_pair(double delta, double w, dem_backend_kind be)
{
    dem_sim *s = dem_create();
    dem_material m = {RHO, YOUNG, NU, 1.0, 0.8, 0, 0, 0, MU_R};
    int id = dem_add_material(s, &m);
    dem_add_particle(s, (double[3]){-R + 0.5 * delta, 0, 0}, NULL, R, id);
    dem_add_particle(s, (double[3]){R - 0.5 * delta, 0, 0}, NULL, R, id);
    dem_set_domain(s, (double[3]){-0.02, -0.02, -0.02}, (double[3]){0.02, 0.02, 0.02});
    assert_int_equal(dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_FRICTION | DEM_EFFECT_ROLLING), 0);
    dem_set_dt(s, 1e-7);
    dem_config c = cfg_of(be, DEM_FP64);
    start_or_fail(s, &c);
    dem_state st;
    assert_int_equal(dem_state_get(s, &st), 0);
    double *ws = dem_state_find(&st, "w")->data;
    ws[1] = w, ws[4] = -w;
    assert_int_equal(dem_state_set(s, &st), 0);
    dem_state_free(&st);
    return s;
}

static void test_pair_torque(void **st)
{
    (void)st;
    double delta = 1e-5, w = 3.0, es = estar_same(), rs = R / 2, x[6];
    double t[2][6];
    for (int k = 0; k < 2; k++) { /* one step: its force pass sees the spins set (and the overlap it moved to) */
        dem_sim *s = rolling_pair(delta, w, k ? DEM_BACKEND_OPENCL : DEM_BACKEND_REFERENCE);
        step_or_fail(s, 1);
        assert_int_equal(dem_get_field(s, DEM_FIELD_TORQUE, t[k]), 0);
        assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
        dem_destroy(s);
    }
    double d = 2 * R - (x[3] - x[0]);
    double fn = 4.0 / 3.0 * es * sqrt(rs) * d * sqrt(d), want = MU_R * rs * fn;
    printf("  rolling pair: torques %.9g and %.9g N m about y (closed form -+%.9g), x %g z %g\n", t[0][1], t[0][4], want,
           t[0][0], t[0][2]);
    assert_memory_equal(t[0], t[1], sizeof t[0]);
    assert_true(fabs(t[0][1] + want) < 1e-12 * want && t[0][4] == -t[0][1]);
    assert_true(t[0][0] == 0 && t[0][2] == 0 && t[0][3] == 0 && t[0][5] == 0);
}

static void test_refused(void **st)
{
    (void)st;
    dem_sim *s = dem_create();
    assert_int_equal(dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_ROLLING), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "friction"));
    dem_material m = {RHO, YOUNG, NU, 1.0, 0.8, 0, 0, 0, -1};
    assert_int_equal(dem_add_material(s, &m), DEM_ERR_ARG);
    dem_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_sphere_on_plane), cmocka_unit_test(test_pair_torque),
                                       cmocka_unit_test(test_refused)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
