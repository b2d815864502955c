/* test_state.c - the checkpoint state (host/core/state.c): a saved state restores bit for bit, and one that does not fit
 * the run is refused and changes nothing (checked before any device state is kept). */
#include "test_util.h"
#include <stdlib.h>
#include <string.h>

static dem_sim *frictional_box(void)
{
    packing_opts o;
    packing_defaults(&o);
    o.side = 4;
    o.lid_speed = 0.2;
    return packing_build(&o);
}

/* A: stepped 40, state saved, stepped 40 more. B: started, given A's saved state, stepped 40: A and B agree bitwise. */
static void test_restore_bitwise(void **st)
{
    (void)st;
    dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    dem_sim *a = frictional_box(), *b = frictional_box();
    start_or_fail(a, &c);
    start_or_fail(b, &c);
    step_or_fail(a, 40);
    dem_state saved;
    assert_int_equal(dem_state_get(a, &saved), 0);
    assert_true(saved.npairs > 0);
    assert_int_equal(dem_state_set(b, &saved), 0);
    step_or_fail(a, 40);
    step_or_fail(b, 40);
    char msg[512];
    if (state_diff(a, b, msg, sizeof msg))
        fail_msg("restored run differs: %s", msg);
    dem_state_free(&saved);
    dem_destroy(a);
    dem_destroy(b);
}

/* The frictional box under lagged MC-strain (mc: 1) or the classical law */
static dem_sim *box_of(int mc)
{
    if (!mc)
        return frictional_box();
    packing_opts o;
    packing_defaults(&o);
    o.side = 4;
    o.lid_speed = 0.2;
    o.effects = DEM_EFFECT_CLASSICAL | DEM_EFFECT_MC_STRAIN;
    o.mc_beta = 1.65;
    o.mc_gamma = 1.12;
    return packing_build(&o);
}

/* The contact network right after a restore is the saved run's at that step, bit for bit, on every backend and
 * under MC-strain (its induced displacements are the network's extra): the restore runs no force pass (it would
 * advance the springs), so the pairs' force records, the kept wall forces and MC-strain's displacements travel in
 * the state. Without them the network would read records of another pair numbering (a --restart run's first
 * frame). */
static void network_after_restore(const backend_case *bc, int mc)
{
    dem_config c = cfg_of(bc->backend, bc->precision);
    c.contacts = 1;
    dem_sim *a = box_of(mc), *b = box_of(mc);
    start_or_fail(a, &c);
    start_or_fail(b, &c);
    step_or_fail(a, 40);
    step_or_fail(b, 7); /* b's own records and rows are of another state */
    dem_state saved;
    assert_int_equal(dem_state_get(a, &saved), 0);
    assert_non_null(saved.pair_rec);
    assert_int_equal(dem_state_set(b, &saved), 0);
    dem_contact *ca, *cb;
    long na, nb, pa, pb;
    assert_int_equal(dem_contacts_get(a, &ca, &na, &pa), 0);
    assert_int_equal(dem_contacts_get(b, &cb, &nb, &pb), 0);
    assert_true(pa > 10);
    assert_int_equal(na, nb);
    assert_int_equal(pa, pb);
    int moved = 0;
    for (long k = 0; k < na; k++) {
        if (ca[k].i != cb[k].i || ca[k].j != cb[k].j || memcmp(&ca[k].overlap, &cb[k].overlap, sizeof(double)) ||
            memcmp(ca[k].fn, cb[k].fn, sizeof ca[k].fn) || memcmp(ca[k].ft, cb[k].ft, sizeof ca[k].ft) ||
            memcmp(ca[k].point, cb[k].point, sizeof ca[k].point) ||
            memcmp(ca[k].extra, cb[k].extra, sizeof ca[k].extra))
            fail_msg("%s%s: contact %ld (%d-%d) differs after the restore: normal force %.17g against %.17g, extra "
                     "%.17g against %.17g",
                     bc->name, mc ? ", MC-strain" : "", k, ca[k].i, ca[k].j, ca[k].fn[2], cb[k].fn[2], ca[k].extra[0],
                     cb[k].extra[0]);
        moved |= ca[k].extra[0] != 0;
    }
    assert_true(moved == mc); /* MC-strain's displacements were at work, and only there */
    free(ca), free(cb);
    dem_state_free(&saved);
    dem_destroy(a);
    dem_destroy(b);
}

static void test_restore_keeps_contact_network(void **st)
{
    (void)st;
    for (int mc = 0; mc < 2; mc++)
        FOR_EACH_BACKEND(bc) network_after_restore(bc, mc);
}

/* Saved states that cannot belong to the run: refused with DEM_ERR_ARG, and the run goes on exactly as a twin that
 * was never offered them. */
static void test_unfit_state_changes_nothing(void **st)
{
    (void)st;
    dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    dem_sim *a = frictional_box(), *twin = frictional_box();
    start_or_fail(a, &c);
    start_or_fail(twin, &c);
    step_or_fail(a, 30);
    step_or_fail(twin, 30);
    dem_state saved;
    assert_int_equal(dem_state_get(a, &saved), 0);
    int n = saved.n;
    /* 1: a contact between particles out of range (checked before anything is written) */
    int keep_i = saved.pair_i[0], keep_j = saved.pair_j[0];
    saved.pair_j[0] = n + 5;
    assert_int_equal(dem_state_set(a, &saved), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(a), "want 0 <= i < j <"));
    /* 1b: more arrays than a state holds (an array count read from a damaged file): refused before any is read */
    int keep_narrays = saved.narrays;
    saved.narrays = DEM_STATE_MAX_ARRAYS + 1;
    assert_int_equal(dem_state_set(a, &saved), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(a), "arrays (at most"));
    saved.narrays = keep_narrays;
    /* 2: a contact between particles that are far apart in the saved positions (found only after the rows of those
     * positions are built: the run's own come back). The saved positions are moved so that the state differs from
     * the run's in every particle. */
    saved.pair_i[0] = keep_i, saved.pair_j[0] = keep_j;
    double *x = dem_state_find(&saved, "x")->data; /* fp64 */
    for (int i = 0; i < n; i++)
        x[3 * i] += 1e-5;
    int far = -1;
    for (int j = 1; j < n && far < 0; j++) {
        double dx = x[3 * j] - x[0], dy = x[3 * j + 1] - x[1], dz = x[3 * j + 2] - x[2];
        if (dx * dx + dy * dy + dz * dz > 0.01 * 0.01)
            far = j;
    }
    assert_true(far > 0);
    saved.pair_i[0] = 0, saved.pair_j[0] = far;
    assert_int_equal(dem_state_set(a, &saved), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(a), "is not a neighbour pair of the saved positions"));
    char msg[512];
    if (state_diff(a, twin, msg, sizeof msg))
        fail_msg("a refused state changed the run: %s", msg);
    step_or_fail(a, 30);
    step_or_fail(twin, 30);
    if (state_diff(a, twin, msg, sizeof msg))
        fail_msg("after a refused state the run went on differently: %s", msg);
    assert_int_equal(dem_step_index(a), dem_step_index(twin));
    dem_state_free(&saved);
    dem_destroy(a);
    dem_destroy(twin);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_restore_bitwise),
        cmocka_unit_test(test_restore_keeps_contact_network),
        cmocka_unit_test(test_unfit_state_changes_nothing),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
