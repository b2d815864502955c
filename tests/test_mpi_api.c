/* test_mpi_api.c - the library's own split run (include/dem_mpi.h: dem_create_mpi), driven through dem.h's calls
 * alone, as a program would (tests/mpi_check.sh: 1, 2 and 3 ranks). Every rank makes the same set-up twice: once
 * with dem_create_mpi(MPI_COMM_WORLD), split over the ranks, and once with dem_create(), the whole run in this
 * process. The scene: 341 polydisperse spheres (Hertz-Mindlin with friction and damping, gravity) thrown about at
 * up to 1.5 m/s in a box of six walls whose lid comes down, so that particles move several radii and the run is
 * split anew, particles and contact histories migrating (asserted from the physics: some sphere moved further than
 * the half margin that calls for it). After 400 steps, sampled every 40, the split run's series rows, its
 * dem_sample_get, step, time and lid position, the whole state it gathers (every array and every contact with
 * its history and force record) and every public field (dem_get_field, dem_field_bytes) have the one-process run's
 * bits; test_refusals: what a split run refuses, with the
 * same code and words on every rank. Reference fp64 and PoCL fp32. */
#include "mpi_util.h"
#include "dem_mpi.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SIDE 6 /* large spheres on SIDE^3 lattice points, small ones in the (SIDE-1)^3 centres */
#define NTOT (SIDE * SIDE * SIDE + (SIDE - 1) * (SIDE - 1) * (SIDE - 1))
#define RMAX 0.001
#define L (SIDE * 2 * RMAX)
#define STEPS 400
#define EVERY 40
static double px[NTOT][3], pv[NTOT][3], pr[NTOT];

static void make_particles(void) { mixed_lattice(SIDE, RMAX, 1.5, 2718281828ull, px, pv, pr); }

/* the scene into s (made by dem_create or dem_create_mpi): the same calls either way; its time step */
static double build(dem_sim *s)
{
    REQUIRE(s != NULL);
    int mat = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0.5});
    int wmat = dem_add_material(s, &(dem_material){7800, 2e8, 0.3, 0.5, 0.5});
    for (int k = 0; k < NTOT; k++)
        REQUIRE(dem_add_particle(s, px[k], pv[k], pr[k], mat) == k);
    REQUIRE(dem_add_box(s, (double[3]){0, 0, 0}, (double[3]){L, L, L}, wmat) >= 0);
    dem_stage lid = {0.01, {0, 0, -0.2}};
    REQUIRE_SIM(s, dem_set_wall_motion(s, 5, 1, &lid));
    dem_set_gravity(s, (double[3]){0, 0, -9.81});
    REQUIRE_SIM(s, dem_set_domain(s, (double[3]){-0.5 * L, -0.5 * L, -0.5 * L}, (double[3]){1.5 * L, 1.5 * L, 1.5 * L}));
    REQUIRE_SIM(s, dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_DAMPING | DEM_EFFECT_FRICTION |
                                          DEM_EFFECT_GRAVITY | DEM_EFFECT_WALLS));
    dem_time_scales ts;
    REQUIRE_SIM(s, dem_time_scales_get(s, 0, &ts));
    REQUIRE_SIM(s, dem_set_dt(s, ts.recommended_dt));
    return ts.recommended_dt;
}

static int samples_equal(const dem_sample *a, const dem_sample *b, int nw)
{
    return !memcmp(&a->energy, &b->energy, sizeof a->energy) && a->step == b->step && a->time == b->time &&
           !memcmp(&a->mc, &b->mc, sizeof a->mc) && !memcmp(a->wall_pos, b->wall_pos, sizeof(double) * 3 * (size_t)nw) &&
           !memcmp(a->wall_force, b->wall_force, sizeof(double) * 3 * (size_t)nw) &&
           !memcmp(a->wall_normal, b->wall_normal, sizeof(double) * (size_t)nw);
}

