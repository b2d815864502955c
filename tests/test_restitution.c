/* test_restitution.c - the damping calibrated from e (host/restitution.c) gives that e in a simulated head-on
 * collision, within 1 %, for e in {0.3, 0.5, 0.7, 0.9, 0.95}, at two impact speeds (it must not depend on speed). */
#include "test_util.h"
#include <math.h>
#include <stdio.h>

static double measure(double e, double v)
{
    dem_material m = {1000, 1e7, 0.3, e, 0.0};
    dem_sim *s = pair_build(&m, 0.01, 0.01, v, 1.0 / 1000);
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, DEM_FP64);
    start_or_fail(s, &c);
    int touched = 0;
    for (int k = 0; k < 5000; k++) {
        step_or_fail(s, 1);
        double gap = pair_distance(s) - 0.02;
        if (gap < 0)
            touched = 1;
        else if (touched)
            break;
    }
    double vel[6];
    dem_get_field(s, DEM_FIELD_V, vel);
    dem_destroy(s);
    assert_true(touched);
    return (vel[3] - vel[0]) / v;
}

static void test_restitution(void **st)
{
    (void)st;
    const double es[] = {0.3, 0.5, 0.7, 0.9, 0.95};
    for (int k = 0; k < 5; k++)
        for (int sp = 0; sp < 2; sp++) {
            double v = sp ? 3.0 : 0.2, got = measure(es[k], v);
            printf("  e requested %.2f, v %.1f m/s: measured %.5f (damping factor %.5f)\n", es[k], v, got,
                   dem_damping_for_restitution(es[k]));
            assert_true(fabs(got / es[k] - 1) < 0.01);
        }
}

/* e = 1 means no damping at all, and the calibration is monotonic. */
static void test_calibration(void **st)
{
    (void)st;
    assert_true(dem_damping_for_restitution(1.0) == 0.0);
    double prev = 0;
    for (double e = 0.95; e > 0.1; e -= 0.1) {
        double c = dem_damping_for_restitution(e);
        assert_true(c > prev);
        assert_true(fabs(dem_restitution_for_damping(c) - e) < 1e-6);
        prev = c;
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_calibration),
        cmocka_unit_test(test_restitution),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
