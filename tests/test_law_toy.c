/* test_law_toy.c - a contact law added as a unit: the test-only linear spring of common/laws/linear_spring.h
 * (F = k delta, energy k delta^2 / 2, stiffness k), compiled in by -DDEM_TEST_LAWS (this test links a library built
 * with it: Makefile, build/testlaws/) and chosen by its effect bit DEM_EFFECT_TEST_SPRING. Two spheres collide
 * head-on, and one sphere meets a plane wall, on the reference and on OpenCL (PoCL), fp64 and fp32; the closed forms
 * are typed in here, not taken from the library:
 *   a pair (masses m1, m2, m* = m1 m2 / (m1 + m2)) approaching at relative speed v: contact time pi sqrt(m* / k),
 *   largest overlap v sqrt(m* / k), leaving at speed v (no damping); a sphere on a rigid wall the same with m* = m;
 *   while touching: force k delta on each body, elastic energy k delta^2 / 2 (dem_energy), and the stability
 *   estimate's omega dt = dt sqrt(k (1/m1 + 1/m2)) (dem_stability_get: normal mode only, no damping).
 * Every step the OpenCL state must equal the reference's bit for bit, and so must the host's energy and stability
 * figures taken from the two. */
#include "test_util.h"
#include "dem_internal_bits.h" /* DEM_EFFECT_TEST_SPRING: the test-only law's bit */
#include <math.h>
#include <stdio.h>
#include <string.h>

#ifndef DEM_TEST_LAWS
#error "tests/test_law_toy.c is built with -DDEM_TEST_LAWS (Makefile)"
#endif

#define K_SPRING 65536.0 /* [N/m]; E = 2 k, nu = 0 makes the pair's E* (the law's k column) exactly k */
#define RHO 1000.0
#define R 0.01

static double sphere_mass(double r) { return RHO * 4.0 / 3.0 * M_PI * r * r * r; }

/* wall = 0: two spheres of radius R approaching along x at +-v/2, touching at t = 0; wall = 1: one sphere moving at
 * -v towards the plane x = 0, touching it at t = 0 (the wall's material rigid: E* = E of the sphere = k) */
static dem_sim *build(int wall, double v, double dt)
{
    dem_material m = {RHO, wall ? K_SPRING : 2 * K_SPRING, 0.0, 1.0, 0.0, 0.0, 0.0};
    dem_material rigid = {RHO, INFINITY, 0.0, 1.0, 0.0, 0.0, 0.0};
    return head_on_build(&m, wall ? &rigid : NULL, R, v,
                         DEM_EFFECT_HERTZ | DEM_EFFECT_TEST_SPRING | (wall ? DEM_EFFECT_WALLS : 0), dt);
}

/* the overlap, the x force on the sphere at the smaller x side (particle 0) and the host's figures */
typedef struct {
    double delta, f0;
    dem_energy_t en;
    dem_stability st;
} sample;

static sample take(dem_sim *s, int wall)
{
    sample o;
    double x[6], f[6];
    assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
    assert_int_equal(dem_get_field(s, DEM_FIELD_FORCE, f), 0);
    o.delta = wall ? R - x[0] : 2 * R - fabs(x[3] - x[0]);
    o.f0 = f[0];
    assert_int_equal(dem_energy(s, &o.en), 0);
    assert_int_equal(dem_stability_get(s, &o.st), 0);
    return o;
}

