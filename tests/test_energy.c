/* test_energy.c - with e = 1 and mu = 0 nothing dissipates: over at least 10 collisions (particle-particle and
 * particle-wall) in a closed box without gravity, total energy drifts by less than 1e-4 relative. Velocity Verlet
 * is symplectic, so the energy error made inside a contact is given back when it ends: the drift is measured
 * between contact-free instants. Runs on PoCL, fp64, bitwise checked against the reference at the end. */
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

static dem_sim *box_gas(void)
{
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){1000, 1e6, 0.3, 1.0, 0.0});
    unsigned st = 3;
    const double L = 0.06;
    for (int k = 0; k < 12; k++) {
        double x[3] = {0.015 + 0.015 * (k % 3), 0.02 + 0.02 * (k / 3 % 2), 0.02 + 0.02 * (k / 6)};
        double v[3] = {2 * uniform01(&st) - 1, 2 * uniform01(&st) - 1, 2 * uniform01(&st) - 1};
        double r = 0.003 + 0.002 * (k % 3);
        dem_add_particle(s, x, v, r, m);
    }
    dem_add_box(s, (double[3]){0, 0, 0}, (double[3]){L, L, L}, m);
    dem_set_domain(s, (double[3]){-0.01, -0.01, -0.01}, (double[3]){0.07, 0.07, 0.07});
    /* 1/200 of the Hertz contact time of the smallest like pair at 2 m/s */
    dem_time_scales ts;
    dem_time_scales_get(s, 2.0, &ts);
    dem_set_dt(s, ts.hertz_time / 200);
    return s;
}

static void test_energy_conserved(void **st)
{
    (void)st;
    dem_sim *s = box_gas(), *ref = box_gas();
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, DEM_FP64), rc = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    start_or_fail(s, &c);
    start_or_fail(ref, &rc);
    dem_energy_t e;
    dem_energy(s, &e);
    const double e0 = e.total;
    assert_true(e.elastic == 0); /* the set-up starts contact-free */
    int collisions = 0, in_contact = 0;
    double drift = 0, inside = 0;
    long steps = 0;
    while (collisions < 12 && steps < 400000) {
        step_or_fail(s, 10);
        steps += 10;
        dem_energy(s, &e);
        double rel = fabs(e.total - e0) / e0;
        if (e.elastic > 0) {
            if (!in_contact)
                collisions++;
            in_contact = 1;
            inside = fmax(inside, rel);
        } else {
            in_contact = 0;
            drift = fmax(drift, rel);
        }
    }
    step_or_fail(ref, steps);
    char msg[256];
    if (state_diff(s, ref, msg, sizeof msg))
        fail_msg("PoCL vs reference: %s", msg);
    printf("  %d collisions in %ld steps: drift between contacts %.3g, largest deviation inside contacts %.3g\n",
           collisions, steps, drift, inside);
    assert_true(collisions >= 10);
    assert_true(drift < 1e-4);
    dem_destroy(s);
    dem_destroy(ref);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_energy_conserved)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
