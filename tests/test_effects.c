/* test_effects.c - effects on demand.
 * An effect that is off allocates nothing, launches nothing and is compiled out of the kernels; the reference and
 * PoCL stay bitwise identical for every effect mask; an effect on at zero strength (mu = 0, e = 1, g = 0) gives the
 * same trajectories as leaving it out. */
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define STEPS 300

static packing_opts small(unsigned effects)
{
    packing_opts o;
    packing_defaults(&o);
    o.side = 6; /* 216 + 125 = 341 spheres */
    o.speed = 0.3;
    o.effects = effects;
    return o;
}

static void lockstep_mask(unsigned effects, dem_precision prec)
{
    packing_opts o = small(effects);
    dem_config rc = cfg_of(DEM_BACKEND_REFERENCE, prec), c = cfg_of(DEM_BACKEND_OPENCL, prec);
    dem_sim *ref, *cl;
    packing_pair(&o, &rc, &c, 0, &ref, &cl);
    char msg[512];
    for (int step = 0; step < STEPS; step++) {
        step_or_fail(ref, 1);
        step_or_fail(cl, 1);
        if (state_diff(ref, cl, msg, sizeof msg))
            fail_msg("effects 0x%x, %s, step %d: %s", effects, prec == DEM_FP64 ? "fp64" : "fp32", step + 1, msg);
    }
    dem_energy_t e;
    assert_int_equal(dem_energy(ref, &e), 0);
    assert_true(e.contacts > 0); /* the packing really collides */
    dem_destroy(ref);
    dem_destroy(cl);
}

static void test_every_mask_bitwise(void **st)
{
    (void)st;
    const unsigned H = DEM_EFFECT_HERTZ, D = DEM_EFFECT_DAMPING, F = DEM_EFFECT_FRICTION, G = DEM_EFFECT_GRAVITY,
                   W = DEM_EFFECT_WALLS;
    unsigned masks[] = {H | W, H | D | W, H | F | W, H | D | G | W, H | D | F | G | W};
    for (size_t k = 0; k < sizeof masks / sizeof masks[0]; k++) {
        lockstep_mask(masks[k], DEM_FP64);
        lockstep_mask(masks[k], DEM_FP32);
    }
}

/* Without friction there is no tangential history at all, torques stay zero and spins stay as set. */
static void test_frictionless_allocates_no_history(void **st)
{
    (void)st;
    packing_opts o = small(DEM_EFFECT_CLASSICAL & ~(unsigned)DEM_EFFECT_FRICTION);
    dem_sim *s = packing_build(&o);
    dem_set_particle_omega(s, 3, (double[3]){0, 50, 0});
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, DEM_FP64);
    start_or_fail(s, &c);
    step_or_fail(s, STEPS);
    assert_int_equal(dem_field_bytes(s, DEM_FIELD_HIST), 0);
    assert_int_equal(dem_field_bytes(s, DEM_FIELD_WALL_HIST), 0);
    assert_true(dem_field_bytes(s, DEM_FIELD_TOUCH) > 0); /* the touching flags remain: pass 2 needs them */
    assert_non_null(strstr(dem_describe(s), "effects hertz+damping+gravity+walls"));
    int n = dem_count(s);
    double *t = malloc(sizeof(double) * 3 * n), *w = malloc(sizeof(double) * 3 * n);
    assert_int_equal(dem_get_field(s, DEM_FIELD_TORQUE, t), 0);
    assert_int_equal(dem_get_field(s, DEM_FIELD_W, w), 0);
    for (int k = 0; k < 3 * n; k++) {
        assert_true(t[k] == 0);
        assert_true(w[k] == (k == 3 * 3 + 1 ? 50 : 0));
    }
    free(t);
    free(w);
    dem_destroy(s);
}

/* Same trajectories: an effect on with zero strength, and the effect off. Compared by value (==), since only the
 * sign of a zero may differ (x + (+0) against x + (-0)). */
