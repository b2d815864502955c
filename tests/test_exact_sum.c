/* test_exact_sum.c - the exact accumulator (common/exact_sum.h), against what does not share its code:
 *  - random doubles over 240 binary orders of magnitude, both signs: the sum in input order, reversed, shuffled, and
 *    cut into random parts summed apart and merged in a random order - all the same bits, and those of Python's
 *    math.fsum (correctly rounded, Shewchuk's algorithm) of the same numbers;
 *  - hand-made cases whose correctly rounded sums are known: cancellation of huge terms, subnormals, a tie rounded to
 *    even and the same tie broken by a far smaller term, overflow to infinity, in double and in float (a float sum
 *    rounded once from the exact sum, never through a double);
 *  - floats against math.fsum of the same floats rounded to float;
 *  - an OpenCL kernel: four work items each sum a quarter, the four accumulators merged in two orders, and the whole
 *    summed by one item - the reference's bits, in an fp64 and an fp32 program. */
#include "test_util.h" /* test_cl_open, test_python */
#include <CL/cl.h>
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "exact_sum.h"

#define N 20000

static unsigned long long lcg = 0x243f6a8885a308d3ull;
static unsigned long long next_u(void)
{
    lcg = lcg * 6364136223846793005ull + 1442695040888963407ull;
    return lcg;
}
static double uniform(void) { return (double)(next_u() >> 11) / 9007199254740992.0; }

static double sum_of(const double *x, const int *idx, int n)
{
    exact_acc a;
    exact_clear(&a);
    for (int k = 0; k < n; k++)
        exact_add_double(&a, x[idx ? idx[k] : k]);
    return exact_to_double(&a);
}

static int same_bits(double a, double b) { return memcmp(&a, &b, sizeof a) == 0; }

/* The correctly rounded sum of the numbers in path (hex floats, one per line): math.fsum's double, or, to_float, the
 * exact sum (fractions.Fraction) rounded once to float by hand (nearest, ties to even; 24 bits, subnormals from
 * 2^-149) */
static double python_fsum(const char *dir, const char *path, int to_float)
{
    char err[2048], out[600];
    snprintf(out, sizeof out, "%s/fsum.txt", dir);
    static const char *f32 =
        "import fractions, sys\n"
        "F = fractions.Fraction\n"
        "s = sum(F(float.fromhex(l)) for l in open(sys.argv[1]))\n"
        "a = abs(s)\n"
        "if a == 0: print((0.0).hex()); sys.exit()\n"
        "e = a.numerator.bit_length() - a.denominator.bit_length()\n"
        "e = e - 1 if F(2) ** e > a else e\n"
        "q = max(e - 23, -149)\n"
        "t = a / F(2) ** q\n"
        "n = t.numerator // t.denominator\n"
        "r = t - n\n"
        "n = n + 1 if r > F(1, 2) or (r == F(1, 2) and n % 2) else n\n"
        "print((float(n) * 2.0 ** q * (1 if s > 0 else -1)).hex())\n";
    char script[600];
    snprintf(script, sizeof script, "%s/f32.py", dir);
    FILE *sp = fopen(script, "w");
    assert_non_null(sp);
    fputs(f32, sp);
    fclose(sp);
    if (to_float ? test_sh(dir, err, sizeof err, "%s %s %s > %s", test_python(), script, path, out)
                 : test_sh(dir, err, sizeof err, "%s -c \"import math; print(math.fsum(float.fromhex(l) for l in "
                                                 "open('%s')).hex())\" > %s", test_python(), path, out))
        fail_msg("python fsum: %s", err);
    FILE *fp = fopen(out, "r");
    assert_non_null(fp);
    char line[128];
    assert_non_null(fgets(line, sizeof line, fp));
    fclose(fp);
    return strtod(line, NULL);
}

