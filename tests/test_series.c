/* test_series.c - series rows taken on the device (dem_step_sampled, common/series.h).
 *
 * A settling polydisperse packing with gravity, friction and a moving lid in a box of six walls, sampled every step
 * for 100 steps, then every 7th, with more rows than the device's ring holds (so it wraps), on every backend and
 * precision, with the wall forces kept (samples every step) and not kept. Checked against the same run stepped one
 * step at a time and sampled on the host (dem_sample_get, which computes in double from the state):
 *   - sampling leaves the run's bits alone (state_diff of the two runs);
 *   - each row's wall forces are bitwise those the device summed in that step, its step, time and wall positions equal;
 *   - contact counts equal, energies within a few roundoffs of the precision (the device sums each particle's terms
 *     in the run's precision, the host from positions widened to double);
 * and the rows of the OpenCL device are bitwise the reference's. Sampled every step, the pairs' elastic energies come
 * from contact_pairs (DEM_KEEP_PAIR_ENERGY), otherwise contact_forces computes them: the rows are bitwise the same,
 * under the classical law and under MC-strain (whose force is at the induced overlap, not at the geometric one). */
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define STEPS 300

static int settling_mc_strain; /* 1: the same packing under lagged MC-strain with a contact reach of 1.1 */

static dem_sim *settling(void)
{
    packing_opts o;
    packing_defaults(&o);
    o.side = 5;
    o.gravity = 1;
    o.friction = 0.4;
    o.speed = 0.05;
    o.lid_speed = 0.05;
    o.effects = DEM_EFFECT_CLASSICAL | DEM_EFFECT_FRICTION | DEM_EFFECT_GRAVITY;
    if (settling_mc_strain) {
        o.effects |= DEM_EFFECT_MC_STRAIN;
        o.mc_beta = 1.65;
        o.mc_gamma = 1.12;
        o.mc_reach = 1.1;
    }
    return packing_build(&o);
}

static void want_pattern(unsigned char *want)
{
    for (int k = 0; k < STEPS; k++)
        want[k] = k < 100 || k % 7 == 3 || k == STEPS - 1;
}

/* the rows of a run sampled on the device; returns the simulation (to compare states) */
static dem_sim *sampled_run(const dem_config *c, dem_sample *rows, long *nrows)
{
    unsigned char want[STEPS];
    want_pattern(want);
    dem_sim *s = settling();
    start_or_fail(s, c);
    long first = 0;
    *nrows = 0;
    for (int k = 0; k < STEPS; k++) {
        *nrows += want[k];
        first += k < 150 && want[k];
    }
    /* two calls, the second starting inside the pattern */
    if (dem_step_sampled(s, 150, want, rows) || dem_step_sampled(s, STEPS - 150, want + 150, rows + first))
        fail_msg("dem_step_sampled: %s", dem_error(s));
    return s;
}

static double rel(double a, double b) { return fabs(a - b) / fmax(fabs(b), 1e-300); }

static void check_case(const backend_case *bc, long sample_every, dem_sample *rows_out, long *nrows)
{
    dem_config c = cfg_of(bc->backend, bc->precision);
    c.sample_every = sample_every;
    static dem_sample rows[STEPS];
    dem_sim *s = sampled_run(&c, rows, nrows);
    assert_true(*nrows > 2 * 64); /* the ring (DEM_SERIES_RING = 64 rows here, common/dem_layout.h) wraps */
    unsigned char want[STEPS];
    want_pattern(want);
    dem_sim *h = settling();
    start_or_fail(h, &c);
    int nw = dem_wall_count(h), r = 0;
    double worst[3] = {0, 0, 0};
    for (int k = 0; k < STEPS; k++) {
        step_or_fail(h, 1);
        if (!want[k])
            continue;
        dem_sample hs;
        if (dem_sample_get(h, &hs))
            fail_msg("dem_sample_get: %s", dem_error(h));
        const dem_sample *d = &rows[r++];
        assert_int_equal(d->step, hs.step);
        assert_true(d->time == hs.time);
        assert_memory_equal(d->wall_force, hs.wall_force, sizeof(double) * 3 * nw);
        assert_memory_equal(d->wall_normal, hs.wall_normal, sizeof(double) * nw);
        assert_memory_equal(d->wall_pos, hs.wall_pos, sizeof(double) * 3 * nw);
        assert_int_equal(d->energy.contacts, hs.energy.contacts);
        assert_int_equal(d->energy.wall_contacts, hs.energy.wall_contacts);
        double e[3] = {rel(d->energy.kinetic, hs.energy.kinetic), rel(d->energy.potential, hs.energy.potential),
                       hs.energy.elastic > 0 ? rel(d->energy.elastic, hs.energy.elastic) : d->energy.elastic};
        for (int q = 0; q < 3; q++)
            worst[q] = fmax(worst[q], e[q]);
    }
    assert_int_equal(r, *nrows);
    char msg[256];
    if (state_diff(s, h, msg, sizeof msg))
        fail_msg("%s: sampling changed the run: %s", bc->name, msg);
    printf("  %s, sample_every %ld: %ld rows; largest relative difference from the host's double: kinetic %.2g, "
           "potential %.2g, elastic %.2g (%.0f, %.0f, %.0f roundoffs)\n",
           bc->name, sample_every, *nrows, worst[0], worst[1], worst[2], worst[0] / bc->eps, worst[1] / bc->eps,
           worst[2] / bc->eps);
    /* the energies of motion and the sums: a few roundoffs. The elastic energy goes as the overlap^(5/2), and an
     * overlap is a difference of positions 1e3-1e5 times larger (this packing barely touches), so in the run's
     * precision it carries that many roundoffs: 1e4 of them in fp64 (2e-12), 1 % in fp32, where the force law's own
     * overlaps are no better */
    assert_true(worst[0] < 64 * bc->eps && worst[1] < 64 * bc->eps);
    assert_true(worst[2] < (bc->precision == DEM_FP64 ? 1e4 * bc->eps : 1e-2));
    memcpy(rows_out, rows, sizeof(dem_sample) * (size_t)*nrows);
    dem_destroy(s);
    dem_destroy(h);
}

