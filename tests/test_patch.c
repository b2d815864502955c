/* test_patch.c - the patch geometry of common/patch.h (seed 001 section 2.5), through its reference twin
 * (reference/patch.c) and an OpenCL program built from the same header on device DEM_DEVICE:
 *  - the closest point of a triangle to a point is no farther than the nearest of 20301 points sampled on the
 *    triangle, lies on it, meets the first-order conditions of its feature, and is classified as that feature
 *    (face: all weights > 0; edge: the weight off the edge exactly 0; vertex: weights exactly (1, 0, 0) in turn);
 *  - OpenCL gives the reference's bits, fp32 and fp64;
 *  - Table 1: each of its nine cells on two patches with a common edge, the "rand" cells and vertex contacts at one
 *    mesh vertex resolved to the lower patch index, patches without a common edge left alone, and the decisions
 *    independent of the order the contacts are listed in. */
#include "test_util.h" /* test_cl_open: the probe kernel, built with the library's options */
#include <CL/cl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#define DEM_REAL_SIZE 8 /* for the constants (PATCH_FACE, ...); the items run through reference/patch.c */
#include "patch.h"
#include "ref_kernels.h" /* dem_patch_probe_f32/_f64, dem_patch_keep_f64 */

#define NPROBE 4000

static unsigned long long lcg = 0x9e3779b97f4a7c15ull;
static double rnd(void) /* uniform in [-1, 1) */
{
    lcg = lcg * 6364136223846793005ull + 1442695040888963407ull;
    return (double)(lcg >> 11) / 9007199254740992.0 * 2 - 1;
}

static double *probe_x, *probe_tri; /* points, triangles (9 per probe) */

static void make_probes(void)
{
    probe_x = malloc(sizeof(double) * 3 * NPROBE), probe_tri = malloc(sizeof(double) * 9 * NPROBE);
    for (int i = 0; i < NPROBE; i++) {
        for (int k = 0; k < 9; k++)
            probe_tri[9 * i + k] = 0.01 * rnd();
        for (int k = 0; k < 3; k++) /* around the triangle, some far off: every region gets points */
            probe_x[3 * i + k] = (i % 4 == 0 ? 0.05 : 0.015) * rnd();
    }
}

static double dist2(const double *a, const double *b)
{
    return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
}

static void test_closest_point(void **st)
{
    (void)st;
    int *kind = malloc(sizeof(int) * NPROBE), *index = malloc(sizeof(int) * NPROBE), count[3] = {0, 0, 0};
    double *w = malloc(sizeof(double) * 3 * NPROBE), *pt = malloc(sizeof(double) * 3 * NPROBE);
    dem_patch_probe_f64(NPROBE, probe_x, probe_tri, kind, index, w, pt);
    for (int i = 0; i < NPROBE; i++) {
        const double *p = probe_x + 3 * i, *a = probe_tri + 9 * i, *b = a + 3, *c = a + 6, *x = pt + 3 * i;
        const double *wi = w + 3 * i;
        count[kind[i]]++;
        /* on the triangle: its weights */
        assert_true(wi[0] >= 0 && wi[1] >= 0 && wi[2] >= 0 && fabs(wi[0] + wi[1] + wi[2] - 1) < 1e-12);
        for (int q = 0; q < 3; q++)
            assert_true(fabs(wi[0] * a[q] + wi[1] * b[q] + wi[2] * c[q] - x[q]) < 1e-15);
        /* no sample of the triangle is nearer */
        double best = INFINITY, d = dist2(p, x);
        for (int u = 0; u <= 200; u++)
            for (int v = 0; u + v <= 200; v++) {
                double s[3], su = u / 200.0, sv = v / 200.0;
                for (int q = 0; q < 3; q++)
                    s[q] = a[q] + su * (b[q] - a[q]) + sv * (c[q] - a[q]);
                best = fmin(best, dist2(p, s));
            }
        if (!(d <= best * (1 + 1e-12) + 1e-30))
            fail_msg("probe %d: closest point at distance^2 %.17g, a sample at %.17g", i, d, best);
        /* the feature's conditions: the offset p - x is normal to a face or to an edge; a vertex has its weight 1 */
        double r[3], e1[3], e2[3];
        for (int q = 0; q < 3; q++)
            r[q] = p[q] - x[q], e1[q] = b[q] - a[q], e2[q] = c[q] - a[q];
        double scale = sqrt(dist2(p, x)) * 0.03 + 1e-30;
        if (kind[i] == PATCH_FACE) {
            assert_true(wi[0] > 0 && wi[1] > 0 && wi[2] > 0);
            assert_true(fabs(r[0] * e1[0] + r[1] * e1[1] + r[2] * e1[2]) < 1e-9 * scale);
            assert_true(fabs(r[0] * e2[0] + r[1] * e2[1] + r[2] * e2[2]) < 1e-9 * scale);
        } else if (kind[i] == PATCH_EDGE) {
            int k = index[i], off = (k + 2) % 3;
            const double *v0 = a + 3 * k, *v1 = a + 3 * ((k + 1) % 3);
            assert_true(wi[off] == 0 && wi[k] > 0 && wi[(k + 1) % 3] > 0);
            double t = 0;
            for (int q = 0; q < 3; q++)
                t += r[q] * (v1[q] - v0[q]);
            assert_true(fabs(t) < 1e-9 * scale);
        } else {
            assert_true(wi[index[i]] == 1 && wi[(index[i] + 1) % 3] == 0 && wi[(index[i] + 2) % 3] == 0);
            assert_true(dist2(x, a + 3 * index[i]) == 0);
        }
    }
    printf("  %d probes: %d face, %d edge, %d vertex contacts, each no farther than the nearest of 20301 samples\n",
           NPROBE, count[PATCH_FACE], count[PATCH_EDGE], count[PATCH_VERTEX]);
    assert_true(count[0] > NPROBE / 20 && count[1] > NPROBE / 20 && count[2] > NPROBE / 20);
    free(kind), free(index), free(w), free(pt);
}