static void test_same_bits(void **st)
{
    (void)st;
    make_particles();
    const backend_case *cases[2] = {&backend_cases[0], &backend_cases[0]};
    for (int k = 0; k < BACKEND_CASES; k++) /* the reference in fp64, PoCL in fp32 */
        if (backend_cases[k].backend == DEM_BACKEND_REFERENCE && backend_cases[k].precision == DEM_FP64)
            cases[0] = &backend_cases[k];
        else if (backend_cases[k].backend == DEM_BACKEND_OPENCL && backend_cases[k].precision == DEM_FP32)
            cases[1] = &backend_cases[k];
    for (int c = 0; c < 2; c++) {
        dem_config cfg = cfg_of(cases[c]->backend, cases[c]->precision);
        dem_sim *one = dem_create(), *par = dem_create_mpi(MPI_COMM_WORLD);
        double dt = build(one);
        assert_true(all_ok(build(par) == dt));
        REQUIRE_SIM(one, dem_start(one, &cfg));
        int e = dem_start(par, &cfg);
        if (!all_ok(e == 0) && rank == 0)
            fprintf(stderr, "dem_start of the split run: %s\n", dem_error(par));
        assert_true(all_ok(e == 0));
        dem_sample s1, s2;
        REQUIRE_SIM(one, dem_sample_get(one, &s1));
        REQUIRE_SIM(par, dem_sample_get(par, &s2));
        assert_true(all_ok(samples_equal(&s1, &s2, dem_wall_count(one)))); /* the start's row */
        static unsigned char want[STEPS];
        static dem_sample r1[STEPS / EVERY], r2[STEPS / EVERY];
        for (int k = 0; k < STEPS; k++)
            want[k] = k % EVERY == EVERY - 1;
        REQUIRE_SIM(one, dem_step_sampled(one, STEPS / 2, want, r1));
        REQUIRE_SIM(par, dem_step_sampled(par, STEPS / 2, want, r2));
        REQUIRE_SIM(one, dem_step(one, STEPS / 2 - EVERY));
        REQUIRE_SIM(par, dem_step(par, STEPS / 2 - EVERY));
        REQUIRE_SIM(one, dem_step_sampled(one, EVERY, want + STEPS / 2, r1 + STEPS / EVERY / 2));
        REQUIRE_SIM(par, dem_step_sampled(par, EVERY, want + STEPS / 2, r2 + STEPS / EVERY / 2));
        int rows_ok = 1;
        for (int k = 0; k < STEPS / EVERY / 2 + 1; k++)
            rows_ok &= samples_equal(&r1[k], &r2[k], dem_wall_count(one));
        assert_true(all_ok(rows_ok));
        REQUIRE_SIM(one, dem_sample_get(one, &s1));
        REQUIRE_SIM(par, dem_sample_get(par, &s2));
        assert_true(all_ok(samples_equal(&s1, &s2, dem_wall_count(one))));
        double l1[3], l2[3];
        REQUIRE0(dem_wall_position(one, 5, l1));
        REQUIRE0(dem_wall_position(par, 5, l2));
        assert_true(all_ok(dem_step_index(par) == STEPS && dem_step_index(one) == STEPS &&
                           dem_time(par) == dem_time(one) && !memcmp(l1, l2, sizeof l1) && l2[2] < L));
        dem_state a, b;
        REQUIRE_SIM(one, dem_state_get(one, &a));
        REQUIRE_SIM(par, dem_state_get(par, &b));
        /* the premise of the migration: a sphere moved twice the split's half margin (r_max / 2) */
        const dem_state_array *x = dem_state_find(&a, "x");
        double most = 0;
        for (int k = 0; k < NTOT; k++) {
            double d2 = 0;
            for (int d = 0; d < 3; d++) {
                double v = a.real_size == 8 ? ((const double *)x->data)[3 * k + d]
                                            : ((const float *)x->data)[3 * k + d];
                d2 += (v - px[k][d]) * (v - px[k][d]);
            }
            most = fmax(most, sqrt(d2));
        }
        assert_true(all_ok(most > RMAX && a.npairs > NTOT / 2)); /* moved, and packed: contacts to carry */
        b.rebuilds = a.rebuilds; /* (the gathered state's count is rank 0's part's: its own neighbour rebuilds) */
        int same = states_equal(&a, &b);
        if (!all_ok(same) && rank == 0)
            fprintf(stderr, "%s on %d ranks: the gathered state differs from one process's\n", cases[c]->name, size);
        assert_true(all_ok(same));
        /* the fields a program reads, gathered: sized and valued as one process's */
        const dem_field fields[] = {DEM_FIELD_X, DEM_FIELD_V, DEM_FIELD_W, DEM_FIELD_FORCE, DEM_FIELD_TORQUE,
                                    DEM_FIELD_STRESS, DEM_FIELD_STRESS_TRACE, DEM_FIELD_RADIUS, DEM_FIELD_WALL_FORCE,
                                    DEM_FIELD_WALL_NORMAL_FORCE};
        static double f1[6 * NTOT], f2[6 * NTOT];
        int fields_ok = 1;
        for (size_t k = 0; k < sizeof fields / sizeof fields[0]; k++) {
            size_t bytes = dem_field_bytes(one, fields[k]), m = bytes / (size_t)cases[c]->precision;
            memset(f2, 0xff, sizeof f2);
            REQUIRE_SIM(one, dem_get_field(one, fields[k], f1));
            REQUIRE_SIM(par, dem_get_field(par, fields[k], f2));
            int ok = dem_field_bytes(par, fields[k]) == bytes && !memcmp(f1, f2, sizeof(double) * m) &&
                     (fields[k] != DEM_FIELD_STRESS || m == 6 * NTOT);
            if (!ok && rank == 0)
                fprintf(stderr, "field %d differs (%zu values)\n", (int)fields[k], m);
            fields_ok &= ok;
        }
        assert_true(all_ok(fields_ok));
        if (rank == 0)
            printf("%s, %d rank(s): %d steps, %ld contacts, largest move %.2f r_max: the one-process bits\n",
                   cases[c]->name, size, STEPS, (long)a.npairs, most / RMAX);
        dem_state_free(&a), dem_state_free(&b);
        dem_destroy(one), dem_destroy(par);
    }
}

