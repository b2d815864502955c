/* test_h5rows.c - a dataset that grows by rows (app/h5util.c) written a row at a time and a row in parts
 * (h5rows_append_part: a frame gathered slab by slab from the ranks of a split run, app/run_mpi.c), read back with
 * HDF5's own reader of the whole dataset: the same values in the same places, for rows small enough to be gathered in
 * memory (written in chunks of rows) and rows large enough to go straight to the file, with the parts cut at chunk
 * boundaries and off them; parts out of order or past the row are refused. */
#include "test_util.h"
#include "h5util.h"
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static double value(long row, long i, int c) { return (double)row * 1e6 + (double)i * 8 + c + 0.25; }

/* rows of d1 x d2 doubles: nrows of them, odd rows whole and even rows in parts of `part` elements; read back */
static void rows_in_parts(long d1, int d2, long part, int nrows)
{
    char path[] = "/tmp/test_h5rows_XXXXXX";
    int fd = mkstemp(path);
    assert_true(fd >= 0);
    close(fd);
    hid_t f = H5Fcreate(path, H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    assert_true(f >= 0);
    h5rows r;
    assert_int_equal(h5rows_create(&r, f, "x", H5T_NATIVE_DOUBLE, d2 > 1 ? 3 : 2, (hsize_t)d1, (hsize_t)d2, "m"), 0);
    double *row = malloc(sizeof(double) * (size_t)(d1 * d2));
    assert_non_null(row);
    for (int k = 0; k < nrows; k++) {
        for (long i = 0; i < d1; i++)
            for (int c = 0; c < d2; c++)
                row[i * d2 + c] = value(k, i, c);
        if (k % 2) {
            assert_int_equal(h5rows_append(&r, row), 0);
            continue;
        }
        for (long a = 0; a < d1; a += part) {
            long b = a + part < d1 ? a + part : d1;
            assert_int_equal(h5rows_append_part(&r, (hsize_t)a, (hsize_t)b, row + a * d2), 0);
        }
    }
    assert_int_equal(h5rows_append_part(&r, 5, 3, row), -1); /* an empty or reversed part */
    assert_int_equal(h5rows_append_part(&r, 0, (hsize_t)d1 + 1, row), -1); /* past the row */
    assert_int_equal(h5rows_flush(&r), 0);
    h5rows_close(&r);
    H5Fclose(f);
    f = H5Fopen(path, H5F_ACC_RDONLY, H5P_DEFAULT);
    assert_true(f >= 0);
    size_t count = (size_t)(nrows * d1 * d2);
    assert_int_equal(h5_count(f, "x"), (long)count);
    double *all = malloc(sizeof(double) * count);
    assert_non_null(all);
    assert_int_equal(h5_read(f, "x", H5T_NATIVE_DOUBLE, all, count), 0);
    long bad = 0;
    for (int k = 0; k < nrows; k++)
        for (long i = 0; i < d1; i++)
            for (int c = 0; c < d2; c++)
                bad += all[((size_t)k * d1 + i) * d2 + c] != value(k, i, c);
    assert_int_equal(bad, 0);
    H5Fclose(f);
    unlink(path);
    free(all);
    free(row);
}

/* 64 particles x 3: gathered in memory; parts of 10 (off any boundary) and of the whole row */
static void test_small_rows(void **state)
{
    (void)state;
    rows_in_parts(64, 3, 10, 7);
    rows_in_parts(64, 3, 64, 5);
    rows_in_parts(729, 1, 100, 6); /* a scalar per particle */
}

/* 300 000 particles x 3 (7.2 MB a row, chunks of 150 000 particles): straight to the file, parts of a chunk and off
 * the chunks (70 001) */
static void test_large_rows(void **state)
{
    (void)state;
    h5rows probe;
    hid_t f = H5Fcreate("/tmp/test_h5rows_probe.h5", H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
    assert_true(f >= 0);
    assert_int_equal(h5rows_create(&probe, f, "x", H5T_NATIVE_DOUBLE, 3, 300000, 3, NULL), 0);
    assert_true(probe.cap <= 1);          /* the rows go straight through */
    assert_int_equal(probe.chunk1, 150000); /* halved to below 4 MiB */
    h5rows_close(&probe);
    H5Fclose(f);
    unlink("/tmp/test_h5rows_probe.h5");
    rows_in_parts(300000, 3, 150000, 3);
    rows_in_parts(300000, 3, 70001, 3);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_small_rows), cmocka_unit_test(test_large_rows)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
