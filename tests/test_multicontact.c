/* test_multicontact.c - stress trace, MC-stress and MC-strain kernels.
 * Reference and PoCL bitwise identical for every model in fp32 and fp64 (stress tensor, traces and stored MC-strain
 * forces included), and every MC-stress pressure convention; zero prefactors reproduce classical DEM bit for bit;
 * two spheres are exactly classical under MC-strain and the own-term-out MC-stress readings (not under the default,
 * asserted too); the stress tensor agrees with its closed form; the iterated MC-strain scheme converges and reports
 * its iterations; MC-strain's contact distance makes gap contacts, bitwise and skin-independent. The physics checks
 * against seed 000 live in test_mc_validation.c. */
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define STEPS 200
static const unsigned CLASSIC = DEM_EFFECT_CLASSICAL;

static packing_opts dense(unsigned mc, double beta, double gamma, int iters)
{
    packing_opts o;
    packing_defaults(&o);
    o.side = 6;          /* 216 + 125 = 341 spheres */
    o.lid_speed = 2.0;   /* a fast lid: many multi-contact particles within STEPS */
    o.speed = 0.3;
    o.effects = CLASSIC | mc;
    o.mc_beta = beta;
    o.mc_gamma = gamma;
    o.mc_iterations = iters;
    return o;
}

/* A run of `steps` on the reference, fp64. */
static dem_sim *run_ref(const packing_opts *o, long steps)
{
    dem_sim *s = packing_build(o);
    dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    start_or_fail(s, &c);
    step_or_fail(s, steps);
    return s;
}

static void lockstep(const packing_opts *o, dem_precision prec, long steps)
{
    dem_config rc = cfg_of(DEM_BACKEND_REFERENCE, prec), c = cfg_of(DEM_BACKEND_OPENCL, prec);
    dem_sim *ref, *cl;
    packing_pair(o, &rc, &c, 0, &ref, &cl);
    char msg[512];
    for (long step = 0; step < steps; step++) {
        step_or_fail(ref, 1);
        step_or_fail(cl, 1);
        if (step % 10 == 9 || step == steps - 1) /* every 10th step: the stress tensor is computed when read */
            if (state_diff(ref, cl, msg, sizeof msg))
                fail_msg("effects 0x%x, %s, step %ld: %s", o->effects, prec == DEM_FP64 ? "fp64" : "fp32", step + 1,
                         msg);
    }
    dem_mc_stats a, b;
    dem_mc_stats_get(ref, &a);
    dem_mc_stats_get(cl, &b);
    assert_int_equal(a.total, b.total); /* the same iterations on both */
    if (o->mc_iterations)
        assert_true(a.max >= 2); /* the fixed point is really iterated */
    dem_destroy(ref);
    dem_destroy(cl);
}

static void test_models_bitwise(void **st)
{
    (void)st;
    packing_opts models[] = {dense(DEM_EFFECT_MC_STRESS, 1.65, 0, 0), dense(DEM_EFFECT_MC_STRAIN, 0, 1.12, 0),
                             dense(DEM_EFFECT_MC_STRAIN, 0, 1.12, 8)};
    for (size_t k = 0; k < sizeof models / sizeof models[0]; k++) {
        lockstep(&models[k], DEM_FP64, STEPS);
        lockstep(&models[k], DEM_FP32, STEPS);
    }
}

