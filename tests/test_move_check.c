/* test_move_check.c - the check of the moves of a run split over MPI ranks, on the device (common/halo.h move_mark,
 * move_check; host/core/part.c sim_move_check; host/mpi/split.c splits anew when it passes half the halo's margin).
 * A rank's part reads back two reals per block of particles, not every position; these tests hold it to what the
 * host computed from every position before (the positions read by dem_get_field, the distances in the run's
 * precision), in one process (no MPI: a run with some particles marked as ghosts is a part as far as the check goes).
 *
 * A packing of 559 polydisperse spheres (three blocks of the check's) thrown about in a box whose lid comes down, stored anew at every neighbour
 * rebuild (so the device's copies of the marked positions must follow their particles), on the reference and PoCL in
 * fp64 and fp32: marked at the start, then after each of 40 calls of 5 steps but the 21st (which marks anew) the
 * check's two values are compared, bitwise, with the largest distance from the marked positions and the largest move since the last call computed on
 * the host over the own particles. Every third particle is a ghost, and the fastest particle of the packing is made a
 * ghost too, so that leaving the ghosts out changes the answer (asserted). A mark mid-run starts the distances
 * again. A NaN position of an own particle comes back as a NaN; of a ghost, not at all. A run without ghosts refuses
 * the check. */
#include "test_util.h"
#include "sim.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { CALLS = 40, PER_CALL = 5 };

/* the distance between a and b in the run's precision (fp32: float arithmetic, as the device's) */
static double dist(const double *a, const double *b, int fp32)
{
    if (fp32) {
        float dx = (float)a[0] - (float)b[0], dy = (float)a[1] - (float)b[1], dz = (float)a[2] - (float)b[2];
        return (double)sqrtf(dx * dx + dy * dy + dz * dz);
    }
    double dx = a[0] - b[0], dy = a[1] - b[1], dz = a[2] - b[2];
    return sqrt(dx * dx + dy * dy + dz * dz);
}

/* the largest distances over the particles with ghost[k] == 0 (all: every one), as the device keeps a NaN */
static void host_check(int n, const double *x, const double *x0, const double *prev, const unsigned char *ghost,
                       int all, int fp32, double out[2])
{
    out[0] = out[1] = 0;
    for (int k = 0; k < n; k++)
        if (all || !ghost[k]) {
            double d = dist(x + 3 * k, x0 + 3 * k, fp32), st = dist(x + 3 * k, prev + 3 * k, fp32);
            out[0] = d > out[0] || d != d ? d : out[0];
            out[1] = st > out[1] || st != st ? st : out[1];
        }
}

static dem_sim *build(const backend_case *bc, unsigned char **ghost, int *n)
{
    packing_opts o;
    packing_defaults(&o);
    o.side = 7; /* 559 spheres: three blocks of DEM_REDUCE_BLOCK, the last partial */
    o.speed = 0.5;
    o.lid_speed = 0.02;
    o.gravity = 1;
    o.seed = 11;
    o.effects = DEM_EFFECT_CLASSICAL;
    dem_sim *s = packing_build(&o);
    *n = dem_count(s);
    const double *v = s->v; /* the set-up's velocities */
    *ghost = calloc((size_t)*n, 1);
    assert_non_null(*ghost);
    int fast = 0;
    for (int k = 0; k < *n; k++) {
        (*ghost)[k] = k % 3 == 1;
        if (v[3 * k] * v[3 * k] + v[3 * k + 1] * v[3 * k + 1] + v[3 * k + 2] * v[3 * k + 2] >
            v[3 * fast] * v[3 * fast] + v[3 * fast + 1] * v[3 * fast + 1] + v[3 * fast + 2] * v[3 * fast + 2])
            fast = k;
    }
    (*ghost)[fast] = 1;
    assert_int_equal(sim_set_ghosts(s, *ghost), 0);
    dem_config c = cfg_of(bc->backend, bc->precision);
    c.reorder = 1, c.reorder_gain = 1; /* stored anew at every rebuild where the order changes */
    if (dem_start(s, &c))
        fail_msg("%s: %s", bc->name, dem_error(s));
    return s;
}