static const char *probe_src =
    "#include \"patch.h\"\n"
    "__kernel void probe(__global const real *p, __global const real *tri_x, __global int *kind,\n"
    "                    __global int *index, __global real *w, __global real *point)\n"
    "{\n"
    "    int i = get_global_id(0);\n"
    "    patch_point c = patch_closest(v3_load(p, i), v3_load(tri_x, 3 * i), v3_load(tri_x, 3 * i + 1),\n"
    "                                  v3_load(tri_x, 3 * i + 2));\n"
    "    kind[i] = c.kind, index[i] = c.index;\n"
    "    w[3 * i] = c.w[0], w[3 * i + 1] = c.w[1], w[3 * i + 2] = c.w[2];\n"
    "    v3_store(point, i, c.point);\n"
    "}\n";

/* Runs the probe kernel in precision rs on device DEM_DEVICE; the results into kind, index, w, pt */
static void opencl_probe(int rs, const void *p, const void *tri, int *kind, int *index, void *w, void *pt)
{
    test_cl t;
    test_cl_open(&t, probe_src, "probe", rs);
    size_t r = (size_t)rs;
    cl_mem args[6] = {test_cl_buffer(&t, 3 * r * NPROBE, p), test_cl_buffer(&t, 9 * r * NPROBE, tri),
                      test_cl_buffer(&t, sizeof(int) * NPROBE, NULL), test_cl_buffer(&t, sizeof(int) * NPROBE, NULL),
                      test_cl_buffer(&t, 3 * r * NPROBE, NULL), test_cl_buffer(&t, 3 * r * NPROBE, NULL)};
    cl_kernel k = t.kernel;
    cl_command_queue q = t.queue;
    for (cl_uint a = 0; a < 6; a++)
        assert_int_equal(clSetKernelArg(k, a, sizeof(cl_mem), &args[a]), CL_SUCCESS);
    size_t global = NPROBE;
    assert_int_equal(clEnqueueNDRangeKernel(q, k, 1, NULL, &global, NULL, 0, NULL, NULL), CL_SUCCESS);
    clEnqueueReadBuffer(q, args[2], CL_TRUE, 0, sizeof(int) * NPROBE, kind, 0, NULL, NULL);
    clEnqueueReadBuffer(q, args[3], CL_TRUE, 0, sizeof(int) * NPROBE, index, 0, NULL, NULL);
    clEnqueueReadBuffer(q, args[4], CL_TRUE, 0, 3 * r * NPROBE, w, 0, NULL, NULL);
    clEnqueueReadBuffer(q, args[5], CL_TRUE, 0, 3 * r * NPROBE, pt, 0, NULL, NULL);
    for (int a = 0; a < 6; a++)
        clReleaseMemObject(args[a]);
    test_cl_close(&t);
}

static void test_opencl_bits(void **st)
{
    (void)st;
    for (int rs = 4; rs <= 8; rs += 4) {
        size_t r = (size_t)rs;
        void *p = malloc(3 * r * NPROBE), *tri = malloc(9 * r * NPROBE);
        for (int k = 0; k < 3 * NPROBE; k++)
            rs == 8 ? (void)(((double *)p)[k] = probe_x[k]) : (void)(((float *)p)[k] = (float)probe_x[k]);
        for (int k = 0; k < 9 * NPROBE; k++)
            rs == 8 ? (void)(((double *)tri)[k] = probe_tri[k]) : (void)(((float *)tri)[k] = (float)probe_tri[k]);
        int *k1 = malloc(sizeof(int) * NPROBE), *i1 = malloc(sizeof(int) * NPROBE);
        int *k2 = malloc(sizeof(int) * NPROBE), *i2 = malloc(sizeof(int) * NPROBE);
        void *w1 = malloc(3 * r * NPROBE), *x1 = malloc(3 * r * NPROBE), *w2 = malloc(3 * r * NPROBE);
        void *x2 = malloc(3 * r * NPROBE);
        if (rs == 8)
            dem_patch_probe_f64(NPROBE, p, tri, k1, i1, w1, x1);
        else
            dem_patch_probe_f32(NPROBE, p, tri, k1, i1, w1, x1);
        opencl_probe(rs, p, tri, k2, i2, w2, x2);
        assert_memory_equal(k1, k2, sizeof(int) * NPROBE);
        assert_memory_equal(i1, i2, sizeof(int) * NPROBE);
        assert_memory_equal(w1, w2, 3 * r * NPROBE);
        assert_memory_equal(x1, x2, 3 * r * NPROBE);
        printf("  fp%d: OpenCL = reference, bit for bit, on %d probes\n", 8 * rs, NPROBE);
        free(p), free(tri), free(k1), free(i1), free(k2), free(i2), free(w1), free(x1), free(w2), free(x2);
    }
}

