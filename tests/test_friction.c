/* test_friction.c - Coulomb friction on an incline (gravity tilted by theta over a flat floor, mu = 0.4).
 * A sphere that cannot rotate is a block: it sticks for tan(theta) < mu and slides above, with acceleration
 * g (sin theta - mu cos theta), also with mu from the material-pair table (test_pair_friction). A free sphere rolls
 * without slipping for tan(theta) < 7/2 mu (contact point at rest, acceleration 5/7 g sin theta) and slips above. Angles 10 % either side of each threshold. PoCL, fp64. */
#include "test_util.h"
#include <math.h>
#include <stdio.h>

#define MU 0.4
#define G 9.81

typedef struct {
    double disp;      /* distance travelled down the slope [m] */
    double accel;     /* from the velocities at t = 0.05 s and 0.1 s [m/s^2] */
    double slip;      /* contact-point speed v - w r at the end [m/s] */
} slope_result;

static double inertia_factor = 0; /* > 0: the sphere's moment of inertia set to this x m r^2 (dem_set_particle_mass) */
/* 1: the sphere's material has friction 0.7 and the floor's another material with 0 (their mean 0.35), and the pair is
 * set apart to MU (dem_set_material_pair): a lubricated die against a sticky powder */
static int pair_set_apart = 0;

static slope_result slide(double theta, int rotate)
{
    const double r = 0.005, rho = 2500, E = 1e7, nu = 0.3;
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){rho, E, nu, 0.5, pair_set_apart ? 0.7 : MU});
    int fm = pair_set_apart ? dem_add_material(s, &(dem_material){rho, E, nu, 0.5, 0.0}) : m;
    if (pair_set_apart)
        assert_int_equal(dem_set_material_pair(s, fm, m, &(dem_material_pair){MU, NAN, NAN, NAN, NAN}), 0);
    /* start at the static overlap under the normal load m g cos(theta) */
    double mass = rho * 4.0 / 3.0 * M_PI * r * r * r, es = E / (2 * (1 - nu * nu)); /* sphere on a wall of the same */
    double d = pow(mass * G * cos(theta) / (4.0 / 3.0 * es * sqrt(r)), 2.0 / 3.0);
    int id = dem_add_particle(s, (double[3]){0, 0, r - d}, (double[3]){0, 0, 0}, r, m);
    if (!rotate)
        dem_set_particle_flags(s, id, DEM_PARTICLE_NO_ROTATION);
    if (inertia_factor > 0)
        assert_int_equal(dem_set_particle_mass(s, id, mass, inertia_factor * mass * r * r), 0);
    dem_wall floor = {.kind = DEM_WALL_PLANE, .material = fm, .point = {0, 0, 0}, .normal = {0, 0, 1}};
    dem_add_wall(s, &floor);
    dem_set_gravity(s, (double[3]){G * sin(theta), 0, -G * cos(theta)});
    dem_set_domain(s, (double[3]){-0.05, -0.05, -0.05}, (double[3]){1.0, 0.05, 0.05});
    dem_time_scales ts;
    dem_time_scales_get(s, 0, &ts);
    dem_set_dt(s, ts.recommended_dt);
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, DEM_FP64);
    start_or_fail(s, &c);
    long half = lround(0.05 / dem_dt(s));
    double x[3], v1[3], v[3], w[3];
    step_or_fail(s, half);
    dem_get_field(s, DEM_FIELD_V, v1);
    step_or_fail(s, half);
    dem_get_field(s, DEM_FIELD_X, x);
    dem_get_field(s, DEM_FIELD_V, v);
    dem_get_field(s, DEM_FIELD_W, w);
    slope_result res = {x[0], (v[0] - v1[0]) / (half * dem_dt(s)), v[0] - w[1] * r};
    dem_destroy(s);
    return res;
}

static void test_block(void **st)
{
    (void)st;
    double crit = atan(MU);
    slope_result below = slide(0.9 * crit, 0), above = slide(1.1 * crit, 0);
    double a_expect = G * (sin(1.1 * crit) - MU * cos(1.1 * crit));
    printf("  block: theta 0.9 atan(mu): moved %.3g m; 1.1 atan(mu): a %.4g m/s^2 (expected %.4g)\n", below.disp,
           above.accel, a_expect);
    assert_true(fabs(below.disp) < 1e-5); /* only the tangential spring's elastic creep */
    assert_true(fabs(above.accel / a_expect - 1) < 0.005);
}

static void test_rolling_sphere(void **st)
{
    (void)st;
    double crit = atan(3.5 * MU);
    slope_result roll = slide(0.9 * crit, 1), slip = slide(1.1 * crit, 1);
    double a_roll = 5.0 / 7.0 * G * sin(0.9 * crit);
    /* slipping from rest: v grows at g (sin - mu cos), w r at 5/2 mu g cos, so the contact point slips at
     * g (sin - 7/2 mu cos) t, t = 0.1 s at the end */
    double th = 1.1 * crit, slip_expect = G * (sin(th) - 3.5 * MU * cos(th)) * 0.1;
    printf("  sphere: theta 0.9 atan(3.5 mu): a %.4g (rolling %.4g), slip speed %.3g m/s; 1.1 atan(3.5 mu): slip "
           "speed %.4g m/s (expected %.4g)\n", roll.accel, a_roll, roll.slip, slip.slip, slip_expect);
    assert_true(fabs(roll.accel / a_roll - 1) < 0.02);
    assert_true(fabs(roll.slip) < 1e-3);
    assert_true(fabs(slip.slip / slip_expect - 1) < 0.03);
}

/* A body's inertia apart from its radius (dem_set_particle_mass): with I = m r^2 (a thin shell's 2/3 would do too)
 * a rolling sphere accelerates at g sin(theta) / (1 + I / (m r^2)) = g sin(theta) / 2, and rolls for
 * tan(theta) < mu (1 + m r^2 / I) = 2 mu. */
static void test_explicit_inertia(void **st)
{
    (void)st;
    inertia_factor = 1.0;
    double th = 0.5 * atan(2 * MU);
    slope_result roll = slide(th, 1);
    inertia_factor = 0;
    double a = G * sin(th) / 2;
    printf("  I = m r^2: theta %.4f: a %.4g m/s^2 (rolling %.4g), slip %.3g m/s\n", th, roll.accel, a, roll.slip);
    assert_true(fabs(roll.accel / a - 1) < 0.02);
    assert_true(fabs(roll.slip) < 1e-3);
}

/* The block again with its friction from the material-pair table: the pair's 0.4, not the mean 0.35 of 0.7 and 0 */
static void test_pair_friction(void **st)
{
    (void)st;
    pair_set_apart = 1;
    double crit = atan(MU);
    slope_result below = slide(0.9 * crit, 0), above = slide(1.1 * crit, 0);
    pair_set_apart = 0;
    double a_expect = G * (sin(1.1 * crit) - MU * cos(1.1 * crit));
    printf("  block, pair friction 0.4 over materials 0.7 and 0: theta 0.9 atan(0.4), tan 0.356: moved %.3g m (it would slide at "
           "the mean 0.35); 1.1 atan(0.4): a %.4g m/s^2 (expected %.4g)\n", below.disp, above.accel, a_expect);
    assert_true(fabs(below.disp) < 1e-5);
    assert_true(fabs(above.accel / a_expect - 1) < 0.005);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_block),
        cmocka_unit_test(test_rolling_sphere),
        cmocka_unit_test(test_explicit_inertia),
        cmocka_unit_test(test_pair_friction),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
