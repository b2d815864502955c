/* test_one_pass.c - the particle contacts in one pass (dem_config.one_pass, common/contact_rows.h) give the bits of
 * the two passes (contact_pairs, then contact_forces). Each particle evaluates its row's pairs itself, in the
 * canonical orientation, so both ends of a pair must compute the same force from the same inputs, and the tangential
 * history and touching flags must go from one copy to the other without either end reading what the other wrote.
 *
 * A packing of 189 polydisperse spheres thrown about in a box whose lid comes down (gravity, damping, contacts
 * starting and ending, neighbour rebuilds) runs 300 steps in calls of 100, twice - in one pass and in two - on the
 * reference and on PoCL, in fp64 and fp32; after each call the states (positions, velocities, spins, forces,
 * torques, wall forces, every touching pair's history) are bitwise equal, and the one-pass runs of the two backends
 * are equal too. The kernel's time shows that it ran (the reference always times its kernels; PoCL does with
 * DEM_PROFILE, set here) and that the two-pass run never launched it. Cases: the classical law with friction and
 * rolling resistance of constant torque, the particles stored anew at every rebuild (the rows' storage split is not
 * their id split: contact_forces' other way of finding a pair); MC-stress with the lid held by a servo (the walls'
 * sums every step, from the forces contact_rows keeps); no friction (no history, no torque).
 * The frictionless case is stepped by dem_step_sampled with every seventh step sampled and the wall forces kept
 * (dem_config.contacts), its rows compared too. Every case asserts neighbour rebuilds (the flags' and histories'
 * copies carried by pair_index across them). A law that keeps a state per pair (MDR, MC-strain, Thornton-Ning with
 * and without adhesion, the rolling spring) keeps the two passes when one pass is asked for: the kernel never runs
 * (and for MDR the bits are the two passes'). A one-pass run restored from a two-pass run's state mid-run goes on
 * with its bits; DEM_ONE_PASS=1 in the environment, and nothing else, sets dem_config.one_pass. */
#include "test_util.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* the seconds contact_rows has taken in s */
static double rows_seconds(dem_sim *s)
{
    const char **names;
    const double *sec;
    int count;
    assert_int_equal(dem_kernel_times(s, &names, &sec, &count), 0);
    for (int k = 0; k < count; k++)
        if (!strcmp(names[k], "contact_rows"))
            return sec[k];
    fail_msg("no kernel contact_rows among the %d timed", count);
    return 0;
}

/* the packing, its lid held by a servo (servo: the walls' sums every step, from the wall forces kept) or moving as
 * packing_build moves it */
static dem_sim *build(const packing_opts *o, int servo)
{
    dem_sim *s = packing_build(o);
    dem_stage press = {.duration = 1, .force = 0.05, .gain = 0.5, .max_speed = 0.05};
    if (servo && dem_set_wall_motion(s, 5, 1, &press))
        fail_msg("servo: %s", dem_error(s));
    return s;
}

/* a and b stepped n in one dem_step_sampled call each, every seventh step sampled on the device (its forces from the
 * two passes, the others' from one in a one-pass run): the states and every row bitwise equal */
static void sampled_twins(dem_sim *a, dem_sim *b, long n, const char *what)
{
    unsigned char want[100];
    dem_sample ra[100], rb[100];
    for (long k = 0; k < n; k++)
        want[k] = k % 7 == 3;
    if (dem_step_sampled(a, n, want, ra) || dem_step_sampled(b, n, want, rb))
        fail_msg("%s: %s", what, dem_error(a)[0] ? dem_error(a) : dem_error(b));
    for (long k = 0, r = 0; k < n; k++) {
        if (!want[k])
            continue;
        const dem_energy_t *x = &ra[r].energy, *y = &rb[r].energy;
        if (memcmp(&x->kinetic, &y->kinetic, sizeof(double)) || memcmp(&x->elastic, &y->elastic, sizeof(double)) ||
            memcmp(&x->potential, &y->potential, sizeof(double)) || x->contacts != y->contacts ||
            x->wall_contacts != y->wall_contacts || memcmp(ra[r].wall_force, rb[r].wall_force, sizeof ra[r].wall_force))
            fail_msg("%s: the row of step %ld differs (elastic %.17g against %.17g)", what, ra[r].step, x->elastic,
                     y->elastic);
        r++;
    }
    char msg[512];
    if (state_diff(a, b, msg, sizeof msg))
        fail_msg("%s: %s", what, msg);
}

