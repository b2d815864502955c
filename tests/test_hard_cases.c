/* test_hard_cases.c - hard cases stay finite and clear, on the reference and on PoCL:
 * coincident centres, a particle leaving the binning domain, glass (65 GPa, seed 000 Table 1) at the recommended
 * time step, refusal of a time step above the stability bound, rejection of invalid parameters, and a kernel that
 * fails to build (the device's build log reaches the caller). */
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int all_finite(dem_sim *s, dem_field f)
{
    int n = dem_count(s);
    double *a = malloc(sizeof(double) * 3 * n);
    int ok = dem_get_field(s, f, a) == 0;
    for (int k = 0; ok && k < 3 * n; k++)
        ok = isfinite(a[k]);
    free(a);
    return ok;
}

/* Two spheres of radius r, the second at x1 with speed v1 along x, in the cube [-half, half]^3, started. */
static dem_sim *two_spheres(double r, double x1, double v1, double half, int opencl, dem_precision prec)
{
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0.3});
    dem_add_particle(s, (double[3]){0, 0, 0}, NULL, r, m);
    dem_add_particle(s, (double[3]){x1, 0, 0}, (double[3]){v1, 0, 0}, r, m);
    dem_set_domain(s, (double[3]){-half, -half, -half}, (double[3]){half, half, half});
    dem_time_scales ts;
    dem_time_scales_get(s, 0, &ts);
    dem_set_dt(s, ts.recommended_dt);
    dem_config c = cfg_of(opencl ? DEM_BACKEND_OPENCL : DEM_BACKEND_REFERENCE, prec);
    start_or_fail(s, &c);
    return s;
}

static void test_coincident_centres(void **st)
{
    (void)st;
    for (int b = 0; b < 2; b++) {
        dem_sim *s = two_spheres(0.01, 0, 0, 1, b, DEM_FP64);
        double x[6] = {0};
        for (int k = 0; k < 200 && x[2] - x[5] < 0.02; k++) { /* until they no longer touch */
            step_or_fail(s, 10);
            assert_true(all_finite(s, DEM_FIELD_X) && all_finite(s, DEM_FIELD_V) && all_finite(s, DEM_FIELD_FORCE));
            dem_get_field(s, DEM_FIELD_X, x);
        }
        /* defined policy: the lower id is pushed along +z; they separate along z */
        assert_true(x[2] > x[5]);
        assert_true(x[2] - x[5] >= 0.02);
        assert_true(x[0] == 0 && x[3] == 0);
        dem_destroy(s);
    }
}

static void test_leaves_domain(void **st)
{
    (void)st;
    for (int b = 0; b < 2; b++) {
        dem_sim *s = two_spheres(0.001, 0.05, 5, 0.1, b, DEM_FP32);
        long need = lround(0.06 / (5 * dem_dt(s))) + 100;
        int e = dem_step(s, need);
        assert_int_equal(e, DEM_ERR_DOMAIN);
        const char *msg = dem_error(s);
        printf("  %s: %s\n", b ? "PoCL" : "reference", msg);
        assert_non_null(strstr(msg, "particle 1 "));
        assert_non_null(strstr(msg, "outside the binning domain"));
        /* it stopped right after leaving: the check runs at each neighbour rebuild, which comes once a particle has
         * moved skin/2 (skin: the default 0.3 r_min), so the particle is past the grid's boundary (the domain's
         * 0.1 m rounded up to whole cells, as the message says) by at most skin/2 plus one step's travel */
        assert_true(dem_step_index(s) < need);
        const char *at = strstr(msg, " at ("), *dom = strstr(msg, "domain [");
        double px = NAN, lo = NAN, hi = NAN;
        assert_non_null(at);
        assert_non_null(dom);
        assert_int_equal(sscanf(at, " at (%lf", &px), 1);
        assert_int_equal(sscanf(dom, "domain [%lf,%lf]", &lo, &hi), 2);
        assert_true(lo == -0.1 && hi >= 0.1 && hi < 0.2);
        double bound = hi + 0.5 * 0.3 * 0.001 + 5 * dem_dt(s);
        printf("  stopped at x = %.6f m: %.3g m past the grid's boundary %.6f m (bound %.3g m)\n", px, px - hi, hi,
               bound - hi);
        assert_true(px > hi && px <= bound * (1 + 1e-6));
        dem_destroy(s);
    }
}