/* Pairs in the row that touch (touch flag) while their spheres do not overlap: contacts made by MC-strain's reach. */
static int gap_contacts(dem_sim *s)
{
    int n = dem_count(s);
    size_t bl = dem_field_bytes(s, DEM_FIELD_NBR_LIST), bt = dem_field_bytes(s, DEM_FIELD_TOUCH);
    int found = 0;
    double *x = malloc(sizeof(double) * 3 * (size_t)n);
    int *cnt = malloc(sizeof(int) * (size_t)n), *list = malloc(bl), *start = malloc(sizeof(int) * ((size_t)n + 1));
    unsigned char *touch = malloc(bt);
    assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
    assert_int_equal(dem_get_raw(s, DEM_FIELD_NBR_COUNT, cnt, sizeof(int) * (size_t)n), 0);
    assert_int_equal(dem_get_raw(s, DEM_FIELD_NBR_LIST, list, bl), 0);
    assert_int_equal(dem_get_raw(s, DEM_FIELD_NBR_START, start, sizeof(int) * ((size_t)n + 1)), 0);
    assert_int_equal(dem_get_raw(s, DEM_FIELD_TOUCH, touch, bt), 0);
    size_t p = 0; /* touching flags are kept per pair: the owned slots (partner above) in row order */
    for (int i = 0; i < n; i++)
        for (int k = 0; k < cnt[i]; k++) {
            int j = list[start[i] + k];
            if (j < i)
                continue;
            double d2 = 0;
            for (int q = 0; q < 3; q++)
                d2 += (x[3 * i + q] - x[3 * j + q]) * (x[3 * i + q] - x[3 * j + q]);
            double rs = dem_particle_radius(s, i) + dem_particle_radius(s, j);
            assert_true(p < bt);
            found += touch[p++] && d2 >= rs * rs;
        }
    free(x), free(cnt), free(list), free(start), free(touch);
    return found;
}

/* MC-strain's contact distance (LIGGGHTS' option): neighbours within F (r_i + r_j) bear a force once the induced
 * displacements close their gap. Bitwise on PoCL (fp64 and fp32, lagged and iterated), independent of the skin (the
 * rows reach further, the trigger does not move), it really makes gap contacts, and it changes the physics. */
static void test_mc_reach(void **st)
{
    (void)st;
    packing_opts lag = dense(DEM_EFFECT_MC_STRAIN, 0, 1.12, 0), it = dense(DEM_EFFECT_MC_STRAIN, 0, 1.12, 8);
    lag.mc_reach = it.mc_reach = 1.05;
    lockstep(&lag, DEM_FP64, STEPS);
    lockstep(&lag, DEM_FP32, STEPS);
    lockstep(&it, DEM_FP64, STEPS / 2);
    /* skin independence, with the reach off and on: the per-particle state (state_hash: x, v, w, force, torque, wall
     * forces) must agree bit for bit; per-slot arrays are laid out by the rows and are not comparable across skins */
    for (int on = 0; on < 2; on++) {
        packing_opts o2 = lag;
        o2.mc_reach = on ? 1.05 : 1;
        dem_sim *p = run_ref(&o2, STEPS), *q = packing_build(&o2);
        dem_config c0 = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
        c0.skin = 4e-4; /* the default: at most 0.3 x the smallest radius = 1.35e-4 m */
        start_or_fail(q, &c0);
        step_or_fail(q, STEPS);
        if (state_hash(p) != state_hash(q))
            fail_msg("reach %g: skin 4e-4 m and the default skin give different states", o2.mc_reach);
        dem_destroy(p), dem_destroy(q);
    }
    dem_sim *a = run_ref(&lag, STEPS);
    assert_true(gap_contacts(a) > 0);
    char msg[512];
    packing_opts off = lag;
    off.mc_reach = 1;
    dem_sim *o = run_ref(&off, STEPS);
    assert_int_equal(gap_contacts(o), 0);
    assert_true(state_diff(a, o, msg, sizeof msg) != 0);
    assert_int_equal(dem_set_mc_strain_reach(o, 1.5), DEM_ERR_STATE); /* started: the set-up is fixed */
    dem_sim *t = dem_create();
    assert_int_equal(dem_set_mc_strain_reach(t, 0.99), DEM_ERR_ARG);
    assert_int_equal(dem_set_mc_strain_reach(t, 2.01), DEM_ERR_ARG);
    assert_int_equal(dem_set_mc_strain_reach(t, NAN), DEM_ERR_ARG);
    dem_destroy(t), dem_destroy(a), dem_destroy(o);
}

/* Every MC-stress pressure convention is its own compiled branch: each one bitwise on PoCL against its reference
 * twin in fp64, and in fp32 three that between them take every branch (own term out, contact-point lever, text and
 * mean-pressure scales; the default is covered by test_models_bitwise in both). Each convention is a program build
 * of its own, a few seconds on PoCL, hence not all twelve twice. And each one is a different force law. */
