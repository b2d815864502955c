/* test_extra_buffer.c - a checkpointed per-particle buffer is its registry line plus where it is first computed.
 *
 * Built against the library compiled with DEM_TEST_EXTRA_BUFFER (Makefile: build/extra/), whose registry
 * (common/dem_buffers.h) has one more line: TEST_EXTRA, an int per particle created from the setup's 0, 1, ..., n - 1
 * (each particle's id of dem_start), moved with its particle (P(1)) and checkpointed as "test_extra". Nothing else
 * in the library names it. On the polydisperse packing of test_util, stored anew along a Morton curve at every
 * rebuild (dem_config.reorder, as tests/test_particle_order.c), the test checks that
 * - the device's buffer followed its particles: at each place it holds the stable id of the particle stored there;
 * - dem_state_get hands it out in the callers' order (element i is i), under its name;
 * - a checkpoint (app/checkpoint.c) writes it as /state/test_extra and reads it back bit for bit;
 * - dem_state_set writes it back: a state whose test_extra was changed reads back changed, bit for bit, in the run
 *   it was saved from and in a fresh run restarted from the checkpoint (stored in id order there). */
#include "test_util.h"
#include "checkpoint.h"
#include "sim.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#ifndef DEM_TEST_EXTRA_BUFFER
#error "tests/test_extra_buffer.c is built against the library compiled with -DDEM_TEST_EXTRA_BUFFER (Makefile)"
#endif

#define STEPS 150

static packing_opts opts(void)
{
    packing_opts o;
    packing_defaults(&o);
    o.side = 6; /* 341 spheres in lattice order, which the Morton order moves almost entirely */
    o.lid_speed = 2.0;
    o.speed = 0.3;
    return o;
}

static dem_config config(const backend_case *bc, int reorder)
{
    dem_config c = cfg_of(bc->backend, bc->precision);
    c.reorder = reorder;
    c.reorder_gain = 1; /* whenever the order changes */
    return c;
}

/* The state's test_extra: n ints */
static int *extra_of(const dem_state *st)
{
    dem_state_array *a = dem_state_find(st, "test_extra");
    assert_non_null(a);
    assert_int_equal(a->elem, DEM_STATE_INT);
    assert_int_equal(a->count, (size_t)st->n);
    assert_non_null(a->data);
    return a->data;
}

static void test_moves_and_checkpoints(void **unused)
{
    (void)unused;
    char path[256], err[4096];
    snprintf(path, sizeof path, "/tmp/test_extra_buffer-%d.h5", (int)getpid());
    FOR_EACH_BACKEND(bc)
    {
        packing_opts o = opts();
        dem_sim *s = packing_build(&o);
        dem_config c = config(bc, 1);
        start_or_fail(s, &c);
        step_or_fail(s, STEPS);
        int n = dem_count(s);
        assert_true(dem_reorder_count(s) > 0);
        /* on the device: the stable id of the particle at each place, and the places are not the ids */
        int e = 0, moved = 0;
        int *raw = sim_buffer_get(s, BUF_TEST_EXTRA, &e);
        assert_int_equal(e, 0);
        for (int k = 0; k < n; k++) {
            if (raw[k] != s->setup.sid[k])
                fail_msg("%s: place %d holds %d, the particle there is %d", bc->name, k, raw[k], s->setup.sid[k]);
            moved += raw[k] != k;
        }
        assert_true(moved > n / 2);
        free(raw);
        /* in the state, in the callers' order */
        dem_state st;
        assert_int_equal(dem_state_get(s, &st), 0);
        int *x = extra_of(&st);
        for (int i = 0; i < n; i++)
            if (x[i] != i)
                fail_msg("%s: the saved test_extra of particle %d is %d", bc->name, i, x[i]);
        /* changed, set, read back: dem_state_set writes it (through the order the particles are stored in) */
        for (int i = 0; i < n; i++)
            x[i] = 7 * i + 3;
        assert_int_equal(dem_state_set(s, &st), 0);
        dem_state again;
        assert_int_equal(dem_state_get(s, &again), 0);
        assert_memory_equal(extra_of(&again), x, sizeof(int) * (size_t)n);
        dem_state_free(&again);
        /* through a checkpoint, into a run that was never stored anew */
        scene sc;
        memset(&sc, 0, sizeof sc);
        sc.path = "tests/test_extra_buffer.c";
        sc.text = "(no scene: a test packing)";
        scene_run run;
        memset(&run, 0, sizeof run);
        assert_int_equal(checkpoint_write(path, s, &sc, &run, err, sizeof err), 0);
        checkpoint ck;
        if (checkpoint_read(path, &ck, err, sizeof err))
            fail_msg("%s: %s", bc->name, err);
        assert_memory_equal(extra_of(&ck.st), x, sizeof(int) * (size_t)n);
        dem_sim *r = packing_build(&o);
        dem_config rc = config(bc, 0);
        start_or_fail(r, &rc);
        assert_int_equal(dem_state_set(r, &ck.st), 0);
        assert_int_equal(dem_state_get(r, &again), 0);
        assert_memory_equal(extra_of(&again), x, sizeof(int) * (size_t)n);
        raw = sim_buffer_get(r, BUF_TEST_EXTRA, &e); /* stored in id order: place i holds particle i's */
        assert_int_equal(e, 0);
        assert_memory_equal(raw, x, sizeof(int) * (size_t)n);
        free(raw);
        /* the rest of the state came along too: both runs go on alike */
        step_or_fail(s, 20);
        step_or_fail(r, 20);
        dem_state a, b;
        assert_int_equal(dem_state_get(s, &a), 0);
        assert_int_equal(dem_state_get(r, &b), 0);
        for (int k = 0; k < a.narrays; k++) {
            const dem_state_array *p = &a.arrays[k], *q = dem_state_find(&b, p->name);
            size_t bytes = p->count * (p->elem == DEM_STATE_REAL ? (size_t)a.real_size : sizeof(int));
            assert_non_null(q);
            if (q->count != p->count || memcmp(p->data, q->data, bytes))
                fail_msg("%s: %s differs after the restart", bc->name, p->name);
        }
        dem_state_free(&a), dem_state_free(&b), dem_state_free(&again), dem_state_free(&st);
        checkpoint_free(&ck);
        unlink(path);
        dem_destroy(r);
        dem_destroy(s);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_moves_and_checkpoints),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