static void test_nonfinite_rejected(void **st)
{
    (void)st;
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0.3});
    assert_int_equal(dem_add_particle(s, (double[3]){NAN, 0, 0}, NULL, 0.001, m), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "finite"));
    assert_int_equal(dem_add_particle(s, (double[3]){0, 0, 0}, NULL, -0.001, m), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "radius"));
    assert_int_equal(dem_add_material(s, &(dem_material){2500, 1e7, 0.6, 0.5, 0.3}), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "Poisson"));
    assert_int_equal(dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.0, 0.3}), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "restitution"));
    assert_int_equal(dem_add_material(s, &(dem_material){-1, 1e7, 0.3, 0.5, 0.3}), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "density"));
    dem_destroy(s);
}

/* 64 glass beads (seed 000 Table 1: 2500 kg/m^3, d 4 mm, 65 GPa, nu 0.24, e 0.98, mu 0.2) dropped at 1 m/s onto
 * a floor and each other in a box, at the recommended time step: finite, bounded energy, overlaps small. */
static dem_sim *glass_box(double dt_factor)
{
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){2500, 65e9, 0.24, 0.98, 0.2});
    unsigned seed = 11;
    for (int k = 0; k < 64; k++) {
        double x[3] = {0.003 + 0.0045 * (k % 4), 0.003 + 0.0045 * (k / 4 % 4), 0.003 + 0.0045 * (k / 16)};
        double v[3] = {uniform01(&seed) - 0.5, uniform01(&seed) - 0.5, -1};
        dem_add_particle(s, x, v, 0.002, m);
    }
    dem_add_box(s, (double[3]){0, 0, 0}, (double[3]){0.02, 0.02, 0.02}, m);
    dem_set_gravity(s, (double[3]){0, 0, -9.81});
    dem_set_domain(s, (double[3]){-0.01, -0.01, -0.01}, (double[3]){0.03, 0.03, 0.03});
    dem_time_scales ts;
    dem_time_scales_get(s, 1.0, &ts);
    dem_set_dt(s, dt_factor * ts.recommended_dt);
    return s;
}

static void test_glass_recommended_dt(void **st)
{
    (void)st;
    dem_sim *s = glass_box(1.0);
    dem_time_scales ts;
    dem_time_scales_get(s, 1.0, &ts);
    printf("  glass: Rayleigh time %.4g s, Hertz time at 1 m/s %.4g s, recommended dt %.4g s\n", ts.rayleigh_time,
           ts.hertz_time, ts.recommended_dt);
    /* Rayleigh time by hand: pi r sqrt(rho/G)/(0.1631 nu + 0.8766), G = E/(2(1+nu)) */
    double G = 65e9 / (2 * 1.24), tr = M_PI * 0.002 * sqrt(2500 / G) / (0.1631 * 0.24 + 0.8766);
    assert_true(fabs(ts.rayleigh_time / tr - 1) < 1e-12);
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, DEM_FP64);
    start_or_fail(s, &c);
    dem_energy_t e0, e;
    dem_energy(s, &e0);
    double worst = 0;
    for (int k = 0; k < 40; k++) {
        step_or_fail(s, 500);
        dem_energy(s, &e);
        assert_true(isfinite(e.total));
        assert_true(e.total <= e0.total * 1.001); /* nothing creates energy */
        double x[3 * 64];
        dem_get_field(s, DEM_FIELD_X, x);
        for (int i = 0; i < 64; i++)
            worst = fmax(worst, 0.002 - x[3 * i + 2]); /* overlap with the floor */
    }
    printf("  glass: %ld steps, energy %.4g -> %.4g J, largest floor overlap %.3g %% of r\n", dem_step_index(s),
           e0.total, e.total, 100 * worst / 0.002);
    assert_true(all_finite(s, DEM_FIELD_V) && all_finite(s, DEM_FIELD_W));
    assert_true(worst < 0.01 * 0.002);
    dem_destroy(s);
}

static void test_dt_bound(void **st)
{
    (void)st;
    dem_sim *s = glass_box(3.0); /* 0.6 x Rayleigh time: above the 0.5 bound */
    dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    assert_int_equal(dem_start(s, &c), DEM_ERR_DT);
    printf("  %s\n", dem_error(s));
    assert_non_null(strstr(dem_error(s), "stability bound"));
    dem_destroy(s);
    s = glass_box(3.0);
    c.force_dt = 1;
    start_or_fail(s, &c);
    dem_destroy(s);
}

/* A kernel that does not compile: dem_start fails with DEM_ERR_DEVICE and the device's build log, naming the file.
 * The project's kernels are copied to a temporary folder and one of them is broken there. */
