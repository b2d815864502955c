/* test_mpi_sum.c - the exact sums merged across MPI ranks (host/mpi/mpi_layer.h), run by tests/mpi_check.sh on 1, 2
 * and 3 ranks (mpirun --oversubscribe): the result may not depend on the number of ranks or on how the terms are cut.
 *
 * - 20 000 doubles over 240 binary orders of magnitude with cancelling pairs, cut among the ranks in a scattered way
 *   that differs with the rank count: the merged sum rounded to double is bit for bit fsum_ref's (test_util.c,
 *   Shewchuk's partials, written apart from common/exact_sum.h), and rounded to float it lies within half an ulp of
 *   each format of that double;
 * - a run split by space: the 40 000 spheres of test_wall_forces's tree scene on a floor under a ceiling, each rank
 *   building only the spheres of its slab (other ids, other storage places, other blocks), one step, the walls' exact
 *   sums (sim_wall_sums_exact) merged across the ranks: the bits of the whole scene's wall forces in one process,
 *   on the reference and PoCL, fp64 and fp32.
 * Every verdict is agreed by all ranks (an MPI_MIN of the local verdicts) before it is asserted, and a rank's own
 * failing call ends all ranks (tests/mpi_util.h), so no rank is left waiting in a collective. */
#include "mpi_util.h"
#include "sim.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>


/* term k of the sums: a mantissa from a 64-bit LCG times 2^e, e in [-120, 120); every fourth term cancels the one
 * before it but for its lowest bits */
static double term(long k)
{
    unsigned long long z = 0x9E3779B97F4A7C15ull * (unsigned long long)(k + 1) + 0xD1B54A32D192ED03ull;
    z ^= z >> 29, z *= 0xBF58476D1CE4E5B9ull, z ^= z >> 32;
    double m = (double)(z >> 11) / 9007199254740992.0; /* [0, 1) with 53 bits */
    int e = (int)((z >> 3) % 240) - 120;
    double x = ldexp(m, e) * ((z & 1) ? -1 : 1);
    if (k % 4 == 3)
        x = -term(k - 1) + ldexp(m, e - 60);
    return x;
}

static void test_sums_any_cut(void **st)
{
    (void)st;
    enum { N = 20000 };
    static double x[N];
    exact_acc a[2]; /* the terms as doubles, and as floats */
    exact_clear(&a[0]), exact_clear(&a[1]);
    for (long k = 0; k < N; k++) {
        x[k] = term(k);
        if ((k * 7919 + 13 * size) % size == rank) /* this rank's cut: scattered, and another for each rank count */
            exact_add_double(&a[0], x[k]), exact_add_float(&a[1], (float)x[k]);
    }
    REQUIRE0(dem_mpi_exact_allreduce(MPI_COMM_WORLD, a, 2));
    double got = exact_to_double(&a[0]), want = fsum_ref(x, N);
    static float xf[N];
    static double xd[N];
    for (long k = 0; k < N; k++)
        xf[k] = (float)x[k], xd[k] = xf[k];
    double wantf = fsum_ref(xd, N), gotf = exact_to_float(&a[1]);
    if (rank == 0)
        printf("  %d ranks: sum %.17g (fsum %.17g); of the floats %.9g (fsum %.17g)\n", size, got, want, gotf, wantf);
    int ok = !memcmp(&got, &want, sizeof got) &&
             fabs(gotf - wantf) <= ldexp(1, ilogb(wantf) - 24) + ldexp(1, ilogb(wantf) - 53);
    assert_true(all_ok(ok));
}

/* the tree scene of test_wall_forces.c: sphere i at column i % 200, row i / 200, the 12 000 of lowest index larger
 * and touching the ceiling too; columns [c0, c1) only */
#define TREE_N 40000
#define TREE_BIG 12000
static dem_sim *tree_slab(int c0, int c1)
{
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0, 0, 0});
    for (int i = 0; i < TREE_N; i++) {
        if (i % 200 < c0 || i % 200 >= c1)
            continue;
        double r = i < TREE_BIG ? 0.0015 : 0.001, d = 1e-6 * (1 + (i % 97) / 97.0);
        double x[3] = {0.0032 * (i % 200), 0.0032 * (i / 200), r - d};
        dem_add_particle(s, x, NULL, r, m);
    }
    dem_wall w = {.kind = DEM_WALL_PLANE, .material = m, .point = {0, 0, 0}, .normal = {0, 0, 1}};
    REQUIRE(dem_add_wall(s, &w) >= 0);
    w.point[2] = 0.0029975, w.normal[2] = -1;
    REQUIRE(dem_add_wall(s, &w) >= 0);
    dem_set_domain(s, (double[3]){-0.01, -0.01, -0.01}, (double[3]){0.65, 0.65, 0.02});
    if (dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_WALLS))
        rank_fails(__FILE__, __LINE__, "dem_set_effects", dem_error(s));
    dem_set_dt(s, 1e-11);
    return s;
}

static void test_walls_split_by_space(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    {
        dem_config c = cfg_of(bc->backend, bc->precision);
        dem_sim *whole = tree_slab(0, 200), *part = tree_slab(200 * rank / size, 200 * (rank + 1) / size);
        REQUIRE_SIM(whole, dem_start(whole, &c));
        REQUIRE_SIM(part, dem_start(part, &c));
        REQUIRE_SIM(whole, dem_step(whole, 1));
        REQUIRE_SIM(part, dem_step(part, 1));
        exact_acc a[2 * WP_STRIDE];
        for (int w = 0; w < 2; w++)
            REQUIRE0(sim_wall_sums_exact(part, w, a + w * WP_STRIDE));
        REQUIRE0(dem_mpi_exact_allreduce(MPI_COMM_WORLD, a, 2 * WP_STRIDE));
        int ok = 1;
        for (int w = 0; w < 2; w++) {
            double f[3], fn, got[WP_STRIDE];
            dem_wall_force(whole, w, f);
            dem_wall_normal_force(whole, w, &fn);
            for (int q = 0; q < WP_STRIDE; q++) /* rounded once, to the run's precision */
                got[q] = bc->precision == DEM_FP64 ? exact_to_double(&a[w * WP_STRIDE + q])
                                                   : (double)exact_to_float(&a[w * WP_STRIDE + q]);
            ok &= !memcmp(got, f, sizeof f) && !memcmp(&got[WP_FN], &fn, sizeof fn);
            if (rank == 0 && w == 0)
                printf("  %s, %d ranks: floor %.17g N merged, %.17g N in one process\n", bc->name, size, got[WP_FZ],
                       f[2]);
        }
        assert_true(all_ok(ok));
        dem_destroy(whole);
        dem_destroy(part);
    }
}

MPI_TEST_MAIN(cmocka_unit_test(test_sums_any_cut), cmocka_unit_test(test_walls_split_by_space))