static void test_against_host(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc) {
        int n, fp32 = bc->precision == DEM_FP32, differs = 0;
        unsigned char *ghost;
        dem_sim *s = build(bc, &ghost, &n);
        double *x = malloc(sizeof(double) * 3 * (size_t)n), *x0 = malloc(sizeof(double) * 3 * (size_t)n),
               *prev = malloc(sizeof(double) * 3 * (size_t)n), dev[2], host[2], every[2];
        assert_non_null(x), assert_non_null(x0), assert_non_null(prev);
        assert_int_equal(sim_move_check(s, 1, dev), 0);
        assert_true(dev[0] == 0 && dev[1] == 0);
        assert_int_equal(dem_get_field(s, DEM_FIELD_X, x0), 0);
        memcpy(prev, x0, sizeof(double) * 3 * (size_t)n);
        long reorders0 = dem_reorder_count(s);
        for (int call = 0; call < CALLS; call++) {
            if (dem_step(s, PER_CALL))
                fail_msg("%s: %s", bc->name, dem_error(s));
            if (call == CALLS / 2) { /* marked anew: distances from here on */
                assert_int_equal(sim_move_check(s, 1, dev), 0);
                assert_int_equal(dem_get_field(s, DEM_FIELD_X, x0), 0);
                memcpy(prev, x0, sizeof(double) * 3 * (size_t)n);
                continue;
            }
            assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
            if (sim_move_check(s, 0, dev))
                fail_msg("%s: %s", bc->name, dem_error(s));
            host_check(n, x, x0, prev, ghost, 0, fp32, host);
            host_check(n, x, x0, prev, ghost, 1, fp32, every);
            if (dev[0] != host[0] || dev[1] != host[1])
                fail_msg("%s, call %d: the device's check %.17g %.17g, the host's %.17g %.17g", bc->name, call,
                         dev[0], dev[1], host[0], host[1]);
            assert_true(host[0] > 0 && host[1] > 0);
            differs += every[0] != host[0] || every[1] != host[1];
            memcpy(prev, x, sizeof(double) * 3 * (size_t)n);
        }
        /* the particles were stored anew under the check's copies, and the ghosts' moves were left out */
        assert_true(dem_reorder_count(s) - reorders0 >= 3);
        assert_true(differs > 0);

        /* a NaN: a ghost's is not seen, an own particle's is */
        int g = 1, own = 0;
        while (ghost[own])
            own++;
        assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
        x[3 * g] = NAN;
        assert_int_equal(sim_set_field(s, DEM_FIELD_X, x), 0);
        assert_int_equal(sim_move_check(s, 0, dev), 0);
        assert_false(isnan(dev[0]) || isnan(dev[1]));
        x[3 * own + 2] = NAN;
        assert_int_equal(sim_set_field(s, DEM_FIELD_X, x), 0);
        assert_int_equal(sim_move_check(s, 0, dev), 0);
        assert_true(isnan(dev[0]) && isnan(dev[1]));
        free(x), free(x0), free(prev), free(ghost);
        dem_destroy(s);
    }
}

static void test_refused_without_ghosts(void **st)
{
    (void)st;
    packing_opts o;
    packing_defaults(&o);
    o.side = 3;
    dem_sim *s = packing_build(&o);
    double out[2] = {1, 1};
    assert_int_equal(sim_move_check(s, 1, out), DEM_ERR_STATE); /* not started */
    dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    assert_int_equal(dem_start(s, &c), 0);
    assert_int_equal(sim_move_check(s, 0, out), DEM_ERR_STATE); /* no ghosts: not a part */
    assert_non_null(strstr(dem_error(s), "split run"));
    assert_true(out[0] == 0 && out[1] == 0);
    dem_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_against_host),
        cmocka_unit_test(test_refused_without_ghosts),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