static void test_orders_and_fsum(void **st)
{
    (void)st;
    static double x[N];
    static int idx[N];
    for (int k = 0; k < N; k++) /* mantissas at random, magnitudes from 2^-120 to 2^120, both signs */
        x[k] = ldexp(uniform() + 0.5, (int)(next_u() % 241) - 120) * ((next_u() >> 7) & 1 ? -1 : 1);
    double fwd = sum_of(x, NULL, N);
    for (int k = 0; k < N; k++)
        idx[k] = N - 1 - k;
    double rev = sum_of(x, idx, N);
    for (int k = 0; k < N; k++)
        idx[k] = k;
    for (int k = N - 1; k > 0; k--) { /* a shuffle */
        int j = (int)(next_u() % (unsigned long long)(k + 1)), t = idx[k];
        idx[k] = idx[j], idx[j] = t;
    }
    double shuf = sum_of(x, idx, N);
    /* parts: 37 random cuts, each part summed apart, the parts merged last to first */
    int cuts[39] = {0};
    for (int k = 1; k < 38; k++)
        cuts[k] = (int)(next_u() % N);
    cuts[38] = N;
    for (int a = 1; a < 39; a++) /* sorted */
        for (int b = a; b > 0 && cuts[b] < cuts[b - 1]; b--) {
            int t = cuts[b];
            cuts[b] = cuts[b - 1], cuts[b - 1] = t;
        }
    exact_acc total;
    exact_clear(&total);
    for (int p = 37; p >= 0; p--) {
        exact_acc part;
        exact_clear(&part);
        for (int k = cuts[p]; k < cuts[p + 1]; k++)
            exact_add_double(&part, x[idx[k]]);
        exact_merge(&total, &part);
    }
    double merged = exact_to_double(&total);
    /* the same numbers to Python */
    char dir[256], path[400];
    assert_int_equal(test_tmpdir_make(dir, sizeof dir, "dem-test-exact"), 0);
    snprintf(path, sizeof path, "%s/x.txt", dir);
    FILE *fp = fopen(path, "w");
    for (int k = 0; k < N; k++)
        fprintf(fp, "%a\n", x[k]);
    fclose(fp);
    double fsum = python_fsum(dir, path, 0);
    double naive = 0;
    for (int k = 0; k < N; k++)
        naive += x[k];
    printf("  %d doubles: exact sum %a in four orders; math.fsum %a; a plain loop %a\n", N, fwd, fsum, naive);
    assert_true(same_bits(fwd, rev) && same_bits(fwd, shuf) && same_bits(fwd, merged));
    assert_true(same_bits(fwd, fsum));
    /* cancelling: pairs y and -(y + e), y up to 2^100, e up to 2^-20 (y + e rounded: most of a large y's e is lost),
     * shuffled: a plain loop is left with rounding errors of the y's */
    for (int k = 0; k < N; k += 2) {
        double y = ldexp(uniform() + 0.5, (int)(next_u() % 100)), e = ldexp(uniform(), -20 - (int)(next_u() % 30));
        x[k] = y, x[k + 1] = -(y + e);
    }
    double csum = sum_of(x, idx, N), cfwd = sum_of(x, NULL, N);
    fp = fopen(path, "w");
    for (int k = 0; k < N; k++)
        fprintf(fp, "%a\n", x[k]);
    fclose(fp);
    double cfsum = python_fsum(dir, path, 0);
    naive = 0;
    for (int k = 0; k < N; k++)
        naive += x[idx[k]];
    printf("  %d cancelling doubles: exact sum %a in two orders; math.fsum %a; a plain loop, shuffled, %a\n", N, csum,
           cfsum, naive);
    assert_true(same_bits(csum, cfwd) && same_bits(csum, cfsum));
    /* floats: 2^-60 to 2^60 */
    static float xf[N];
    fp = fopen(path, "w");
    exact_acc af, ar;
    exact_clear(&af), exact_clear(&ar);
    for (int k = 0; k < N; k++) {
        xf[k] = (float)ldexp(uniform() + 0.5, (int)(next_u() % 121) - 60) * ((next_u() >> 7) & 1 ? -1.0f : 1.0f);
        fprintf(fp, "%a\n", (double)xf[k]);
        exact_add_float(&af, xf[k]);
    }
    fclose(fp);
    for (int k = N - 1; k >= 0; k--)
        exact_add_float(&ar, xf[k]);
    float sf = exact_to_float(&af), sr = exact_to_float(&ar), pf = (float)python_fsum(dir, path, 1);
    printf("  %d floats: exact sum %a (reversed %a); the exact sum rounded once by Python %a\n", N, (double)sf,
           (double)sr, (double)pf);
    assert_true(memcmp(&sf, &sr, sizeof sf) == 0 && memcmp(&sf, &pf, sizeof sf) == 0);
    test_tmpdir_remove(dir);
}

static double dsum(int n, const double *v)
{
    exact_acc a;
    exact_clear(&a);
    for (int k = 0; k < n; k++)
        exact_add_double(&a, v[k]);
    return exact_to_double(&a);
}
static float fsum32(int n, const float *v)
{
    exact_acc a;
    exact_clear(&a);
    for (int k = 0; k < n; k++)
        exact_add_float(&a, v[k]);
    return exact_to_float(&a);
}