static void test_kernel_build_log(void **st)
{
    (void)st;
    char dir[] = "/tmp/dem-kernels-XXXXXX", cmd[512];
    assert_non_null(mkdtemp(dir));
    snprintf(cmd, sizeof cmd, "cp -r '%s/kernels' '%s/common' '%s/include' '%s/' && echo 'this is not OpenCL C;' >> "
             "'%s/kernels/program.cl'", DEM_DEFAULT_SOURCE_DIR, DEM_DEFAULT_SOURCE_DIR, DEM_DEFAULT_SOURCE_DIR, dir,
             dir);
    assert_int_equal(system(cmd), 0);
    dem_sim *s = glass_box(1.0);
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, DEM_FP64);
    c.source_dir = dir;
    assert_int_equal(dem_start(s, &c), DEM_ERR_DEVICE);
    printf("  %.300s...\n", dem_error(s));
    assert_non_null(strstr(dem_error(s), "build log"));
    assert_non_null(strstr(dem_error(s), "program.cl"));
    dem_destroy(s);
    /* and a folder without kernels says where it looked */
    s = glass_box(1.0);
    c.source_dir = "/nonexistent-dem-folder";
    assert_int_equal(dem_start(s, &c), DEM_ERR_DEVICE);
    assert_non_null(strstr(dem_error(s), "/nonexistent-dem-folder/kernels/"));
    dem_destroy(s);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    assert_int_equal(system(cmd), 0);
}

/* The source hash the program is built with (-DDEM_SOURCE_HASH, which keys PoCL's compiler cache) covers every file of
 * the source folders: a header added in a new subfolder of common/ changes it, and so does an edit of it; an unchanged
 * folder gives the same hash again. The copy's program stops at its first line (#error), so that each start fails at
 * once with the build options, hash included, in its message, instead of compiling a program for each hash. */
static unsigned long long source_hash_of(const char *dir)
{
    dem_sim *s = glass_box(1.0);
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, DEM_FP64);
    c.source_dir = dir;
    assert_int_equal(dem_start(s, &c), DEM_ERR_DEVICE);
    assert_non_null(strstr(dem_error(s), "hash probe"));
    const char *h = strstr(dem_error(s), "-DDEM_SOURCE_HASH=0x");
    assert_non_null(h);
    unsigned long long v = strtoull(h + strlen("-DDEM_SOURCE_HASH=0x"), NULL, 16);
    dem_destroy(s);
    return v;
}

static void test_source_hash_covers_folders(void **st)
{
    (void)st;
    char dir[] = "/tmp/dem-hash-XXXXXX", cmd[512];
    assert_non_null(mkdtemp(dir));
    snprintf(cmd, sizeof cmd, "cp -r '%s/kernels' '%s/common' '%s/include' '%s/' && sed -i '1i #error hash probe' "
             "'%s/kernels/program.cl'", DEM_DEFAULT_SOURCE_DIR, DEM_DEFAULT_SOURCE_DIR, DEM_DEFAULT_SOURCE_DIR, dir, dir);
    assert_int_equal(system(cmd), 0);
    unsigned long long h0 = source_hash_of(dir), h1 = source_hash_of(dir);
    snprintf(cmd, sizeof cmd, "mkdir '%s/common/sub' && echo '#define DEM_UNUSED 1' > '%s/common/sub/new.h'", dir, dir);
    assert_int_equal(system(cmd), 0);
    unsigned long long h2 = source_hash_of(dir);
    snprintf(cmd, sizeof cmd, "echo '#define DEM_UNUSED 2' > '%s/common/sub/new.h'", dir);
    assert_int_equal(system(cmd), 0);
    unsigned long long h3 = source_hash_of(dir);
    printf("  source hashes: %016llx, again %016llx, a new header in common/sub/ %016llx, edited %016llx\n", h0, h1,
           h2, h3);
    assert_true(h0 == h1);
    assert_true(h2 != h1);
    assert_true(h3 != h2 && h3 != h1);
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    assert_int_equal(system(cmd), 0);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_coincident_centres), cmocka_unit_test(test_leaves_domain),
        cmocka_unit_test(test_nonfinite_rejected), cmocka_unit_test(test_glass_recommended_dt),
        cmocka_unit_test(test_dt_bound), cmocka_unit_test(test_kernel_build_log),
        cmocka_unit_test(test_source_hash_covers_folders),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