static void test_conventions_bitwise(void **st)
{
    (void)st;
    char name[96];
    uint64_t hash[MCS_CONVENTIONS];
    for (int k = 0; k < MCS_CONVENTIONS; k++) {
        packing_opts o = dense(DEM_EFFECT_MC_STRESS, 1.65, 0, 0);
        o.mcs_conv = mcs_convention(k);
        print_message("# convention %d: %s\n", k, mcs_convention_name(o.mcs_conv, name, sizeof name));
        if (k > 0)
            lockstep(&o, DEM_FP64, STEPS / 2);
        if (k == 4 || k == 7 || k == 11) /* in/contact/text, out/centres/text, out/contact/mean_pressure */
            lockstep(&o, DEM_FP32, STEPS / 2);
        dem_sim *s = run_ref(&o, STEPS / 2);
        hash[k] = state_hash(s);
        for (int q = 0; q < k; q++)
            if (hash[q] == hash[k])
                fail_msg("conventions %d and %d give the same state (%s)", q, k, name);
        dem_destroy(s);
    }
}


static void test_zero_prefactor_is_classical(void **st)
{
    (void)st;
    packing_opts cl = dense(0, 0, 0, 0);
    dem_sim *base = run_ref(&cl, STEPS);
    char msg[512];
    packing_opts zero[] = {dense(DEM_EFFECT_MC_STRESS, 0, 0, 0), dense(DEM_EFFECT_MC_STRAIN, 0, 0, 0),
                           dense(DEM_EFFECT_MC_STRAIN, 0, 0, 5), dense(DEM_EFFECT_MC_STRESS, 1.65, 0, 0)};
    zero[3].poisson = 0; /* nu = 0 switches MC-stress off (seed 000: "nu = 0 de-activates the model") */
    for (size_t k = 0; k < sizeof zero / sizeof zero[0]; k++) {
        dem_sim *s = run_ref(&zero[k], STEPS);
        dem_sim *b = base;
        if (k == 3) { /* nu = 0 changes E* itself: compare with classical at nu = 0 */
            packing_opts c0 = cl;
            c0.poisson = 0;
            b = run_ref(&c0, STEPS);
        }
        if (state_diff(b, s, msg, sizeof msg))
            fail_msg("case %zu (effects 0x%x, beta %g, gamma %g, nu %g): %s", k, zero[k].effects, zero[k].mc_beta,
                     zero[k].mc_gamma, zero[k].poisson, msg);
        if (b != base)
            dem_destroy(b);
        dem_destroy(s);
    }
    /* and non-zero prefactors do change the physics */
    packing_opts on[] = {dense(DEM_EFFECT_MC_STRESS, 1.65, 0, 0), dense(DEM_EFFECT_MC_STRAIN, 0, 1.12, 0)};
    for (size_t k = 0; k < 2; k++) {
        dem_sim *s = run_ref(&on[k], STEPS);
        assert_true(state_diff(base, s, msg, sizeof msg) != 0);
        dem_destroy(s);
    }
    dem_destroy(base);
}

/* Two hydrogel spheres at 10 m/s (seed 000 section 3.4: "multi-contact models do not show any difference with the
 * classical DEM in case of two sphere interactions"). MC-strain is exactly classical (one contact induces nothing),
 * and so is MC-stress under every convention that leaves the contact's own term out (tr - t = 0 exactly). With the
 * own term in (the default, under which Eq. 11 holds) a lone contact stiffens itself: the paper cannot have both,
 * docs/multicontact.md quotes the two passages. That difference is asserted too. */