static void collide(int wall, dem_precision prec)
{
    const double v = 0.1;
    double m = sphere_mass(R), ms = wall ? m : m / 2, inv_m = wall ? 1 / m : 2 / m;
    double tc0 = M_PI * sqrt(ms / K_SPRING), d0 = v * sqrt(ms / K_SPRING), dt = tc0 / 2000;
    /* fp32 positions near R carry an absolute error of about R 2^-24, a part 1e-3 or so of the overlaps here */
    double tol = prec == DEM_FP64 ? 1e-9 : 2e-2, ptol = prec == DEM_FP64 ? 1e-4 : 1e-3;
    dem_sim *cl = build(wall, v, dt), *ref = build(wall, v, dt);
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, prec), rc = cfg_of(DEM_BACKEND_REFERENCE, prec);
    start_or_fail(cl, &c);
    start_or_fail(ref, &rc);
    double e0 = 0, dmax = 0, tc = 0, worst_f = 0, worst_e = 0, worst_w = 0, etot_dev = 0;
    int was = 0, touching_steps = 0;
    for (int k = 0; k < 4000; k++) {
        twins_step(cl, ref, 1, wall ? "wall, PoCL vs reference" : "pair, PoCL vs reference");
        sample a = take(ref, wall), b = take(cl, wall);
        /* the host's figures are the same bits from either backend's state */
        assert_memory_equal(&a.en, &b.en, sizeof a.en);
        assert_true(a.st.ratio == b.st.ratio && a.st.omega_dt == b.st.omega_dt);
        if (k == 0)
            e0 = a.en.kinetic + a.en.elastic;
        etot_dev = fmax(etot_dev, fabs((a.en.kinetic + a.en.elastic) / e0 - 1));
        if (a.delta > 0) {
            was = 1;
            tc += dt;
            touching_steps++;
            dmax = fmax(dmax, a.delta);
            /* force on particle 0: pushed towards -x by the other sphere, towards +x by the wall */
            double f = (wall ? 1 : -1) * K_SPRING * a.delta;
            worst_f = fmax(worst_f, fabs(a.f0 - f) / (K_SPRING * d0));
            worst_e = fmax(worst_e, fabs(a.en.elastic - 0.5 * K_SPRING * a.delta * a.delta) / (0.5 * K_SPRING * d0 * d0));
            assert_int_equal(a.st.contacts, 1);
            assert_int_equal(a.st.tangential, 0);
            assert_true(a.st.zeta == 0);
            worst_w = fmax(worst_w, fabs(a.st.omega_dt / (dt * sqrt(K_SPRING * inv_m)) - 1));
            assert_int_equal(wall ? a.en.wall_contacts : a.en.contacts, 1);
        } else if (was) {
            break;
        }
    }
    double vout[6];
    assert_int_equal(dem_get_field(ref, DEM_FIELD_V, vout), 0);
    double vrel = wall ? vout[0] : vout[0] - vout[3]; /* leaving: +v off the wall, -v apart */
    printf("  %s, %s: %d steps in contact, t_c %.6g s (closed %.6g), d_max %.6g m (%.6g), leaving at %.6g m/s (%g); "
           "worst force %.2g, energy %.2g, omega dt %.2g (relative); total energy kept to %.2g\n",
           wall ? "sphere on a wall" : "two spheres", prec == DEM_FP64 ? "fp64" : "fp32", touching_steps, tc, tc0,
           dmax, d0, vrel, wall ? v : -v, worst_f, worst_e, worst_w, etot_dev);
    assert_true(touching_steps > 1000);
    assert_true(fabs(tc / tc0 - 1) < 1e-3);
    assert_true(fabs(dmax / d0 - 1) < ptol);
    assert_true(fabs(vrel / (wall ? v : -v) - 1) < ptol);
    assert_true(worst_f < tol);
    assert_true(worst_e < tol);
    assert_true(worst_w < 1e-12);
    assert_true(etot_dev < 10 * ptol);
    dem_destroy(cl);
    dem_destroy(ref);
}

static void test_pair_fp64(void **st) { (void)st; collide(0, DEM_FP64); }
static void test_pair_fp32(void **st) { (void)st; collide(0, DEM_FP32); }
static void test_wall_fp64(void **st) { (void)st; collide(1, DEM_FP64); }

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pair_fp64),
        cmocka_unit_test(test_pair_fp32),
        cmocka_unit_test(test_wall_fp64),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
