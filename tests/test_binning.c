/* test_binning.c - the binning kernels (common/binning.h) against their reference twins, and both against the
 * definition: cell_start is the exclusive scan of the cell counts, every particle sits in the cell of its position, the
 * cells in use are the particles' bounding box in the grid, and each cell lists its particles in ascending id. fp32 and
 * fp64, work-group sizes auto, 1, 7 and 128. */
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static void check(dem_precision prec, size_t local)
{
    packing_opts o;
    packing_defaults(&o);
    o.side = 9;
    dem_config rc = cfg_of(DEM_BACKEND_REFERENCE, prec), c = cfg_of(DEM_BACKEND_OPENCL, prec);
    c.local_size = local;
    dem_sim *ref, *cl;
    packing_pair(&o, &rc, &c, 50, &ref, &cl); /* 50 steps mix the particles: cells hold ids out of order */
    int n = dem_count(ref), nc = dem_cell_count(ref);
    assert_int_equal(nc, dem_cell_count(cl));
    int *s1 = malloc(sizeof(int) * (nc + 1)), *s2 = malloc(sizeof(int) * (nc + 1));
    int *p1 = malloc(sizeof(int) * n), *p2 = malloc(sizeof(int) * n);
    assert_int_equal(dem_get_raw(ref, DEM_FIELD_CELL_START, s1, sizeof(int) * (nc + 1)), 0);
    assert_int_equal(dem_get_raw(cl, DEM_FIELD_CELL_START, s2, sizeof(int) * (nc + 1)), 0);
    assert_int_equal(dem_get_raw(ref, DEM_FIELD_CELL_PARTICLES, p1, sizeof(int) * n), 0);
    assert_int_equal(dem_get_raw(cl, DEM_FIELD_CELL_PARTICLES, p2, sizeof(int) * n), 0);
    assert_memory_equal(s1, s2, sizeof(int) * (nc + 1));
    assert_memory_equal(p1, p2, sizeof(int) * n);
    /* definition: a permutation, sorted within cells, covering all particles */
    assert_int_equal(s1[0], 0);
    assert_int_equal(s1[nc], n);
    char *seen = calloc(n, 1);
    for (int c0 = 0; c0 < nc; c0++) {
        assert_true(s1[c0] <= s1[c0 + 1]);
        for (int k = s1[c0]; k < s1[c0 + 1]; k++) {
            assert_true(p1[k] >= 0 && p1[k] < n && !seen[p1[k]]);
            seen[p1[k]] = 1;
            if (k > s1[c0])
                assert_true(p1[k - 1] < p1[k]);
        }
    }
    free(seen);
    /* definition: each particle is listed in the cell of its position at the last binning (x_build), the cell
     * computed here in the run's precision from the grid (floor((x - lo) / cell) per axis), among the cells in use:
     * the particles' bounding box in the grid, tight on every side */
    double lo[3], inv_cell, *xb = malloc(sizeof(double) * 3 * n);
    int ncell[3], first[3], count[3], first2[3], count2[3], *cell_of = malloc(sizeof(int) * n);
    assert_int_equal(dem_grid_get(ref, lo, &inv_cell, ncell), 0);
    assert_int_equal(dem_grid_cells(ref, first, count), 0);
    assert_int_equal(dem_grid_cells(cl, first2, count2), 0);
    assert_memory_equal(first, first2, sizeof first);
    assert_memory_equal(count, count2, sizeof count);
    assert_int_equal(count[0] * count[1] * count[2], nc);
    assert_true(nc < ncell[0] * ncell[1] * ncell[2]); /* the packing's domain has room around it */
    assert_int_equal(dem_get_field(ref, DEM_FIELD_X_BUILD, xb), 0);
    for (int c0 = 0; c0 < nc; c0++)
        for (int k = s1[c0]; k < s1[c0 + 1]; k++)
            cell_of[p1[k]] = c0;
    int at_lo[3] = {0, 0, 0}, at_hi[3] = {0, 0, 0};
    for (int i = 0; i < n; i++) {
        int cc[3];
        for (int d = 0; d < 3; d++) {
            double t = prec == DEM_FP64 ? (xb[3 * i + d] - lo[d]) * inv_cell
                                        : (double)(((float)xb[3 * i + d] - (float)lo[d]) * (float)inv_cell);
            assert_true(t >= 0 && t < ncell[d]);
            cc[d] = (int)t - first[d];
            assert_true(cc[d] >= 0 && cc[d] < count[d]);
            at_lo[d] |= cc[d] == 0;
            at_hi[d] |= cc[d] == count[d] - 1;
        }
        int want = (cc[2] * count[1] + cc[1]) * count[0] + cc[0];
        if (cell_of[i] != want)
            fail_msg("particle %d is listed in cell %d, its position is in cell %d", i, cell_of[i], want);
    }
    for (int d = 0; d < 3; d++)
        assert_true(at_lo[d] && at_hi[d]);
    int used = 0; /* the check spans many cells, not one */
    for (int c0 = 0; c0 < nc; c0++)
        used += s1[c0 + 1] > s1[c0];
    assert_true(used > 100);
    free(xb), free(cell_of);
    free(s1), free(s2), free(p1), free(p2);
    dem_destroy(ref);
    dem_destroy(cl);
}

static void test_fp64_auto(void **st) { (void)st; check(DEM_FP64, 0); }
static void test_fp64_wg1(void **st) { (void)st; check(DEM_FP64, 1); }
static void test_fp32_wg7(void **st) { (void)st; check(DEM_FP32, 7); }
static void test_fp32_wg128(void **st) { (void)st; check(DEM_FP32, 128); }

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fp64_auto), cmocka_unit_test(test_fp64_wg1),
        cmocka_unit_test(test_fp32_wg7), cmocka_unit_test(test_fp32_wg128),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
