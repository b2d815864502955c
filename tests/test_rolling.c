/* test_rolling.c - rolling resistance of constant torque (common/rolling.h, DEM_EFFECT_ROLLING; Ai et al. 2011,
 * model A), against closed forms typed in here:
 *   - a sphere rolling without slip on a plane under gravity (friction ample) slows at
 *     a = mu_r g R arm / (2/5 R^2 + arm^2)   (arm = R - delta, the contact's lever; 5/7 mu_r g as delta -> 0),
 *     from m a = F_t and I dw/dt = -arm F_t - mu_r R m g with v = w arm; reference and PoCL, fp64, bit for bit;
 *   - two equal spheres pressed together and spinning oppositely about the same axis roll on each other without
 *     slip: after a step the torques are -+mu_r (R/2) F_n along the axis (F_n Hertz's at the overlap), equal and
 *     opposite, with no friction torque;
 *   - rolling without friction is refused (no spins without it).
 * And model C, the rolling spring (DEM_EFFECT_ROLLING_SPRING):
 *   - the pair above after one step: the spring's -k_r w dt and the dashpot's -eta_r 2 sqrt(I_r k_r) w, equal and
 *     opposite;
 *   - a sphere resting on a plane, given a small spin, rocks on its rolling spring with the period
 *     2 pi sqrt((I + m arm^2) / k_r), k_r = 2.25 (4/3 E* sqrt(R delta)) mu_r^2 R^2 (no dashpot; the amplitude below
 *     the cap mu_r R m g);
 *   - a rolling sphere slows as under model A (the spring at its cap is model A's torque), and once it stops the
 *     spring and its dashpot hold it still where model A rocks it about its rest;
 *   - a packing under a lid: reference and PoCL bit for bit, restored mid-run from dem_state, and with two skins
 *     (the springs carried across neighbour rebuilds), in fp64 and fp32. */
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

static dem_sim *rolling_sphere_with(double v0, double d0, unsigned extra, double eta_r)
{
    dem_sim *s = dem_create();
    dem_material m = {RHO, YOUNG, NU, 0.5, 0.8, 0, 0, 0, MU_R, 0, eta_r};
    int id = dem_add_material(s, &m);
    double arm = R - d0;
    dem_add_particle(s, (double[3]){0, 0, arm}, (double[3]){v0, 0, 0}, R, id);
    dem_wall floor = {.kind = DEM_WALL_PLANE, .material = id, .point = {0, 0, 0}, .normal = {0, 0, 1}};
    assert_true(dem_add_wall(s, &floor) >= 0);
    dem_set_gravity(s, (double[3]){0, 0, -G});
    dem_set_domain(s, (double[3]){-0.01, -0.02, -0.01}, (double[3]){0.1, 0.02, 0.02});
    assert_int_equal(dem_set_effects(s, DEM_EFFECT_CLASSICAL | DEM_EFFECT_ROLLING | extra), 0);
    dem_time_scales ts;
    dem_time_scales_get(s, 0, &ts);
    dem_set_dt(s, 0.2 * ts.rayleigh_time);
    return s;
}
static dem_sim *rolling_sphere(double v0, double d0) { return rolling_sphere_with(v0, d0, 0, 0); }

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

