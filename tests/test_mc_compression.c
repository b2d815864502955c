/* test_mc_compression.c - the multi-contact models on seed 000's compression scenes, end to end through `dem run
 * --model`:
 *  - 514 hydrogel spheres to 13.4 % and back (Fig. 11), 514 rubber spheres to 28 % and back (Fig. 15), 17 glass beads
 *    to 2.64 % and back (Fig. 16), 348 + 1573 generated hydrogel spheres to 10.2 % and back (Fig. 14, the bed settled
 *    under gravity: scenes/hydrogel_1921.yaml says why it is higher than the paper's box): both multi-contact models are stiffer than classical DEM at peak strain, and the
 *    loop closes (the piston is back, the stress is gone) with every series value finite;
 *  - hard cases stay numerically stable (finite, bounded kinetic energy, no particle pushed through another):
 *    MC-strain at 10x the paper's compression speed, lagged and iterated; rubber to 40 % under both models; glass
 *    under both models at its recommended time step (0.2 Rayleigh times, as its scene has).
 * Overlap bound: a uniaxial strain e compresses a contact along the axis to d/D = e of the smaller diameter D by
 * geometry alone, whatever the contact law; the largest overlap in any frame must stay below the run's peak strain
 * plus OVERLAP_MARGIN (settling and polydispersity). A blow-up (spheres passing through each other) breaks it at
 * once. Each multi-contact model's stiffening over classical is asserted at the figure docs/multicontact.md states.
 * Figures measured here are printed for the closing note; `make validate` draws the stress-strain PNGs. */
#include "test_util.h"
#include "h5util.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define DEM DEM_DEFAULT_SOURCE_DIR "/build/dem"
#define SRC DEM_DEFAULT_SOURCE_DIR
static char tmp[256];

typedef struct {
    double peak_strain, stress_at_peak, final_strain, final_stress, max_stress;
    double max_kinetic, max_elastic; /* [J] */
    double max_overlap;              /* largest particle-particle overlap in any frame / smaller diameter */
    int finite;
} loop_result;

static double *series(hid_t f, const char *name, long *n)
{
    hid_t g = H5Gopen2(f, "series", H5P_DEFAULT);
    *n = h5_count(g, name);
    double *d = malloc(sizeof(double) * (size_t)(*n > 0 ? *n : 1));
    if (*n <= 0 || h5_read(g, name, H5T_NATIVE_DOUBLE, d, (size_t)*n))
        fail_msg("series/%s missing", name);
    H5Gclose(g);
    return d;
}

/* Runs scene (a path, or that scene edited by a NULL-terminated list of sed expressions first) with a model and
 * reads its output. Each expression must change the scene: one that stops matching (the scene was edited) fails the
 * test instead of silently running the plain scene as the "hard case". */