static void test_two_spheres_identical(void **st)
{
    (void)st;
    dem_material gel = {11.5, 23.3e3, 0.5, 0.95, 0.03, 1.65, 1.12};
    const unsigned base = CLASSIC & ~(unsigned)DEM_EFFECT_WALLS;
    enum { NS = 2 + 6 + 1 + 1 }; /* classical, MC-strain lagged and iterated, MC-stress own-out x 6, default */
    dem_sim *s[NS];
    for (int k = 0; k < NS; k++) {
        s[k] = pair_build(&gel, 0.01, 0.01, 20, 0.002);
        unsigned fx = base | (k == 0 ? 0u : k <= 2 ? (unsigned)DEM_EFFECT_MC_STRAIN : (unsigned)DEM_EFFECT_MC_STRESS);
        assert_int_equal(dem_set_effects(s[k], fx), 0);
        if (k == 2)
            assert_int_equal(dem_set_mc_strain(s[k], 10, 1e-9), 0);
        if (k >= 3 && k < NS - 1) /* conventions 6..11: the contact's own term left out */
            assert_int_equal(dem_set_mc_stress_convention(s[k], mcs_convention(k - 3 + 6)), 0);
        dem_config c = cfg_of(DEM_BACKEND_OPENCL, DEM_FP64);
        start_or_fail(s[k], &c);
    }
    char msg[512], name[96];
    double dmin = 1, dmin_own = 1;
    int differs = 0;
    /* every step: a force one ulp off for a step can vanish in the velocity's rounding, so only the step's own
     * state shows it (classical's state read once for the eight it is compared with) */
    for (int step = 0; step < 800; step++) {
        for (int k = 0; k < NS; k++)
            step_or_fail(s[k], 1);
        int k = state_diff_each(s[0], s + 1, NS - 2, msg, sizeof msg) + 1; /* 0: all equal */
        if (k > 0)
            fail_msg("model %d (%s) differs from classical at step %d: %s", k,
                     k >= 3 ? mcs_convention_name(mcs_convention(k - 3 + 6), name, sizeof name) : "MC-strain",
                     step + 1, msg);
        differs |= state_diff(s[0], s[NS - 1], msg, sizeof msg) != 0;
        dmin = fmin(dmin, pair_distance(s[0]));
        dmin_own = fmin(dmin_own, pair_distance(s[NS - 1]));
    }
    assert_true(dmin < 0.02 - 1e-3); /* they really collided (overlap above 1 mm) */
    assert_true(differs);
    assert_true(dmin_own > dmin); /* own term in: the lone contact is stiffer, the overlap smaller */
    print_message("# two spheres: largest overlap %.4f mm classical, %.4f mm MC-stress with the own term in\n",
                  1e3 * (0.02 - dmin), 1e3 * (0.02 - dmin_own));
    for (int k = 0; k < NS; k++)
        dem_destroy(s[k]);
}

/* One sphere squeezed between two plates: sigma = -(1/V) sum (r - d) f_H n n, so sigma_zz = -2 (r - d) f_H / V,
 * the other components zero, whatever the MC-stress convention (the tensor is Eq. 9's, contact-point lever). The
 * online trace is the convention's: the default's lever to the mirror centre doubles it, and the plate force is
 * f_H + beta nu pi r d P with P = -(T + T)/2 = the whole trace (own term in); the shipped-before reading (own term
 * out, contact point, 1/6) sees only the other plate's term, a third of it. */
static void test_stress_tensor_closed_form(void **st)
{
    (void)st;
    for (int conv = 0; conv < 2; conv++) {
        dem_sim *s = dem_create();
        dem_material rub = {2000, 1.85e6, 0.46, 0.7, 0.5, 1.71, 0.55};
        int m = dem_add_material(s, &rub);
        double r = 0.01, d = 0.001;
        dem_add_particle(s, (double[3]){0, 0, 0}, NULL, r, m);
        dem_add_wall(s, &(dem_wall){DEM_WALL_PLANE, m, {0, 0, -(r - d)}, {0, 0, 1}, 0, 0, {{0}}});
        dem_add_wall(s, &(dem_wall){DEM_WALL_PLANE, m, {0, 0, r - d}, {0, 0, -1}, 0, 0, {{0}}});
        dem_set_domain(s, (double[3]){-0.05, -0.05, -0.05}, (double[3]){0.05, 0.05, 0.05});
        dem_set_dt(s, 1e-6);
        dem_set_effects(s, CLASSIC | DEM_EFFECT_MC_STRESS);
        assert_int_equal(dem_set_mc_stress_convention(s, conv ? DEM_MCS_APPENDIX_OWN_OUT : DEM_MCS_DEFAULT), 0);
        dem_config c = cfg_of(DEM_BACKEND_OPENCL, DEM_FP64);
        start_or_fail(s, &c);
        double sig[6], tr[1];
        assert_int_equal(dem_get_field(s, DEM_FIELD_STRESS, sig), 0);
        assert_int_equal(dem_get_field(s, DEM_FIELD_STRESS_TRACE, tr), 0);
        double es = 1 / (2 * (1 - 0.46 * 0.46) / 1.85e6), fh = 4.0 / 3.0 * es * sqrt(r * d) * d;
        double V = 4.0 / 3.0 * M_PI * r * r * r, want = -2 * (r - d) * fh / V;
        assert_true(fabs(sig[2] - want) <= 1e-12 * fabs(want));
        for (int k = 0; k < 6; k++)
            if (k != 2)
                assert_true(fabs(sig[k]) <= 1e-12 * fabs(want));
        double want_tr = conv ? want : 2 * want;
        assert_true(fabs(tr[0] - want_tr) <= 1e-12 * fabs(want_tr));
        double f[3];
        assert_int_equal(dem_wall_force(s, 0, f), 0);
        double p = conv ? (r - d) * fh / V / 3 : -want_tr; /* the pressure each plate contact sees */
        double extra = 1.71 * 0.46 * M_PI * r * d * p;
        assert_true(fabs(-f[2] - (fh + extra)) <= 1e-9 * fh);
        dem_destroy(s);
    }
}