/* o on every backend and precision, one pass against two; rows: whether the one-pass run must launch contact_rows;
 * anew: the particles stored anew at every rebuild where their order changes (dem_config.reorder, reorder_gain 1);
 * sampled: stepped by dem_step_sampled (sampled_twins) in a run that keeps its wall forces (dem_config.contacts),
 * else by dem_step */
static void one_against_two(const packing_opts *o, int rows, int anew, int servo, int sampled, const char *what)
{
    dem_sim *one[BACKEND_CASES] = {0};
    int k = 0;
    FOR_EACH_BACKEND(bc) {
        dem_config c = cfg_of(bc->backend, bc->precision), c1;
        if (anew)
            c.reorder = 1, c.reorder_gain = 1;
        if (sampled)
            c.contacts = 1;
        c1 = c;
        c.one_pass = 0;
        c1.one_pass = 1;
        dem_sim *two = build(o, servo), *s = build(o, servo);
        start_or_fail(two, &c);
        start_or_fail(s, &c1);
        char label[160];
        for (int call = 0; call < 3; call++) {
            snprintf(label, sizeof label, "%s, %s, one pass against two, call %d", what, bc->name, call + 1);
            if (sampled)
                sampled_twins(two, s, 100, label);
            else
                twins_step(two, s, 100, label);
        }
        if (dem_rebuild_count(s) < 3)
            fail_msg("%s, %s: %ld neighbour rebuilds (the history's copies carried across none)", what, bc->name,
                     dem_rebuild_count(s));
        double t1 = rows_seconds(s), t2 = rows_seconds(two);
        if (rows && !(t1 > 0))
            fail_msg("%s, %s: contact_rows never ran in the one-pass run", what, bc->name);
        if (!rows && t1 != 0)
            fail_msg("%s, %s: contact_rows ran (%g s) for a law that keeps the two passes", what, bc->name, t1);
        if (anew && dem_reorder_count(s) < 2)
            fail_msg("%s, %s: stored anew %ld times, not at the rebuilds", what, bc->name, dem_reorder_count(s));
        if (t2 != 0)
            fail_msg("%s, %s: contact_rows ran (%g s) in the two-pass run", what, bc->name, t2);
        dem_destroy(two);
        one[k++] = s;
    }
    /* the one-pass runs of both backends, each precision: OpenCL's against the reference's */
    char msg[512];
    for (int a = 0; a < BACKEND_CASES; a++)
        for (int b = a + 1; b < BACKEND_CASES; b++)
            if (backend_cases[a].precision == backend_cases[b].precision && state_diff(one[a], one[b], msg, sizeof msg))
                fail_msg("%s, one pass: %s against %s: %s", what, backend_cases[a].name, backend_cases[b].name, msg);
    for (int a = 0; a < BACKEND_CASES; a++)
        dem_destroy(one[a]);
}

static void base(packing_opts *o)
{
    packing_defaults(o);
    o->side = 5;
    o->speed = 0.3;
    o->lid_speed = 0.05;
    o->friction = 0.4;
    o->gravity = 1;
}

static void test_classical_rolling_stored_anew(void **st)
{
    (void)st;
    packing_opts o;
    base(&o);
    o.effects = DEM_EFFECT_CLASSICAL | DEM_EFFECT_ROLLING;
    o.rolling_friction = 0.05;
    one_against_two(&o, 1, 1, 0, 0, "classical with rolling resistance, stored anew");
}

static void test_mc_stress(void **st)
{
    (void)st;
    packing_opts o;
    base(&o);
    o.effects = DEM_EFFECT_CLASSICAL | DEM_EFFECT_MC_STRESS;
    o.mc_beta = 1.0;
    one_against_two(&o, 1, 0, 1, 0, "MC-stress, the lid a servo");
}

static void test_frictionless(void **st)
{
    (void)st;
    packing_opts o;
    base(&o);
    o.friction = 0;
    o.effects = DEM_EFFECT_HERTZ | DEM_EFFECT_DAMPING | DEM_EFFECT_GRAVITY | DEM_EFFECT_WALLS;
    one_against_two(&o, 1, 0, 0, 1, "no friction, sampled, wall forces kept");
}

