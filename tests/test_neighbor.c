/* test_neighbor.c - the neighbour-row kernels (common/neighbor.h) against their reference twins and against a
 * brute-force O(n^2) search: row i holds exactly the j != i with |x_i - x_j| < r_i + r_j + skin at the last build
 * (evaluated in the run precision with the kernel's operation order), sorted ascending and symmetric. The packing
 * starts with rows of capacity 16, so the large skins also exercise the overflow-and-grow path. fp32 and fp64, a small
 * and a large skin each, and the automatic one (dem_config.skin 0: chosen at each rebuild), which must also leave the
 * bits of a run with a fixed skin, shrink on a packing at rest and stay larger where the particles move. */
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* brute-force membership in the run precision T */
#define IN_RANGE(T, x, rad, skin, i, j)                                                                              \
    ({                                                                                                               \
        const T *X_ = (const T *)(x);                                                                                \
        T d0 = X_[3 * (i)] - X_[3 * (j)], d1 = X_[3 * (i) + 1] - X_[3 * (j) + 1], d2 = X_[3 * (i) + 2] - X_[3 * (j) + 2]; \
        T cut = (T)(rad)[i] + (T)(rad)[j] + (T)(skin);                                                               \
        d0 * d0 + d1 * d1 + d2 * d2 < cut * cut;                                                                     \
    })

static void check(dem_precision prec, double cfg_skin, long steps)
{
    packing_opts o;
    packing_defaults(&o);
    o.side = 8;
    dem_config rc = cfg_of(DEM_BACKEND_REFERENCE, prec), c = cfg_of(DEM_BACKEND_OPENCL, prec);
    rc.skin = c.skin = cfg_skin;
    dem_sim *ref, *cl;
    packing_pair(&o, &rc, &c, steps, &ref, &cl);
    double skin = dem_neighbor_skin(ref); /* the rows' skin: the one given, or the automatic one's choice */
    assert_true(skin == dem_neighbor_skin(cl));
    if (cfg_skin > 0)
        assert_true(skin == cfg_skin);
    int n = dem_count(ref), m = dem_neighbor_capacity(ref); /* slots of all rows together: they are packed */
    assert_int_equal(m, dem_neighbor_capacity(cl));
    int *c1 = malloc(sizeof(int) * n), *c2 = malloc(sizeof(int) * n);
    int *s1 = malloc(sizeof(int) * (n + 1)), *s2 = malloc(sizeof(int) * (n + 1));
    int *l1 = malloc(sizeof(int) * m), *l2 = malloc(sizeof(int) * m);
    double *rad = malloc(sizeof(double) * n);
    size_t bytes = dem_field_bytes(ref, DEM_FIELD_X_BUILD);
    void *xb = malloc(bytes);
    assert_int_equal(dem_get_raw(ref, DEM_FIELD_NBR_COUNT, c1, sizeof(int) * n), 0);
    assert_int_equal(dem_get_raw(cl, DEM_FIELD_NBR_COUNT, c2, sizeof(int) * n), 0);
    assert_int_equal(dem_get_raw(ref, DEM_FIELD_NBR_START, s1, sizeof(int) * (n + 1)), 0);
    assert_int_equal(dem_get_raw(cl, DEM_FIELD_NBR_START, s2, sizeof(int) * (n + 1)), 0);
    assert_int_equal(dem_get_raw(ref, DEM_FIELD_NBR_LIST, l1, sizeof(int) * m), 0);
    assert_int_equal(dem_get_raw(cl, DEM_FIELD_NBR_LIST, l2, sizeof(int) * m), 0);
    assert_int_equal(dem_get_raw(ref, DEM_FIELD_X_BUILD, xb, bytes), 0);
    assert_memory_equal(c1, c2, sizeof(int) * n);
    assert_memory_equal(s1, s2, sizeof(int) * (n + 1));
    assert_true(s1[0] == 0 && s1[n] <= m);
    for (int i = 0; i < n; i++) {
        assert_int_equal(s1[i + 1] - s1[i], c1[i]); /* packed: each row right after the one before */
        rad[i] = dem_particle_radius(ref, i);
    }
    assert_memory_equal(l1, l2, sizeof(int) * s1[n]);
    long total = 0;
    int widest = 0;
    for (int i = 0; i < n; i++) {
        int k = 0;
        for (int j = 0; j < n; j++) {
            if (j == i)
                continue;
            int in = prec == DEM_FP64 ? IN_RANGE(double, xb, rad, skin, i, j) : IN_RANGE(float, xb, rad, skin, i, j);
            if (!in)
                continue;
            if (k >= c1[i] || l1[s1[i] + k] != j)
                fail_msg("row %d: partner %d missing or out of order (slot %d)", i, j, k);
            k++;
        }
        if (k != c1[i])
            fail_msg("row %d: %d partners listed, %d in range", i, c1[i], k);
        total += k;
        widest = k > widest ? k : widest;
    }
    printf("  %s, skin %g m: %ld row entries, widest row %d, capacity %d\n", prec == DEM_FP64 ? "fp64" : "fp32", skin,
           total, widest, m);
    assert_true(total > 2 * n); /* a dense packing */
    /* the rows are packed: their slots start at 8 per particle and grow when a build's count needs more (they never
     * shrink): with the large skins the rows outgrew them, so the count-and-grow path has run. They grow to 1/8 over
     * what that build needed, plus 16 (host/core/rebuild.c row_capacity), not by doubling, and not to the widest row for every
     * particle. The rows now may be a little shorter than when they grew: 1/8 of slack. */
    assert_true(total <= m);
    if (cfg_skin > 5e-4)
        assert_true(m > 8 * n && widest > 16);
    assert_true(m == 8 * n || m <= total + total / 4 + 16);
    /* the memory report by part (dem_memory_part) adds up to the whole, and holds at least the current row set (a
     * count and a start per particle, m slots) and a 7-real record for each listed pair */
    size_t parts = 0, rs = prec == DEM_FP64 ? 8 : 4;
    for (int k = 0; k < DEM_MEM__COUNT; k++)
        parts += dem_device_bytes_part(cl, (dem_memory_part)k);
    assert_true(parts == dem_device_bytes(cl) && parts > 0);
    assert_true(dem_device_bytes_part(cl, DEM_MEM_ROWS) >= sizeof(int) * (2 * (size_t)n + 1 + (size_t)m));
    assert_true(dem_device_bytes_part(cl, DEM_MEM_PAIRS) >= (size_t)(total / 2) * 7 * rs);
    assert_true(dem_device_bytes_part(cl, DEM_MEM_MESH) <= dem_device_bytes(cl) / 100); /* no membranes: empty ones */
    assert_string_equal(dem_memory_part_name(DEM_MEM_PAIRS), "pairs");
    free(xb);
    free(c1), free(c2), free(s1), free(s2), free(l1), free(l2), free(rad);
    dem_destroy(ref);
    dem_destroy(cl);
}