/* Two patches with the common edge 1-2: A = (0, 1, 2) id 7, B = (2, 1, 3) id 4; a third, C = (3, 4, 5) id 9,
 * touching B only at vertex 3 and A nowhere. */

static void decide(int n, const int *id, const int (*tri)[3], const int *kind, const double *d2, int *keep)
{
    int t[3 * 8];
    for (int k = 0; k < n; k++)
        memcpy(t + 3 * k, tri[k], sizeof(int[3]));
    for (int k = 0; k < n; k++)
        keep[k] = dem_patch_keep_f64(k, n, id, t, kind, d2);
}

static void test_table_1(void **st)
{
    (void)st;
    /* columns: A face, edge, vertex; rows: B face, edge, vertex; 1 = A stays, 2 = B stays, 3 = both (Table 1;
     * "A or B (rand)" -> the lower patch id, B's 4) */
    static const int table[3][3] = {{3, 2, 2}, {1, 2, 2}, {1, 1, 2}};
    static const int kinds[3] = {PATCH_FACE, PATCH_EDGE, PATCH_VERTEX};
    for (int row = 0; row < 3; row++)
        for (int col = 0; col < 3; col++) {
            int id[2] = {7, 4}, kind[2] = {kinds[col], kinds[row]}, keep[2];
            double same[2] = {1e-6, 1e-6}; /* the table's cases: both at one point */
            const int (*tri)[3] = (const int (*)[3])(const int[2][3]){{0, 1, 2}, {2, 1, 3}};
            decide(2, id, tri, kind, same, keep);
            int got = keep[0] + 2 * keep[1];
            if (got != table[row][col])
                fail_msg("Table 1, A %d / B %d: kept %d, the table says %d", kinds[col], kinds[row], got,
                         table[row][col]);
            /* listed the other way round: the same decisions */
            int id2[2] = {4, 7}, kind2[2] = {kind[1], kind[0]}, keep2[2];
            decide(2, id2, (const int (*)[3])(const int[2][3]){{2, 1, 3}, {0, 1, 2}}, kind2, same, keep2);
            assert_int_equal(keep2[0], keep[1]);
            assert_int_equal(keep2[1], keep[0]);
        }
    /* B and C share vertex 3 only (the extension, patch.h): C's face removes B's edge contact, even when farther */
    int id[2] = {4, 9}, kind[2] = {PATCH_EDGE, PATCH_FACE}, keep[2];
    double d2[2] = {1e-6, 2e-6};
    decide(2, id, (const int (*)[3])(const int[2][3]){{2, 1, 3}, {3, 4, 5}}, kind, d2, keep);
    assert_true(!keep[0] && keep[1]);
    /* ... two edge contacts of B and C: the nearer stays, whatever the ids */
    int kind_e[2] = {PATCH_EDGE, PATCH_EDGE};
    double d2e[2] = {3e-6, 2e-6};
    decide(2, id, (const int (*)[3])(const int[2][3]){{2, 1, 3}, {3, 4, 5}}, kind_e, d2e, keep);
    assert_true(!keep[0] && keep[1]);
    /* patches with no vertex in common (A and C) do not compete: both stay */
    int kind_v[2] = {PATCH_VERTEX, PATCH_EDGE};
    decide(2, id, (const int (*)[3])(const int[2][3]){{0, 1, 2}, {3, 4, 5}}, kind_v, d2e, keep);
    assert_true(keep[0] && keep[1]);
    /* vertex contacts at the common vertex 3 of B and C, and of a third patch D = (6, 3, 7) id 2: one point, so only
     * D (lowest id) stays */
    int id3[3] = {4, 9, 2}, kind3[3] = {PATCH_VERTEX, PATCH_VERTEX, PATCH_VERTEX}, keep3[3];
    double d3[3] = {1e-6, 1e-6, 1e-6};
    decide(3, id3, (const int (*)[3])(const int[3][3]){{2, 1, 3}, {3, 4, 5}, {6, 3, 7}}, kind3, d3, keep3);
    assert_true(!keep3[0] && !keep3[1] && keep3[2]);
}

int main(void)
{
    make_probes();
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_closest_point),
        cmocka_unit_test(test_opencl_bits),
        cmocka_unit_test(test_table_1),
    };
    int rc = cmocka_run_group_tests(tests, NULL, NULL);
    free(probe_x), free(probe_tri);
    return rc;
}