static loop_result run_loop(const char *scene, const char *const *sed, const char *model)
{
    char err[8192], path[512], out[512];
    snprintf(path, sizeof path, "%s", scene);
    if (sed) { /* a variant of a shipped scene, its CSV path made absolute */
        snprintf(path, sizeof path, "%s/variant.yaml", tmp);
        assert_int_equal(test_sh(tmp, err, sizeof err, "sed -e 's|csv: data/|csv: %s/scenes/data/|' %s > %s", SRC,
                                 scene, path), 0);
        for (int k = 0; sed[k]; k++)
            if (test_sh(tmp, err, sizeof err, "sed -e '%s' %s > %s.next && ! cmp -s %s %s.next && mv %s.next %s", sed[k],
                        path, path, path, path, path, path))
                fail_msg("the edit '%s' no longer changes %s", sed[k], scene);
    }
    snprintf(out, sizeof out, "%s/loop.h5", tmp);
    int rc = test_sh(tmp, err, sizeof err, "%s run %s --model %s -o %s --quiet", DEM, path, model, out);
    if (rc)
        fail_msg("dem run %s --model %s: status %d: %s", path, model, rc, err);
    hid_t f = H5Fopen(out, H5F_ACC_RDONLY, H5P_DEFAULT);
    assert_true(f >= 0);
    long n, m;
    double *strain = series(f, "strain", &n), *stress = series(f, "stress", &m), *kin = series(f, "kinetic", &m);
    double *ela = series(f, "elastic", &m);
    loop_result r = {0};
    r.finite = 1;
    long peak = 0;
    for (long k = 0; k < n; k++) {
        r.finite &= isfinite(strain[k]) && isfinite(stress[k]) && isfinite(kin[k]) && isfinite(ela[k]);
        if (strain[k] > strain[peak])
            peak = k;
        r.max_stress = fmax(r.max_stress, stress[k]);
        r.max_kinetic = fmax(r.max_kinetic, kin[k]);
        r.max_elastic = fmax(r.max_elastic, ela[k]);
    }
    r.peak_strain = strain[peak];
    r.stress_at_peak = stress[peak];
    r.final_strain = strain[n - 1];
    r.final_stress = stress[n - 1];
    /* overlaps in every frame */
    hid_t fr = H5Gopen2(f, "frames", H5P_DEFAULT), pg = H5Gopen2(f, "particles", H5P_DEFAULT);
    long np = h5_count(pg, "radius"), nx = h5_count(fr, "position");
    double *rad = malloc(sizeof(double) * (size_t)np), *x = malloc(sizeof(double) * (size_t)nx);
    assert_int_equal(h5_read(pg, "radius", H5T_NATIVE_DOUBLE, rad, (size_t)np), 0);
    assert_int_equal(h5_read(fr, "position", H5T_NATIVE_DOUBLE, x, (size_t)nx), 0);
    for (long fi = 0; fi < nx / (3 * np); fi++) {
        const double *p = x + fi * 3 * np;
        for (long i = 0; i < np; i++) {
            r.finite &= isfinite(p[3 * i]) && isfinite(p[3 * i + 1]) && isfinite(p[3 * i + 2]);
            for (long j = i + 1; j < np; j++) {
                double dx = p[3 * i] - p[3 * j], dy = p[3 * i + 1] - p[3 * j + 1], dz = p[3 * i + 2] - p[3 * j + 2];
                double ov = rad[i] + rad[j] - sqrt(dx * dx + dy * dy + dz * dz);
                r.max_overlap = fmax(r.max_overlap, ov / (2 * fmin(rad[i], rad[j])));
            }
        }
    }
    H5Gclose(fr), H5Gclose(pg), H5Fclose(f);
    free(strain), free(stress), free(kin), free(ela), free(rad), free(x);
    printf("# %-26s %-18s peak strain %6.2f %%: stress %10.4g Pa (max %10.4g); end: strain %.5f, stress %.3g Pa; "
           "max KE %.3g J, max elastic %.3g J, max overlap %.1f %% of r (%.1f %% of d)\n",
           sed ? "(variant)" : strrchr(scene, '/') + 1, model, 100 * r.peak_strain, r.stress_at_peak, r.max_stress,
           r.final_strain, r.final_stress, r.max_kinetic, r.max_elastic, 200 * r.max_overlap, 100 * r.max_overlap);
    return r;
}

/* Overlap bound: a contact along the axis of a uniaxial strain e is compressed to d/D = e (D the smaller diameter)
 * by geometry alone; settling under gravity and polydispersity add a little. A blow-up exceeds it at once. */
#define OVERLAP_MARGIN 0.03

static void bounded_overlap(loop_result r)
{
    if (!(r.max_overlap < r.peak_strain + OVERLAP_MARGIN))
        fail_msg("largest overlap %.1f %% of the smaller diameter exceeds the peak strain %.1f %% + %.0f %%",
                 100 * r.max_overlap, 100 * r.peak_strain, 100 * OVERLAP_MARGIN);
}

/* mc_stress / mc_strain: the peak stress over classical as docs/multicontact.md's table settles it (the
 * default MC-stress reading, the paper's beta and gamma). The runs are bitwise reproducible on every device; the
 * tolerance covers the table's rounding. Changing the physics means changing both. */
static loop_result hydrogel_514_mc_strain; /* test_hydrogel_514's run, which test_hard_cases compares with */