static void test_fp64_small_skin(void **st) { (void)st; check(DEM_FP64, 1e-4, 100); }
static void test_fp64_large_skin(void **st) { (void)st; check(DEM_FP64, 1.2e-3, 100); }
static void test_fp32_small_skin(void **st) { (void)st; check(DEM_FP32, 1e-4, 100); }
static void test_fp32_large_skin(void **st) { (void)st; check(DEM_FP32, 7e-4, 100); } /* widest row 17 */
static void test_fp64_auto_skin(void **st) { (void)st; check(DEM_FP64, 0, 700); }

/* The automatic skin on PoCL against a fixed skin (its largest) on the reference, 1000 steps in lockstep: the same
 * bits at every step; returns the automatic run's skin at the end over its largest, and its rebuilds. */
static double auto_against_fixed(dem_precision prec, double speed, double lid_speed, int gravity, long *rebuilds)
{
    packing_opts o;
    packing_defaults(&o);
    o.side = 6;
    o.speed = speed;
    o.lid_speed = lid_speed;
    o.gravity = gravity;
    dem_sim *a = packing_build(&o), *f = packing_build(&o);
    dem_config ca = cfg_of(DEM_BACKEND_OPENCL, prec), cf = cfg_of(DEM_BACKEND_REFERENCE, prec);
    start_or_fail(a, &ca);
    double hi = dem_neighbor_skin(a), least = hi; /* 0.3 x the smallest radius */
    cf.skin = hi;
    start_or_fail(f, &cf);
    char msg[512];
    for (int k = 0; k < 10; k++) {
        step_or_fail(a, 100);
        step_or_fail(f, 100);
        if (state_diff(f, a, msg, sizeof msg))
            fail_msg("automatic skin against a fixed one, step %d: %s", 100 * (k + 1), msg);
        least = dem_neighbor_skin(a) < least ? dem_neighbor_skin(a) : least;
    }
    double now = dem_neighbor_skin(a);
    assert_true(least >= hi / 6 * (1 - 1e-12)); /* never below 0.05 x the smallest radius */
    *rebuilds = dem_rebuild_count(a);
    printf("  %s, speed %g m/s, lid %g m/s: skin %.3g of its largest at the end (least %.3g), %ld rebuilds (fixed: %ld)\n",
           prec == DEM_FP64 ? "fp64" : "fp32", speed, lid_speed, now / hi, least / hi, *rebuilds,
           dem_rebuild_count(f));
    dem_destroy(a);
    dem_destroy(f);
    return now / hi;
}

static void test_auto_skin(void **st)
{
    (void)st;
    long r_rest, r_moving;
    /* at rest: no particle reaches the trigger, the rows are tried smaller every 200 steps down to 0.05 r_min */
    double rest = auto_against_fixed(DEM_FP32, 0, 0, 0, &r_rest);
    assert_true(rest < 1.0 / 6 * 1.2 && r_rest >= 4);
    /* moving: the trigger fires every few tens of steps, and the chosen skin stays larger */
    double moving = auto_against_fixed(DEM_FP64, 0.5, 0.2, 1, &r_moving);
    assert_true(moving > 1.5 * rest && r_moving > r_rest);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fp64_small_skin), cmocka_unit_test(test_fp64_large_skin),
        cmocka_unit_test(test_fp32_small_skin), cmocka_unit_test(test_fp32_large_skin),
        cmocka_unit_test(test_fp64_auto_skin),  cmocka_unit_test(test_auto_skin),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
