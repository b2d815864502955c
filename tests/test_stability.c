/* test_stability.c - hard cases of issue 13 that need a whole packing (the short versions; test_hard_cases.c has the
 * two-particle ones).
 *
 * Size ratio 20:1 (hard case 2): 60 coarse spheres (r 2 mm) and 4000 fines (r 0.1 mm) placed at random in a box and
 * set flying at 0.5 m/s, so that fines hit coarse spheres, fines and walls. The binning cells are sized by the coarse
 * spheres, so each holds hundreds of fines: after 1500 steps every touching pair the library counts from its
 * neighbour rows (dem_energy) must be one a brute-force search over all pairs finds, and none missing, on every
 * backend and precision, and OpenCL has the reference's bits. (Its cost against a monodisperse packing belongs to
 * `make bench`, not to a timed test.) */
#include "test_util.h"
#include "scene.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char size_ratio_scene[] =
    "name: size ratio 20\n"
    "precision: fp64\n"
    "effects: [hertz, damping, friction, walls]\n"
    "materials:\n"
    "  - {name: grain, density: 2500, young: 1.0e7, poisson: 0.3, restitution: 0.5, friction: 0.4}\n"
    "particles:\n"
    "  - material: grain\n"
    "    generate: {kind: random, shape: box, region: {lo: [0, 0, 0], hi: [0.02, 0.02, 0.02]}, radius: 0.002, "
    "count: 60, speed: 0.5, seed: 1}\n"
    "  - material: grain\n"
    "    generate: {kind: random, shape: box, region: {lo: [0, 0, 0], hi: [0.02, 0.02, 0.02]}, radius: 0.0001, "
    "count: 4000, speed: 0.5, seed: 2}\n"
    "walls:\n"
    "  - {type: box, material: grain, lo: [0, 0, 0], hi: [0.02, 0.02, 0.02]}\n"
    "time: {dt_rayleigh: 0.2, duration: 1.0}\n";

static dem_sim *size_ratio_build(dem_precision p)
{
    char err[4096];
    scene *sc = scene_load_text("size_ratio.yaml", size_ratio_scene, sizeof size_ratio_scene - 1, err, sizeof err);
    if (!sc)
        fail_msg("%s", err);
    scene_run run;
    dem_sim *s = scene_build(sc, &run, err, sizeof err);
    if (!s)
        fail_msg("%s", err);
    scene_free(sc);
    (void)p;
    return s;
}

/* touching pairs by brute force over all pairs (overlap > 0, as dem_energy counts them), coarse-fine ones apart */
static long brute_pairs(dem_sim *s, long *mixed)
{
    int n = dem_count(s);
    double *x = malloc(sizeof(double) * 3 * n);
    assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
    long c = 0;
    *mixed = 0;
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++) {
            double d[3] = {x[3 * i] - x[3 * j], x[3 * i + 1] - x[3 * j + 1], x[3 * i + 2] - x[3 * j + 2]};
            double rs = dem_particle_radius(s, i) + dem_particle_radius(s, j);
            if (rs - sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) > 0) {
                c++;
                *mixed += dem_particle_radius(s, i) != dem_particle_radius(s, j);
            }
        }
    free(x);
    return c;
}

static void test_size_ratio(void **st)
{
    (void)st;
    for (int p = 0; p < 2; p++) {
        dem_precision prec = p ? DEM_FP64 : DEM_FP32;
        dem_sim *cl = size_ratio_build(prec), *ref = size_ratio_build(prec);
        dem_config c = cfg_of(DEM_BACKEND_OPENCL, prec), rc = cfg_of(DEM_BACKEND_REFERENCE, prec);
        start_or_fail(cl, &c);
        start_or_fail(ref, &rc);
        long seen = 0;
        for (int k = 0; k < 3; k++) {
            step_or_fail(cl, 500);
            dem_energy_t e;
            assert_int_equal(dem_energy(cl, &e), 0);
            long mixed, brute = brute_pairs(cl, &mixed);
            printf("  %s, step %ld: %ld touching pairs from the rows, %ld by brute force (%ld coarse-fine), %ld wall "
                   "contacts, %d rebuilds so far, %d cells\n",
                   p ? "fp64" : "fp32", dem_step_index(cl), e.contacts, brute, mixed, e.wall_contacts,
                   (int)dem_rebuild_count(cl), dem_cell_count(cl));
            assert_int_equal(e.contacts, brute);
            seen += mixed;
        }
        assert_true(seen > 0); /* fines did meet coarse spheres */
        step_or_fail(ref, 1500);
        char msg[256];
        if (state_diff(cl, ref, msg, sizeof msg))
            fail_msg("OpenCL vs reference: %s", msg);
        dem_destroy(cl);
        dem_destroy(ref);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_size_ratio)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