static void test_known_sums(void **st)
{
    (void)st;
    const double tiny = ldexp(1, -1074), eps = ldexp(1, -52);
    struct {
        int n;
        double v[4], want;
    } d[] = {
        {3, {1e300, 1, -1e300}, 1},                           /* the huge terms cancel, the 1 survives */
        {3, {1, 1e100, -1e100}, 1},
        {2, {tiny, -tiny}, 0},                                /* exactly zero */
        {3, {tiny, tiny, tiny}, 3 * tiny},                    /* subnormals, exact */
        {2, {ldexp(1, -1022), -tiny}, ldexp(1, -1022) - tiny}, /* the largest subnormal */
        {2, {1, eps / 2}, 1},                                 /* a tie: to even */
        {3, {1, eps / 2, ldexp(1, -200)}, 1 + eps},           /* the same tie, broken by a far smaller term */
        {2, {1 + eps, eps / 2}, 1 + 2 * eps},                 /* a tie from an odd mantissa: up */
        {2, {DBL_MAX, DBL_MAX}, INFINITY},                    /* past the largest double */
        {3, {DBL_MAX, DBL_MAX, -DBL_MAX}, DBL_MAX},           /* not past it in the end: exact in between */
        {4, {-0.5, -0.25, -0.125, 0}, -0.875},
        {3, {ldexp(1, 53) - 1, 0.5, 0}, ldexp(1, 53)},       /* a tie rounded up into the next binade */
        {2, {ldexp(1, 1000), -tiny}, ldexp(1, 1000)},        /* a borrow through 15 limbs, rounded back */
        {2, {-0.0, -0.0}, 0.0},                              /* exactly zero: +0 (as from s = 0) */
        {2, {INFINITY, 1}, INFINITY},                        /* an infinity among the terms */
        {3, {-INFINITY, 1e308, 1e308}, -INFINITY},
    };
    for (size_t k = 0; k < sizeof d / sizeof d[0]; k++) {
        double got = dsum(d[k].n, d[k].v);
        if (!same_bits(got, d[k].want))
            fail_msg("double case %zu: %a, want %a", k, got, d[k].want);
    }
    assert_true(isnan(dsum(2, (double[2]){INFINITY, -INFINITY})) && isnan(dsum(2, (double[2]){NAN, 1})));
    /* doubles rounded to float: 2^-150 + 2^-151 = 0.75 of the smallest float subnormal: up to it; 2^-151 alone:
     * down to a zero of its sign; a sum just under the largest float's half ulp past it: FLT_MAX */
    exact_acc a;
    exact_clear(&a);
    exact_add_double(&a, ldexp(1, -150)), exact_add_double(&a, ldexp(1, -151));
    float f1 = exact_to_float(&a);
    exact_clear(&a);
    exact_add_double(&a, -ldexp(1, -151));
    float f2 = exact_to_float(&a);
    exact_clear(&a);
    exact_add_double(&a, (double)FLT_MAX), exact_add_double(&a, ldexp(1, 103) - ldexp(1, 50));
    float f3 = exact_to_float(&a);
    assert_true(f1 == ldexpf(1, -149) && f2 == 0 && signbit(f2) && f3 == FLT_MAX);
    const float ftiny = ldexpf(1, -149), feps = ldexpf(1, -23);
    struct {
        int n;
        float v[4], want;
    } f[] = {
        {2, {1, feps / 2}, 1},                            /* a tie in float: to even */
        {3, {1, feps / 2, ldexpf(1, -60)}, 1 + feps},     /* broken by a term a double tie would have dropped */
        {3, {1e30f, 1, -1e30f}, 1},
        {2, {ftiny, -ftiny}, 0},
        {3, {ftiny, ftiny, ftiny}, 3 * ftiny},
        {2, {FLT_MAX, FLT_MAX}, INFINITY},
    };
    for (size_t k = 0; k < sizeof f / sizeof f[0]; k++) {
        float got = fsum32(f[k].n, f[k].v);
        if (memcmp(&got, &f[k].want, sizeof got))
            fail_msg("float case %zu: %a, want %a", k, (double)got, (double)f[k].want);
    }
    /* the float sum is rounded once: through a double, 1 + 2^-24 + 2^-60 would round to the float tie 1 + 2^-24
     * and then to 1 */
    float v3[3] = {1, ldexpf(1, -24), ldexpf(1, -60)};
    double via = dsum(3, (double[3]){1, ldexp(1, -24), ldexp(1, -60)});
    printf("  %zu double and %zu float cases; 1 + 2^-24 + 2^-60 in float: %a (through a double: %a)\n",
           sizeof d / sizeof d[0], sizeof f / sizeof f[0], (double)fsum32(3, v3), (double)(float)via);
}