static void test_mdr_keeps_two_passes(void **st)
{
    (void)st;
    packing_opts o;
    base(&o);
    o.effects = DEM_EFFECT_CLASSICAL | DEM_EFFECT_MDR;
    o.yield_stress = 5e5;
    o.surface_energy = 0;
    o.bulk_fraction = 0.5;
    o.mdr_damping = 0.2;
    one_against_two(&o, 0, 0, 0, 0, "MDR");
}

/* every other law that keeps a state per pair keeps the two passes too (reference fp64: contact_rows never runs) */
static void test_stateful_laws_keep_two_passes(void **st)
{
    (void)st;
    struct {
        unsigned effects;
        const char *name;
    } laws[] = {{DEM_EFFECT_CLASSICAL | DEM_EFFECT_MC_STRAIN, "MC-strain"},
                {DEM_EFFECT_CLASSICAL | DEM_EFFECT_THORNTON_NING, "Thornton-Ning"},
                {DEM_EFFECT_CLASSICAL | DEM_EFFECT_THORNTON_NING | DEM_EFFECT_ADHESION, "Thornton-Ning with adhesion"},
                {DEM_EFFECT_CLASSICAL | DEM_EFFECT_ROLLING | DEM_EFFECT_ROLLING_SPRING, "the rolling spring"}};
    for (size_t k = 0; k < sizeof laws / sizeof laws[0]; k++) {
        packing_opts o;
        base(&o);
        o.effects = laws[k].effects;
        o.mc_gamma = 0.5;
        o.yield_stress = 5e5;
        o.rolling_friction = 0.05;
        o.rolling_damping = 0.3;
        o.surface_energy = 0.01;
        dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
        c.one_pass = 1;
        dem_sim *s = packing_build(&o);
        if (dem_set_effects(s, laws[k].effects)) /* (packing_build leaves a refused mask unsaid) */
            fail_msg("%s: %s", laws[k].name, dem_error(s));
        start_or_fail(s, &c);
        step_or_fail(s, 30);
        if (rows_seconds(s) != 0)
            fail_msg("%s: contact_rows ran", laws[k].name);
        dem_destroy(s);
    }
}

/* a one-pass run restored from a two-pass run's state mid-run (its second copies hold nothing of it) goes on with
 * the two passes' bits; and DEM_ONE_PASS=1, only that, sets dem_config.one_pass */
static void test_restored_and_environment(void **st)
{
    (void)st;
    packing_opts o;
    base(&o);
    dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP32), c1 = c;
    c.one_pass = 0, c1.one_pass = 1;
    dem_sim *a = packing_build(&o), *b = packing_build(&o);
    start_or_fail(a, &c);
    start_or_fail(b, &c1);
    step_or_fail(b, 57); /* its copies and the flags' parity elsewhere */
    step_or_fail(a, 120);
    dem_state saved;
    if (dem_state_get(a, &saved) || dem_state_set(b, &saved))
        fail_msg("restore: %s", dem_error(a)[0] ? dem_error(a) : dem_error(b));
    dem_state_free(&saved);
    twins_step(a, b, 150, "one pass restored from two passes' state at step 120");
    if (!(rows_seconds(b) > 0))
        fail_msg("contact_rows never ran in the restored run");
    dem_destroy(a);
    dem_destroy(b);
    const char *vals[] = {"1", "0", "yes", "", "11"};
    for (int k = 0; k < 5; k++) {
        setenv("DEM_ONE_PASS", vals[k], 1);
        dem_config_default(&c);
        assert_int_equal(c.one_pass, k == 0);
    }
    unsetenv("DEM_ONE_PASS");
    dem_config_default(&c);
    assert_int_equal(c.one_pass, 0);
}

int main(void)
{
    setenv("DEM_PROFILE", "1", 1); /* PoCL times its kernels: the test reads contact_rows' time */
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_classical_rolling_stored_anew),
        cmocka_unit_test(test_mc_stress),
        cmocka_unit_test(test_frictionless),
        cmocka_unit_test(test_mdr_keeps_two_passes),
        cmocka_unit_test(test_stateful_laws_keep_two_passes),
        cmocka_unit_test(test_restored_and_environment),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