static void same_physics(packing_opts on, unsigned off_effects)
{
    packing_opts off = on;
    off.effects = off_effects;
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, DEM_FP64);
    dem_sim *a = packing_build(&on), *b = packing_build(&off);
    start_or_fail(a, &c);
    start_or_fail(b, &c);
    step_or_fail(a, STEPS);
    step_or_fail(b, STEPS);
    int n = dem_count(a);
    double *xa = malloc(sizeof(double) * 6 * n), *xb = malloc(sizeof(double) * 6 * n);
    assert_int_equal(dem_get_field(a, DEM_FIELD_X, xa), 0);
    assert_int_equal(dem_get_field(a, DEM_FIELD_V, xa + 3 * n), 0);
    assert_int_equal(dem_get_field(b, DEM_FIELD_X, xb), 0);
    assert_int_equal(dem_get_field(b, DEM_FIELD_V, xb + 3 * n), 0);
    double moved = 0;
    for (int k = 0; k < 6 * n; k++) {
        if (xa[k] != xb[k])
            fail_msg("effects 0x%x vs 0x%x: component %d differs: %.17g vs %.17g", on.effects, off_effects, k, xa[k],
                     xb[k]);
        if (k >= 3 * n && fabs(xa[k]) > moved)
            moved = fabs(xa[k]);
    }
    assert_true(moved > 0.01); /* not a frozen system */
    dem_energy_t e;
    dem_energy(a, &e);
    assert_true(e.contacts > 0);
    free(xa);
    free(xb);
    dem_destroy(a);
    dem_destroy(b);
}

static void test_zero_strength_equals_off(void **st)
{
    (void)st;
    packing_opts o = small(DEM_EFFECT_CLASSICAL);
    o.friction = 0;
    same_physics(o, DEM_EFFECT_CLASSICAL & ~(unsigned)DEM_EFFECT_FRICTION);
    o = small(DEM_EFFECT_CLASSICAL);
    o.restitution = 1;
    same_physics(o, DEM_EFFECT_CLASSICAL & ~(unsigned)DEM_EFFECT_DAMPING);
    o = small(DEM_EFFECT_CLASSICAL);
    o.gravity = 0;
    same_physics(o, DEM_EFFECT_CLASSICAL & ~(unsigned)DEM_EFFECT_GRAVITY);
}

/* And the converse: a real effect changes the result (so the comparison above could fail). */
static void test_effect_matters(void **st)
{
    (void)st;
    packing_opts o = small(DEM_EFFECT_CLASSICAL);
    packing_opts off = small(DEM_EFFECT_CLASSICAL & ~(unsigned)DEM_EFFECT_FRICTION);
    dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    dem_sim *a = packing_build(&o), *b = packing_build(&off);
    start_or_fail(a, &c);
    start_or_fail(b, &c);
    step_or_fail(a, STEPS);
    step_or_fail(b, STEPS);
    char msg[256];
    assert_int_not_equal(state_diff(a, b, msg, sizeof msg), 0);
    dem_destroy(a);
    dem_destroy(b);
}

static void test_mask_validation(void **st)
{
    (void)st;
    packing_opts o = small(DEM_EFFECT_HERTZ); /* walls defined but the effect is off */
    dem_sim *s = packing_build(&o);
    dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    assert_int_equal(dem_start(s, &c), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "'walls' is off"));
    dem_destroy(s);
    s = dem_create();
    assert_int_equal(dem_set_effects(s, DEM_EFFECT_DAMPING), DEM_ERR_ARG);
    assert_int_equal(dem_set_effects(s, 1u << 20), DEM_ERR_ARG);
    assert_int_equal(dem_effect_bit("friction"), 2);
    assert_int_equal(dem_effect_bit("viscosity"), DEM_ERR_ARG);
    assert_string_equal(dem_effect_name(4), "walls");
    dem_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_mask_bitwise),      cmocka_unit_test(test_frictionless_allocates_no_history),
        cmocka_unit_test(test_zero_strength_equals_off), cmocka_unit_test(test_effect_matters),
        cmocka_unit_test(test_mask_validation),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