/* whether s's words are rank 0's on every rank */
static int same_words(const dem_sim *s)
{
    char w[4096];
    snprintf(w, sizeof w, "%s", dem_error(s));
    MPI_Bcast(w, (int)sizeof w, MPI_CHAR, 0, MPI_COMM_WORLD);
    return all_ok(!strcmp(w, dem_error(s)));
}

static void test_refusals(void **st)
{
    (void)st;
    make_particles();
    dem_config cfg = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    /* before the start: a step, as in one process; no estimate that would pack the set-up the parts copy */
    dem_sim *one = dem_create(), *par = dem_create_mpi(MPI_COMM_WORLD);
    build(one), build(par);
    int e1 = dem_step(one, 1), e = dem_step(par, 1);
    assert_true(all_ok(e1 == DEM_ERR_STATE && e == e1 && !strcmp(dem_error(one), "dem_start first") &&
                       !strcmp(dem_error(par), "dem_start first")));
    size_t bytes;
    assert_true(all_ok(dem_memory_estimate(par, &cfg, &bytes) == DEM_ERR_STATE));
    dem_destroy(one);
    REQUIRE_SIM(par, dem_start(par, &cfg));
    /* what reads the started run directly, and what changes the set-up, refused with words */
    dem_contact *cs = NULL;
    long count = 0, np = 0;
    e = dem_contacts_get(par, &cs, &count, &np);
    assert_true(all_ok(e == DEM_ERR_STATE && strstr(dem_error(par), "split over MPI ranks") != NULL));
    assert_true(same_words(par));
    static double xs[3 * NTOT];
    assert_true(all_ok(dem_get_field(par, 5, xs) == DEM_ERR_ARG && same_words(par))); /* the library's own rows */
    assert_true(all_ok(dem_add_particle(par, px[0], pv[0], pr[0], 0) == DEM_ERR_STATE));
    assert_true(all_ok(dem_start(par, &cfg) == DEM_ERR_STATE));
    assert_true(all_ok(dem_sort_particles(par) == DEM_ERR_STATE));
    assert_true(all_ok(dem_step(par, 3) == 0 && dem_step_index(par) == 3)); /* and it still steps */
    /* this rank's part's device records: its rows built (the start's rebuild at least), its device described */
    assert_true(all_ok(dem_rebuild_count(par) > 0 && dem_device_bytes(par) > 0 &&
                       strcmp(dem_describe(par), "not started") != 0));
    dem_destroy(par);
    /* a step that fails (a sphere flies out of the binning domain): the same code, words and step on every rank as
     * one process's, and nothing more of the run afterwards, without a crash */
    one = dem_create(), par = dem_create_mpi(MPI_COMM_WORLD);
    for (int k = 0; k < 2; k++) {
        dem_sim *s = k ? par : one;
        int mat = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0.5});
        for (int i = 0; i < 12; i++)
            dem_add_particle(s, (double[3]){3 * RMAX * i, 0, 0}, (double[3]){i == 11 ? 40.0 : 0, 0, 0}, RMAX, mat);
        REQUIRE_SIM(s, dem_set_domain(s, (double[3]){-2 * RMAX, -2 * RMAX, -2 * RMAX},
                                      (double[3]){36 * RMAX, 2 * RMAX, 2 * RMAX}));
        dem_set_dt(s, 1e-5);
        REQUIRE_SIM(s, dem_start(s, &cfg));
    }
    e1 = dem_step(one, 50), e = dem_step(par, 50);
    assert_true(all_ok(e1 == DEM_ERR_DOMAIN && e == e1 && dem_step_index(par) == dem_step_index(one) &&
                       strstr(dem_error(par), dem_error(one)) != NULL && dem_error_particle(par) == 11 &&
                       same_words(par)));
    if (rank == 0)
        printf("a failed step: at step %ld on every rank, as in one process: %s\n", dem_step_index(par),
               dem_error(par));
    dem_state gs;
    double lid[3];
    assert_true(all_ok(dem_step(par, 1) == DEM_ERR_STATE && dem_state_get(par, &gs) == DEM_ERR_STATE &&
                       dem_sample_get(par, &(dem_sample){0}) == DEM_ERR_STATE && dem_rebuild_count(par) == 0 &&
                       dem_wall_position(par, 0, lid) == DEM_ERR_ARG));
    dem_destroy(one), dem_destroy(par);
    /* a scene dem_start refuses: the same code on every rank, with one process's words */
    one = dem_create();
    par = dem_create_mpi(MPI_COMM_WORLD);
    build(one), build(par);
    dem_set_dt(one, 1e-3), dem_set_dt(par, 1e-3); /* far above the stability bound */
    e1 = dem_start(one, &cfg);
    int e2 = dem_start(par, &cfg);
    assert_true(all_ok(e1 == DEM_ERR_DT && e2 == e1 && strstr(dem_error(par), dem_error(one)) != NULL));
    if (rank == 0)
        printf("refused as one process refuses it: %s\n", dem_error(par));
    dem_destroy(one), dem_destroy(par);
    /* fewer particles than ranks: no rank left without its share */
    par = dem_create_mpi(MPI_COMM_WORLD);
    int mat = dem_add_material(par, &(dem_material){2500, 1e7, 0.3, 0.5, 0.5});
    dem_add_particle(par, (double[3]){0, 0, 0}, (double[3]){0, 0, 0}, RMAX, mat);
    dem_set_dt(par, 1e-7);
    e = dem_start(par, &cfg);
    assert_true(all_ok(size == 1 ? e == 0 : e == DEM_ERR_ARG && strstr(dem_error(par), "cannot be split") != NULL));
    dem_destroy(par);
}

MPI_TEST_MAIN(cmocka_unit_test(test_same_bits), cmocka_unit_test(test_refusals))