static const char *kernel_src =
    "#include \"dem_real.h\"\n"
    "#include \"exact_sum.h\"\n"
    "#if DEM_REAL_SIZE == 8\n"
    "#define ADD exact_add_double\n"
    "#define OUT exact_to_double\n"
    "#else\n"
    "#define ADD exact_add_float\n"
    "#define OUT exact_to_float\n"
    "#endif\n"
    "__kernel void parts(int n, __global const real *x, __global ulong *acc)\n"
    "{\n"
    "    int i = get_global_id(0), q = (n + 3) / 4;\n"
    "    exact_acc a;\n"
    "    exact_clear(&a);\n"
    "    for (int k = i * q; k < n && k < (i + 1) * q; k++)\n"
    "        ADD(&a, x[k]);\n"
    "    for (int k = 0; k < EXACT_LIMBS; k++)\n"
    "        acc[i * EXACT_LIMBS + k] = a.limb[k];\n"
    "}\n"
    "__kernel void total(int n, __global const real *x, __global const ulong *acc, __global real *out)\n"
    "{\n"
    "    exact_acc a, b, c;\n"
    "    exact_clear(&a), exact_clear(&c);\n"
    "    for (int k = 0; k < n; k++)\n"
    "        ADD(&c, x[k]);\n"
    "    out[0] = OUT(&c);\n"
    "    for (int p = 0; p < 4; p++) {\n"
    "        for (int k = 0; k < EXACT_LIMBS; k++)\n"
    "            b.limb[k] = acc[p * EXACT_LIMBS + k];\n"
    "        exact_merge(&a, &b);\n"
    "    }\n"
    "    out[1] = OUT(&a);\n"
    "    exact_clear(&a);\n"
    "    for (int p = 3; p >= 0; p--) {\n"
    "        for (int k = 0; k < EXACT_LIMBS; k++)\n"
    "            b.limb[k] = acc[p * EXACT_LIMBS + k];\n"
    "        exact_merge(&a, &b);\n"
    "    }\n"
    "    out[2] = OUT(&a);\n"
    "}\n";

static void test_opencl_bits(void **st)
{
    (void)st;
    static double x[N];
    static float xf[N];
    for (int k = 0; k < N; k++) {
        x[k] = ldexp(uniform() + 0.5, (int)(next_u() % 241) - 120) * ((next_u() >> 7) & 1 ? -1 : 1);
        xf[k] = (float)ldexp(uniform() + 0.5, (int)(next_u() % 121) - 60) * ((next_u() >> 7) & 1 ? -1.0f : 1.0f);
    }
    for (int rs = 8; rs >= 4; rs -= 4) {
        test_cl t;
        test_cl_open(&t, kernel_src, "parts", rs);
        cl_int e;
        cl_kernel kt = clCreateKernel((cl_program)t.program, "total", &e);
        assert_int_equal(e, CL_SUCCESS);
        cl_mem bx = test_cl_buffer(&t, (size_t)N * (size_t)rs, rs == 8 ? (void *)x : (void *)xf);
        cl_mem ba = test_cl_buffer(&t, 4 * EXACT_LIMBS * sizeof(cl_ulong), NULL);
        cl_mem bo = test_cl_buffer(&t, 3 * (size_t)rs, NULL);
        int n = N;
        clSetKernelArg(t.kernel, 0, sizeof(int), &n), clSetKernelArg(t.kernel, 1, sizeof(cl_mem), &bx);
        clSetKernelArg(t.kernel, 2, sizeof(cl_mem), &ba);
        clSetKernelArg(kt, 0, sizeof(int), &n), clSetKernelArg(kt, 1, sizeof(cl_mem), &bx);
        clSetKernelArg(kt, 2, sizeof(cl_mem), &ba), clSetKernelArg(kt, 3, sizeof(cl_mem), &bo);
        size_t four = 4, one = 1;
        assert_int_equal(clEnqueueNDRangeKernel(t.queue, t.kernel, 1, NULL, &four, &one, 0, NULL, NULL), CL_SUCCESS);
        assert_int_equal(clEnqueueNDRangeKernel(t.queue, kt, 1, NULL, &one, &one, 0, NULL, NULL), CL_SUCCESS);
        unsigned char got[3 * 8];
        assert_int_equal(clEnqueueReadBuffer(t.queue, bo, CL_TRUE, 0, 3 * (size_t)rs, got, 0, NULL, NULL), CL_SUCCESS);
        unsigned char want[8];
        if (rs == 8) {
            double w = dsum(N, x);
            memcpy(want, &w, 8);
        } else {
            float w = fsum32(N, xf);
            memcpy(want, &w, 4);
        }
        for (int k = 0; k < 3; k++)
            if (memcmp(got + k * rs, want, (size_t)rs))
                fail_msg("%s: OpenCL sum %d differs from the reference", rs == 8 ? "fp64" : "fp32", k);
        printf("  OpenCL %s: one item, four parts merged in two orders: the reference's bits\n",
               rs == 8 ? "fp64" : "fp32");
        clReleaseMemObject(bx), clReleaseMemObject(ba), clReleaseMemObject(bo);
        clReleaseKernel(kt);
        test_cl_close(&t);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_orders_and_fsum), cmocka_unit_test(test_known_sums),
                                       cmocka_unit_test(test_opencl_bits)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