/* The iterated scheme stops at the tolerance; a tight cap is reported as unconverged steps. */
static void test_iteration_reporting(void **st)
{
    (void)st;
    packing_opts o = dense(DEM_EFFECT_MC_STRAIN, 0, 1.12, 50);
    dem_sim *s = run_ref(&o, STEPS);
    dem_mc_stats a;
    dem_mc_stats_get(s, &a);
    assert_true(a.total >= STEPS); /* at least one iteration per step */
    assert_true(a.max >= 2 && a.max < 50);
    assert_int_equal(a.unconverged, 0);
    assert_true(a.first_capped == -1 && a.last_capped == -1);
    dem_destroy(s);
    o.mc_iterations = 1;
    s = run_ref(&o, STEPS);
    dem_mc_stats_get(s, &a);
    assert_int_equal(a.max, 1);
    /* steps, not force evaluations: dem_start's forces are none of them (else: "6001 of 6000 steps") */
    assert_true(a.unconverged > 0 && a.unconverged <= STEPS);
    assert_true(a.first_capped >= 1 && a.first_capped <= a.last_capped && a.last_capped <= STEPS);
    assert_true(a.last_capped - a.first_capped + 1 >= a.unconverged);
    dem_destroy(s);
    o.mc_iterations = 0; /* lagged: no iteration at all */
    s = run_ref(&o, STEPS);
    dem_mc_stats_get(s, &a);
    assert_int_equal(a.total, 0);
    dem_destroy(s);
}

static void test_mask_validation(void **st)
{
    (void)st;
    dem_sim *s = dem_create();
    assert_int_equal(dem_set_effects(s, CLASSIC | DEM_EFFECT_MC_STRESS | DEM_EFFECT_MC_STRAIN), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "choose one"));
    assert_int_equal(dem_set_mc_strain(s, -1, 1e-6), DEM_ERR_ARG);
    assert_int_equal(dem_set_mc_strain(s, 5, 0), DEM_ERR_ARG);
    dem_material bad = {1000, 1e6, 0.3, 0.5, 0.1, -1, 0};
    assert_int_equal(dem_add_material(s, &bad), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "beta and gamma"));
    assert_int_equal(dem_effect_bit("mc_stress"), 5);
    assert_int_equal(dem_effect_bit("mc_strain"), 6);
    dem_destroy(s);
}

int main(void)
{
    test_pocl_threads(); /* the suite's multi-thread runs of these laws (test_util.h) */
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mask_validation),
        cmocka_unit_test(test_stress_tensor_closed_form),
        cmocka_unit_test(test_two_spheres_identical),
        cmocka_unit_test(test_zero_prefactor_is_classical),
        cmocka_unit_test(test_iteration_reporting),
        cmocka_unit_test(test_models_bitwise),
        cmocka_unit_test(test_conventions_bitwise),
        cmocka_unit_test(test_mc_reach),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