static dem_sim *rolling_pair_with(double delta, double w, dem_backend_kind be, unsigned extra, double eta_r)
{
    dem_sim *s = dem_create();
    dem_material m = {RHO, YOUNG, NU, 1.0, 0.8, 0, 0, 0, MU_R, 0, eta_r};
    int id = dem_add_material(s, &m);
    dem_add_particle(s, (double[3]){-R + 0.5 * delta, 0, 0}, NULL, R, id);
    dem_add_particle(s, (double[3]){R - 0.5 * delta, 0, 0}, NULL, R, id);
    dem_set_domain(s, (double[3]){-0.02, -0.02, -0.02}, (double[3]){0.02, 0.02, 0.02});
    assert_int_equal(dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_FRICTION | DEM_EFFECT_ROLLING | extra), 0);
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
static dem_sim *rolling_pair(double delta, double w, dem_backend_kind be)
{
    return rolling_pair_with(delta, w, be, 0, 0);
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

/* Model C on the same pair, spins small enough to stay below the cap: after one step the spring holds
 * -k_r (w_a - w_b) dt and the dashpot adds -eta_r 2 sqrt(I_r k_r) (w_a - w_b), with k_r = 2.25 (4/3 E* sqrt(r* delta))
 * mu_r^2 r*^2, r* = R/2, I_r = (I + m R^2)/2 = 0.7 m R^2; equal and opposite on the two spheres */
static void test_spring_pair_torque(void **st)
{
    (void)st;
    double delta = 1e-5, w = 1e-3, eta = 0.3, es = estar_same(), rs = R / 2, m = RHO * 4.0 / 3.0 * M_PI * R * R * R;
    double t[2][6], x[6];
    for (int k = 0; k < 2; k++) {
        dem_sim *s = rolling_pair_with(delta, w, k ? DEM_BACKEND_OPENCL : DEM_BACKEND_REFERENCE,
                                       DEM_EFFECT_ROLLING_SPRING, eta);
        step_or_fail(s, 1);
        assert_int_equal(dem_get_field(s, DEM_FIELD_TORQUE, t[k]), 0);
        assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
        dem_destroy(s);
    }
    double d = 2 * R - (x[3] - x[0]), dt = 1e-7, wr = 2 * w;
    double kr = 2.25 * (4.0 / 3.0 * es * sqrt(rs * d)) * MU_R * MU_R * rs * rs, ir = 0.7 * m * R * R;
    double want = -kr * wr * dt - eta * 2 * sqrt(ir * kr) * wr;
    double cap = MU_R * rs * 4.0 / 3.0 * es * sqrt(rs) * d * sqrt(d);
    printf("  rolling spring, pair: torque %.9g N m about y after a step (closed form %.9g; cap %.3g), the other "
           "%.9g\n", t[0][1], want, cap, t[0][4]);
    assert_true(fabs(kr * wr * dt) < 0.1 * cap); /* below the cap: the dashpot acts */
    assert_memory_equal(t[0], t[1], sizeof t[0]);
    assert_true(fabs(t[0][1] / want - 1) < 1e-9 && t[0][4] == -t[0][1]);
    assert_true(t[0][0] == 0 && t[0][2] == 0 && t[0][3] == 0 && t[0][5] == 0);
}

/* The spin about y of the one sphere (reference) */
static double spin_y(dem_sim *s)
{
    double w[3];
    assert_int_equal(dem_get_field(s, DEM_FIELD_W, w), 0);
    return w[1];
}

/* Model C: a resting sphere given a small spin rocks on its rolling spring (no dashpot) */
static void test_spring_rocking(void **st)
{
    (void)st;
    double m = RHO * 4.0 / 3.0 * M_PI * R * R * R, es = estar_same(), inertia = 0.4 * m * R * R;
    double d0 = pow(m * G / (4.0 / 3.0 * es * sqrt(R)), 2.0 / 3.0), arm = R - d0;
    double kr = 2.25 * (4.0 / 3.0 * es * sqrt(R * d0)) * MU_R * MU_R * R * R;
    double omega = sqrt(kr / (inertia + m * arm * arm)), period = 2 * M_PI / omega;
    double w0 = 0.3 * MU_R * R * m * G / kr * omega; /* the spring's largest torque: 0.3 of the cap */
    dem_sim *cl = rolling_sphere_with(0, d0, DEM_EFFECT_ROLLING_SPRING, 0), *ref = rolling_sphere_with(0, d0,
                                                                                   DEM_EFFECT_ROLLING_SPRING, 0);
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, DEM_FP64), rc = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    start_or_fail(cl, &c);
    start_or_fail(ref, &rc);
    for (int k = 0; k < 2; k++) { /* rolling without slip from the start: v = w0 arm */
        dem_sim *s = k ? ref : cl;
        dem_state sv;
        assert_int_equal(dem_state_get(s, &sv), 0);
        ((double *)dem_state_find(&sv, "v")->data)[0] = w0 * arm;
        ((double *)dem_state_find(&sv, "w")->data)[1] = w0;
        assert_int_equal(dem_state_set(s, &sv), 0);
        dem_state_free(&sv);
    }
    double dt = dem_dt(ref);
    long steps = lround(3.2 * period / dt);
    twins_step(cl, ref, 1, "rocking sphere, PoCL vs reference");
    /* the spin's sign changes, interpolated in time: successive ones half a period apart */
    double prev = spin_y(ref), first = -1, last = -1, peak = 0;
    int crossings = 0;
    for (long k = 2; k <= steps; k++) {
        step_or_fail(ref, 1);
        double w = spin_y(ref);
        peak = fmax(peak, fabs(w));
        if ((w < 0) != (prev < 0)) {
            double t = ((double)(k - 1) + prev / (prev - w)) * dt;
            if (first < 0)
                first = t;
            last = t, crossings++;
        }
        prev = w;
    }
    double measured = 2 * (last - first) / (crossings - 1);
    printf("  rolling spring: a resting sphere rocks with period %.6g s (closed form %.6g s, %d half periods), spin "
           "amplitude %.4g rad/s (given %.4g)\n", measured, period, crossings - 1, peak, w0);
    assert_true(crossings >= 5);
    assert_true(fabs(measured / period - 1) < 0.01);
    assert_true(peak > 0.95 * w0 && peak < 1.05 * w0); /* no dashpot, below the cap: it keeps its energy */
    step_or_fail(cl, steps - 1); /* PoCL to the same step: the reference's bits */
    twins_step(cl, ref, 0, "rocking sphere, PoCL vs reference");
    dem_destroy(cl);
    dem_destroy(ref);
}