static loop_result stiffer_and_closed(const char *scene, double mc_stress_ratio, double mc_strain_ratio)
{
    loop_result c = run_loop(scene, NULL, "classical"), s = run_loop(scene, NULL, "mc_stress"),
                e = run_loop(scene, NULL, "mc_strain");
    loop_result all[3] = {c, s, e};
    for (int k = 0; k < 3; k++) {
        assert_true(all[k].finite);
        assert_true(all[k].final_strain < 1e-3);                           /* the piston is back ... */
        assert_true(fabs(all[k].final_stress) < 0.05 * all[k].max_stress); /* ... and the load is gone */
        bounded_overlap(all[k]);
    }
    double rs = s.max_stress / c.max_stress, re = e.max_stress / c.max_stress;
    printf("# peak stress over classical: MC-stress %.4f (table %.4f), MC-strain %.4f (table %.4f)\n", rs,
           mc_stress_ratio, re, mc_strain_ratio);
    assert_true(fabs(rs / mc_stress_ratio - 1) < 0.002);
    assert_true(fabs(re / mc_strain_ratio - 1) < 0.002);
    return e;
}

/* docs/multicontact.md, "peak stress for the packings": classical / MC-strain / default MC-stress */
static void test_hydrogel_514(void **st)
{
    (void)st;
    hydrogel_514_mc_strain = stiffer_and_closed(SRC "/scenes/hydrogel_514.yaml", 195.7 / 145.0, 251.3 / 145.0);
}
static void test_rubber_514(void **st)
{
    (void)st;
    (void)stiffer_and_closed(SRC "/scenes/rubber_514.yaml", 138.6 / 83.8, 120.0 / 83.8);
}
static void test_glass_die(void **st)
{
    (void)st;
    (void)stiffer_and_closed(SRC "/scenes/glass_die.yaml", 39.5 / 35.8, 55.6 / 35.8);
}
static void test_hydrogel_1921(void **st)
{
    (void)st;
    (void)stiffer_and_closed(SRC "/scenes/hydrogel_1921.yaml", 112.8 / 87.16, 133.5 / 87.16);
}

static void stable(loop_result r)
{
    assert_true(r.finite);
    bounded_overlap(r);
    /* bounded: the quasi-static compression never turns into a violent motion with more kinetic than stored energy */
    assert_true(r.max_kinetic < r.max_elastic);
}

static void test_hard_cases(void **st)
{
    (void)st;
    /* 10x the paper's piston speed (2 -> 20 cm/s); the hold and settling times stay */
    const char *const fast[] = {"s/velocity: \\[0, 0, -0.02\\]/velocity: [0, 0, -0.2]/",
                                "s/velocity: \\[0, 0, 0.02\\]/velocity: [0, 0, 0.2]/", "s/duration: 2.65 /duration: 0.75 /",
                                NULL};
    /* the plain scene's run is test_hydrogel_514's (the same bits every time; run again if that test did not run) */
    loop_result plain = hydrogel_514_mc_strain;
    if (!(plain.peak_strain > 0))
        plain = run_loop(SRC "/scenes/hydrogel_514.yaml", NULL, "mc_strain");
    loop_result f1 = run_loop(SRC "/scenes/hydrogel_514.yaml", fast, "mc_strain");
    stable(f1);
    stable(run_loop(SRC "/scenes/hydrogel_514.yaml", fast, "mc_strain_iterated"));
    assert_true(fabs(f1.peak_strain - plain.peak_strain) < 0.005); /* the same strain, reached 10x faster */
    const char *const forty[] = {"s/strain: 0.28/strain: 0.40/g", "s/duration: 2.7 /duration: 3.8 /", NULL};
    loop_result r1 = run_loop(SRC "/scenes/rubber_514.yaml", forty, "mc_stress");
    stable(r1);
    assert_true(r1.peak_strain > 0.39); /* the variant did reach 40 % */
    stable(run_loop(SRC "/scenes/rubber_514.yaml", forty, "mc_strain"));
    /* glass: its scene already runs at the recommended dt (dt_rayleigh 0.2); iterated MC-strain too */
    stable(run_loop(SRC "/scenes/glass_die.yaml", NULL, "mc_strain_iterated"));
}

static int setup(void **st) { (void)st; return test_tmpdir_make(tmp, sizeof tmp, "dem-test-mc"); }
static int teardown(void **st) { (void)st; return test_tmpdir_remove(tmp); }

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hydrogel_514),
        cmocka_unit_test(test_rubber_514),
        cmocka_unit_test(test_glass_die),
        cmocka_unit_test(test_hydrogel_1921),
        cmocka_unit_test(test_hard_cases),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
