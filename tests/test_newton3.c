/* test_newton3.c - Newton's third law with no walls and no gravity.
 * Each pair force is evaluated once in canonical orientation and negated for the partner, so f_ji = -f_ij bit for
 * bit. Where every particle has at most one contact the total force is therefore exactly zero, which this test
 * checks bitwise over a gas of colliding spheres. In a dense packing each particle's force is itself a rounded sum
 * of several contacts, so the total is zero only up to that rounding: each particle adds up to c - 1 roundings of
 * its c contacts (c <= 8 here, the squeezed lattice's 8 body-centre neighbours), each at most half an ulp of the
 * partial sum, so the test bounds the total by 8 n ulps (DBL_EPSILON) of the largest particle force, for every step
 * of a run, on the reference and on PoCL (identical bits, so the same total), and prints the largest ratio seen. */
#include "test_util.h"
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

static dem_sim *dimer_gas(int npairs)
{
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.7, 0.5});
    unsigned st = 99;
    for (int k = 0; k < npairs; k++) {
        /* pairs far apart from each other, each pair colliding obliquely with spin */
        double c[3] = {0.1 * (k % 10), 0.1 * (k / 10), 0};
        double r1 = 0.004 + 0.004 * uniform01(&st), r2 = 0.004 + 0.004 * uniform01(&st);
        double y = (uniform01(&st) - 0.5) * r1;
        int a = dem_add_particle(s, (double[3]){c[0] - r1 - 1e-4, c[1] + y, c[2]}, (double[3]){0.5, 0.1, 0}, r1, m);
        int b = dem_add_particle(s, (double[3]){c[0] + r2 + 1e-4, c[1], c[2]}, (double[3]){-0.5, 0, 0.2}, r2, m);
        dem_set_particle_omega(s, a, (double[3]){0, 0, 30});
        dem_set_particle_omega(s, b, (double[3]){10, 0, 0});
    }
    dem_set_domain(s, (double[3]){-0.1, -0.1, -0.1}, (double[3]){1.1, 0.5, 0.1});
    dem_time_scales ts;
    dem_time_scales_get(s, 0, &ts);
    dem_set_dt(s, ts.recommended_dt);
    return s;
}

static void test_pairs_exact(void **st)
{
    (void)st;
    for (int b = 0; b < 2; b++)
        for (int p = 0; p < 2; p++) {
            dem_sim *s = dimer_gas(40);
            dem_config c = cfg_of(b ? DEM_BACKEND_OPENCL : DEM_BACKEND_REFERENCE, p ? DEM_FP64 : DEM_FP32);
            start_or_fail(s, &c);
            int n = dem_count(s), touching = 0;
            double *f = malloc(sizeof(double) * 3 * n);
            for (int k = 0; k < 400; k++) {
                step_or_fail(s, 1);
                dem_get_field(s, DEM_FIELD_FORCE, f);
                for (int i = 0; i < n; i += 2)
                    for (int d = 0; d < 3; d++) {
                        /* exact: the partner's force is the bitwise negation */
                        if (f[3 * i + d] != -f[3 * (i + 1) + d])
                            fail_msg("step %d pair %d: %.17g vs %.17g", k, i / 2, f[3 * i + d], f[3 * (i + 1) + d]);
                        touching += f[3 * i + d] != 0;
                    }
                double sum[3] = {0, 0, 0};
                for (int i = 0; i < n; i++)
                    for (int d = 0; d < 3; d++)
                        sum[d] += f[3 * i + d];
                assert_true(sum[0] == 0 && sum[1] == 0 && sum[2] == 0);
            }
            assert_true(touching > 100); /* the pairs did collide */
            free(f);
            dem_destroy(s);
        }
}

/* The packing's particles squeezed by 3 % without walls or gravity, random velocities (the same for every call). */
static dem_sim *squeezed(const packing_opts *o, const double *x, int n, double dt)
{
    dem_sim *t = dem_create();
    dem_add_material(t, &(dem_material){o->density, o->young, o->poisson, o->restitution, o->friction});
    unsigned seed = 5;
    for (int i = 0; i < n; i++) {
        double v[3] = {0.1 * (uniform01(&seed) - 0.5), 0.1 * (uniform01(&seed) - 0.5), 0.1 * (uniform01(&seed) - 0.5)};
        /* squeeze the lattice by 3 % so that every particle has several contacts from the start */
        double p[3] = {0.97 * x[3 * i], 0.97 * x[3 * i + 1], 0.97 * x[3 * i + 2]};
        dem_add_particle(t, p, v, i < o->side * o->side * o->side ? 1.0e-3 : 0.75e-3, 0);
    }
    dem_set_domain(t, (double[3]){-0.02, -0.02, -0.02}, (double[3]){0.04, 0.04, 0.04});
    dem_set_dt(t, dt);
    return t;
}

static void test_packing_bounded(void **st)
{
    (void)st;
    packing_opts o;
    packing_defaults(&o);
    o.side = 7;
    o.gravity = 0;
    dem_sim *s = packing_build(&o);
    int n = dem_count(s);
    double *x = malloc(sizeof(double) * 3 * n), *f = malloc(sizeof(double) * 3 * n), *fu = malloc(sizeof(double) * 3 * n);
    dem_config rc = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64), c = cfg_of(DEM_BACKEND_OPENCL, DEM_FP64);
    start_or_fail(s, &rc);
    dem_get_field(s, DEM_FIELD_X, x);
    dem_sim *t = squeezed(&o, x, n, dem_dt(s)), *u = squeezed(&o, x, n, dem_dt(s));
    start_or_fail(t, &c);
    start_or_fail(u, &rc);
    int loaded = 0;
    double worst = 0;
    for (int k = 0; k < 200; k++) {
        step_or_fail(t, 1);
        step_or_fail(u, 1);
        dem_get_field(t, DEM_FIELD_FORCE, f);
        dem_get_field(u, DEM_FIELD_FORCE, fu);
        assert_memory_equal(f, fu, sizeof(double) * 3 * n); /* the reference's forces, hence total, are PoCL's */
        double sum[3] = {0, 0, 0}, fmax = 0;
        for (int i = 0; i < n; i++)
            for (int d = 0; d < 3; d++) {
                sum[d] += f[3 * i + d];
                fmax = fmax > fabs(f[3 * i + d]) ? fmax : fabs(f[3 * i + d]);
            }
        loaded += fmax > 0;
        for (int d = 0; d < 3; d++) {
            if (fabs(sum[d]) > 8 * n * DBL_EPSILON * fmax)
                fail_msg("step %d: total force %g exceeds rounding bound (max |f| %g)", k, sum[d], fmax);
            if (fmax > 0 && fabs(sum[d]) / (n * DBL_EPSILON * fmax) > worst)
                worst = fabs(sum[d]) / (n * DBL_EPSILON * fmax);
        }
    }
    printf("  loaded steps %d; largest |total force| %.3g n ulps of the largest particle force (bound 8)\n", loaded,
           worst);
    assert_true(loaded >= 40); /* the bound was tested on a loaded packing */
    free(x), free(f), free(fu);
    dem_destroy(s);
    dem_destroy(t);
    dem_destroy(u);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pairs_exact),
        cmocka_unit_test(test_packing_bounded),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