static void test_series_rows(void **st)
{
    (void)st;
    static dem_sample ref_rows[STEPS], rows[STEPS];
    for (int keep = 0; keep < 2; keep++)
        for (int p = 0; p < 2; p++) {
            long nref = 0, n = 0;
            const backend_case *ref = NULL, *cl = NULL;
            FOR_EACH_BACKEND(bc)
            if (bc->precision == (p ? DEM_FP64 : DEM_FP32))
                *(bc->backend == DEM_BACKEND_REFERENCE ? &ref : &cl) = bc;
            check_case(ref, keep ? 1 : 0, ref_rows, &nref);
            check_case(cl, keep ? 1 : 0, rows, &n);
            assert_int_equal(n, nref);
            for (long k = 0; k < n; k++) { /* field by field: the struct's padding is not compared */
                assert_memory_equal(&rows[k].energy.kinetic, &ref_rows[k].energy.kinetic, sizeof(double));
                assert_memory_equal(&rows[k].energy.potential, &ref_rows[k].energy.potential, sizeof(double));
                assert_memory_equal(&rows[k].energy.elastic, &ref_rows[k].energy.elastic, sizeof(double));
                assert_int_equal(rows[k].energy.contacts, ref_rows[k].energy.contacts);
                assert_memory_equal(rows[k].wall_force, ref_rows[k].wall_force, sizeof rows[k].wall_force);
                assert_memory_equal(rows[k].wall_normal, ref_rows[k].wall_normal, sizeof rows[k].wall_normal);
            }
        }
}

/* Rows sampled every step (pair energies kept by contact_pairs) against the same rows sampled without keeping them
 * (sample_every 0: contact_forces computes each pair's energy from its overlap), field for field, on every backend and
 * precision, classical and MC-strain. */
static void test_series_kept_energy(void **st)
{
    (void)st;
    static dem_sample kept[STEPS], computed[STEPS];
    for (int mc = 0; mc < 2; mc++) {
        settling_mc_strain = mc;
        FOR_EACH_BACKEND(bc) {
            dem_config c = cfg_of(bc->backend, bc->precision);
            long n0 = 0, n1 = 0;
            c.sample_every = 0;
            dem_sim *a = sampled_run(&c, computed, &n0);
            c.sample_every = 1;
            dem_sim *b = sampled_run(&c, kept, &n1);
            assert_int_equal(n0, n1);
            long touching = 0;
            for (long k = 0; k < n0; k++) {
                assert_memory_equal(&kept[k].energy.elastic, &computed[k].energy.elastic, sizeof(double));
                assert_memory_equal(&kept[k].energy.kinetic, &computed[k].energy.kinetic, sizeof(double));
                assert_int_equal(kept[k].energy.contacts, computed[k].energy.contacts);
                touching += kept[k].energy.contacts;
            }
            printf("  %s%s: %ld rows, %ld pair contacts in them, kept and computed energies the same bits\n", bc->name,
                   mc ? ", MC-strain" : "", n0, touching);
            assert_true(touching > 2 * n0); /* the energies compared are those of hundreds of contacts */
            dem_destroy(a);
            dem_destroy(b);
        }
    }
    settling_mc_strain = 0;
}

/* A call that samples nothing is dem_step; one that asks for rows without room for them is refused. */
static void test_series_arguments(void **st)
{
    (void)st;
    dem_sim *a = settling(), *b = settling();
    dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    start_or_fail(a, &c);
    start_or_fail(b, &c);
    unsigned char none[20] = {0}, one[20] = {0};
    one[19] = 1;
    assert_int_equal(dem_step_sampled(a, 20, none, NULL), 0);
    assert_int_equal(dem_step_sampled(a, 20, NULL, NULL), 0);
    step_or_fail(b, 40);
    char msg[256];
    if (state_diff(a, b, msg, sizeof msg))
        fail_msg("%s", msg);
    assert_int_equal(dem_step_sampled(a, 20, one, NULL), DEM_ERR_ARG);
    dem_destroy(a);
    dem_destroy(b);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_series_rows), cmocka_unit_test(test_series_kept_energy),
                                       cmocka_unit_test(test_series_arguments)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