/* Model A against model C on a sphere rolling to rest: the same deceleration while it rolls; then model A rocks it by
 * about mu_r R m g dt / I per step, and model C's spring, released at the stop, rings down with its dashpot (damping
 * ratio 0.3 of a period of 0.092 s: e^-20 in a second) */
static void test_spring_rest(void **st)
{
    (void)st;
    double m = RHO * 4.0 / 3.0 * M_PI * R * R * R, es = estar_same();
    double d0 = pow(m * G / (4.0 / 3.0 * es * sqrt(R)), 2.0 / 3.0), arm = R - d0, v0 = 0.1;
    double a_expect = MU_R * G * R * arm / (0.4 * R * R + arm * arm);
    double spin_end[2], decel[2];
    (void)m;
    for (int model = 0; model < 2; model++) {
        dem_sim *s = rolling_sphere_with(v0, d0, model ? DEM_EFFECT_ROLLING_SPRING : 0, 0.3);
        dem_config rc = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
        start_or_fail(s, &rc);
        set_spin(s, v0 / arm);
        double dt = dem_dt(s), v1[3], v2[3];
        long n1 = lround(0.02 / dt), n2 = lround(0.1 / dt), n3 = lround((v0 / a_expect + 1.0) / dt);
        step_or_fail(s, n1);
        assert_int_equal(dem_get_field(s, DEM_FIELD_V, v1), 0);
        step_or_fail(s, n2 - n1);
        assert_int_equal(dem_get_field(s, DEM_FIELD_V, v2), 0);
        decel[model] = -(v2[0] - v1[0]) / ((double)(n2 - n1) * dt);
        step_or_fail(s, n3 - n2);
        double worst = 0; /* the largest spin over the last 1000 steps, 1 s after the stop */
        for (int k = 0; k < 1000; k++) {
            step_or_fail(s, 1);
            worst = fmax(worst, fabs(spin_y(s)));
        }
        spin_end[model] = worst;
        dem_destroy(s);
    }
    printf("  rolling to rest: slows at %.6g (model A) and %.6g m/s^2 (spring; closed form %.6g); 1 s after the stop "
           "the spin is %.3g rad/s (model A) and %.3g rad/s (spring)\n", decel[0], decel[1], a_expect, spin_end[0],
           spin_end[1]);
    assert_true(fabs(decel[1] / a_expect - 1) < 2e-3);
    assert_true(spin_end[0] > 0);
    assert_true(spin_end[1] < 1e-3 * spin_end[0]);
}

/* A packing under a lid with rolling springs: PoCL = reference, restored mid-run, two skins (the springs carried
 * across rebuilds), stored anew at every rebuild */
static void test_spring_packing(void **st)
{
    (void)st;
    packing_opts o;
    packing_defaults(&o);
    o.side = 4;
    o.effects = DEM_EFFECT_CLASSICAL | DEM_EFFECT_ROLLING | DEM_EFFECT_ROLLING_SPRING;
    o.rolling_friction = 0.1, o.rolling_damping = 0.3;
    o.lid_speed = 0.5;
    FOR_EACH_BACKEND(bc) {
        dem_config c = cfg_of(bc->backend, bc->precision);
        dem_state sa;
        packing_restart_state(&o, &c, bc->name, &sa);
        long wound = 0;
        for (long p = 0; p < 3 * sa.npairs; p++)
            wound += (bc->precision == DEM_FP64 ? ((double *)sa.pair_rspring)[p] : ((float *)sa.pair_rspring)[p]) != 0;
        assert_true(sa.has_rspring && sa.npairs > 10 && wound > sa.npairs);
        dem_state_free(&sa);
        /* two skins, and stored anew: the springs move with their pairs and particles; OpenCL: the reference's bits */
        skins_order_and_reference_check(&o, &c, 600, bc->name);
    }
}

static void test_refused(void **st)
{
    (void)st;
    dem_sim *s = dem_create();
    assert_int_equal(dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_ROLLING), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "friction"));
    dem_material m = {RHO, YOUNG, NU, 1.0, 0.8, 0, 0, 0, -1};
    assert_int_equal(dem_add_material(s, &m), DEM_ERR_ARG);
    assert_int_equal(dem_set_effects(s, DEM_EFFECT_CLASSICAL | DEM_EFFECT_ROLLING_SPRING), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "rolling"));
    dem_material md = {RHO, YOUNG, NU, 1.0, 0.8, 0, 0, 0, 0.1, 0, -0.5};
    assert_int_equal(dem_add_material(s, &md), DEM_ERR_ARG);
    dem_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_sphere_on_plane), cmocka_unit_test(test_pair_torque),
                                       cmocka_unit_test(test_spring_pair_torque), cmocka_unit_test(test_spring_rocking),
                                       cmocka_unit_test(test_spring_rest),
                                       cmocka_unit_test(test_spring_packing),  cmocka_unit_test(test_refused)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
