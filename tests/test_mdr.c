/* test_mdr.c - the MDR contact law's core (common/laws/mdr_core.h; docs/laws/mdr.md), one contact at a time, against
 * what we did not write into it:
 *  - its fixed-count exp, h(u), cube root and acos (F1, F2, F5, M40) against the C library's exp, acos and cbrt, and
 *    h's small-u series;
 *  - a sphere pressed elastically on a wall against Hertz (the limit MDR's circle profile must reach, M9) and against
 *    the profile's closed form with the C library's acos;
 *  - every single-contact path of tools/peer_mdr/cases.py (pairs, walls, an unequal pair, adhesion 0, 2 and 50 J/m^2,
 *    a sphere between six planes through Part II's bulk response) against tools/peer_mdr/mdr_reference.py, the
 *    independent Python reading of the papers that `make peer-mdr` matches with LAMMPS to 1e-13 of the peak force
 *    without adhesion (docs/laws/mdr.md "Against LAMMPS");
 *  - the plastic dent a load leaves (zero force while the spheres still overlap) and the adhesive pull (a tensile
 *    force before the contact lets go);
 *  - an OpenCL kernel built from the same header gives the reference's bits, fp32 and fp64, on device DEM_DEVICE. */
#include "test_util.h" /* test_cl_open */
#include <CL/cl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include "ref_kernels.h" /* dem_mdr_walk_f32/_f64, dem_mdr_fixed_f32/_f64 */

enum { WALK_PAIR = 0, WALK_WALL = 1, WALK_BOX = 2 }; /* mdr_core.h's MDR_WALK_* */
enum { FIXED_EXP = 0, FIXED_H = 1, FIXED_CBRT = 2, FIXED_ACOS = 3, FIXED_PENALTY = 4 }; /* its MDR_FIXED_* */

/* One case of cases.py as mdr_reference.py --walk prints it: its inputs and the reference's rows */
typedef struct {
    char name[64];
    int kind, n;          /* the walk's kind, its last step */
    double head[13];      /* R R2 MASS1 MASS2 DT ES G KAPPA NU Y GAMMA PSI_B DAMP */
    double *u, *delta, *r, *psi, *f; /* the reference's rows, steps 0..n */
} walk_case;

#define MAX_CASES 16
static walk_case cases[MAX_CASES];
static int ncases;

/* Runs mdr_reference.py --walk once and reads every case */
static void read_cases(void)
{
    if (ncases)
        return;
    char cmd[1200];
    snprintf(cmd, sizeof cmd, "%s '%s/tools/peer_mdr/mdr_reference.py' --walk", test_python(), DEM_DEFAULT_SOURCE_DIR);
    FILE *p = popen(cmd, "r");
    assert_non_null(p);
    char line[1024];
    walk_case *c = NULL;
    int row = 0;
    while (fgets(line, sizeof line, p)) {
        if (!strncmp(line, "case ", 5)) {
            if (c && row != c->n + 1)
                fail_msg("%s: case %s has %d rows, not %d", cmd, c->name, row, c->n + 1);
            assert_true(ncases < MAX_CASES);
            c = &cases[ncases++];
            char kind[16];
            double *h = c->head;
            assert_int_equal(sscanf(line, "case %63s %15s %d %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf %lf",
                                    c->name, kind, &c->n, h, h + 1, h + 2, h + 3, h + 4, h + 5, h + 6, h + 7, h + 8,
                                    h + 9, h + 10, h + 11, h + 12),
                             16);
            c->kind = !strcmp(kind, "pair") ? WALK_PAIR : !strcmp(kind, "wall") ? WALK_WALL : WALK_BOX;
            size_t m = (size_t)c->n + 1;
            c->u = malloc(5 * m * sizeof(double));
            assert_non_null(c->u);
            c->delta = c->u + m, c->r = c->u + 2 * m, c->psi = c->u + 3 * m, c->f = c->u + 4 * m;
            row = 0;
            continue;
        }
        assert_non_null(c);
        assert_true(row <= c->n);
        assert_int_equal(sscanf(line, "%lf %lf %lf %lf %lf", &c->u[row], &c->delta[row], &c->r[row], &c->psi[row],
                                &c->f[row]),
                         5);
        row++;
    }
    int st = pclose(p);
    if (c && row != c->n + 1)
        fail_msg("%s: case %s has %d rows, not %d", cmd, c->name, row, c->n + 1);
    if (st != 0 || ncases < 8)
        fail_msg("%s: exit status %d, %d cases read", cmd, st, ncases);
}

/* A walk's outputs, in doubles */
typedef struct {
    double *delta, *r, *psi, *f;
} walk_out;

/* Runs the walk of case c (u its approach; mat its 8 material reals; as c->head gives the rest) in the reference of
 * precision rs; bits (when not NULL) gets the four raw output arrays (rs bytes each, 4 (n+1) values) */
static walk_out walk_ref(int rs, int kind, int n, const double *u, const double *head, void *bits)
{
    size_t m = (size_t)n + 1;
    walk_out o;
    o.delta = malloc(4 * m * sizeof(double));
    assert_non_null(o.delta);
    o.r = o.delta + m, o.psi = o.delta + 2 * m, o.f = o.delta + 3 * m;
    const double *h = head;
    double mat[8] = {h[5], h[6], h[7], h[8], h[9], h[10], h[11], h[12]};
    if (rs == 8) {
        double *b = bits ? bits : malloc(4 * m * sizeof(double));
        dem_mdr_walk_f64(kind, n, u, mat, h[0], h[1], h[2], h[3], h[4], b, b + m, b + 2 * m, b + 3 * m);
        memcpy(o.delta, b, 4 * m * sizeof(double));
        if (!bits)
            free(b);
    } else {
        float *uf = malloc(m * sizeof(float)), matf[8], *b = bits ? bits : malloc(4 * m * sizeof(float));
        for (size_t k = 0; k < m; k++)
            uf[k] = (float)u[k];
        for (int k = 0; k < 8; k++)
            matf[k] = (float)mat[k];
        dem_mdr_walk_f32(kind, n, uf, matf, (float)h[0], (float)h[1], (float)h[2], (float)h[3], (float)h[4], b, b + m,
                         b + 2 * m, b + 3 * m);
        for (size_t k = 0; k < 4 * m; k++)
            o.delta[k] = b[k];
        free(uf);
        if (!bits)
            free(b);
    }
    return o;
}

static void fixed_ref(int rs, int which, int n, const double *x, double *y)
{
    if (rs == 8) {
        dem_mdr_fixed_f64(which, n, x, y);
        return;
    }
    float *xf = malloc((size_t)n * sizeof(float)), *yf = malloc((size_t)n * sizeof(float));
    for (int k = 0; k < n; k++)
        xf[k] = (float)x[k];
    dem_mdr_fixed_f32(which, n, xf, yf);
    for (int k = 0; k < n; k++)
        y[k] = yf[k];
    free(xf), free(yf);
}

static double ulps(double a, double b, int rs) /* |a - b| in units of b's last place in precision rs */
{
    double ulp = rs == 8 ? nextafter(fabs(b), INFINITY) - fabs(b) : (double)(nextafterf((float)fabs(b), INFINITY) -
                                                                             (float)fabs(b));
    return fabs(a - b) / ulp;
}

/* (F1, F2, F5) against the C library */
static void test_fixed_count(void **st)
{
    (void)st;
    enum { N = 4001 };
    static double x[N], y[N];
    for (int rs = 8; rs >= 4; rs -= 4) {
        double worst = 0;
        for (int k = 0; k < N; k++) /* exp over the law's range of arguments, [-80, 20] */
            x[k] = rs == 8 ? -80 + 100.0 * k / (N - 1) : (double)(float)(-80 + 100.0 * k / (N - 1));
        fixed_ref(rs, FIXED_EXP, N, x, y);
        for (int k = 0; k < N; k++)
            worst = fmax(worst, ulps(y[k], rs == 8 ? exp(x[k]) : (double)expf((float)x[k]), rs));
        printf("  %s exp: %.2f ulp at most on [-80, 20]\n", rs == 8 ? "fp64" : "fp32", worst);
        assert_true(worst <= 2.0);
        worst = 0;
        for (int k = 0; k < N; k++) /* cube root over [1e-30, 1e30] */
            x[k] = rs == 8 ? pow(10, -30 + 60.0 * k / (N - 1)) : (double)(float)pow(10, -30 + 60.0 * k / (N - 1));
        fixed_ref(rs, FIXED_CBRT, N, x, y);
        for (int k = 0; k < N; k++)
            worst = fmax(worst, ulps(y[k], rs == 8 ? cbrt(x[k]) : (double)cbrtf((float)x[k]), rs));
        printf("  %s cube root: %.2f ulp at most on [1e-30, 1e30] (the start of F3's Newton steps)\n",
               rs == 8 ? "fp64" : "fp32", worst);
        assert_true(worst <= 4.0);
        /* h(u) = acos(1 - 2u) - 2(1 - 2u) sqrt(u(1 - u)): the acos form where it keeps its digits (u >= 1e-3, in
         * long double), the series 16/3 u^(3/2) (1 - 3u/10 - 3u^2/56) below 1e-7 */
        double wa = 0, ws = 0;
        for (int k = 0; k < N; k++)
            x[k] = k < N / 2 ? pow(10, -3 + log10(0.5 / 1e-3) * k / (N / 2 - 1))
                             : pow(10, -16 + 9.0 * (k - N / 2) / (N - N / 2 - 1));
        if (rs == 4)
            for (int k = 0; k < N; k++)
                x[k] = (float)x[k];
        fixed_ref(rs, FIXED_H, N, x, y);
        for (int k = 0; k < N; k++) {
            long double u = x[k], e;
            if (k < N / 2) {
                e = acosl(1 - 2 * u) - 2 * (1 - 2 * u) * sqrtl(u * (1 - u));
                wa = fmax(wa, (double)fabsl((y[k] - e) / e));
            } else {
                e = 16.0L / 3 * u * sqrtl(u) * (1 - 0.3L * u - 3.0L / 56 * u * u);
                ws = fmax(ws, (double)fabsl((y[k] - e) / e));
            }
        }
        printf("  %s h(u): relative %.1e at most against acos on [1e-3, 0.5], %.1e against the series on [1e-16, "
               "1e-7]\n", rs == 8 ? "fp64" : "fp32", wa, ws);
        assert_true(wa <= (rs == 8 ? 1e-14 : 2e-6));
        assert_true(ws <= (rs == 8 ? 1e-14 : 2e-6));
        /* (M40) acos(c)/pi and the penalty 1/(1 + exp(-50 (acos(c)/pi - 1/2))) on c in [-1, 1] (long double) */
        for (int k = 0; k < N; k++)
            x[k] = rs == 8 ? -1 + 2.0 * k / (N - 1) : (double)(float)(-1 + 2.0 * k / (N - 1));
        fixed_ref(rs, FIXED_ACOS, N, x, y);
        wa = 0, ws = 0;
        for (int k = 0; k < N; k++)
            wa = fmax(wa, (double)fabsl(y[k] - acosl(x[k]) / 3.14159265358979323846264338327950288L));
        fixed_ref(rs, FIXED_PENALTY, N, x, y);
        for (int k = 0; k < N; k++) {
            long double e = 1 / (1 + expl(-50 * (acosl(x[k]) / 3.14159265358979323846264338327950288L - 0.5L)));
            ws = fmax(ws, (double)fabsl((y[k] - e) / e));
        }
        printf("  %s acos(c)/pi on [-1, 1]: %.1e at most; the penalty (M40): relative %.1e at most\n",
               rs == 8 ? "fp64" : "fp32", wa, ws);
        assert_true(wa <= (rs == 8 ? 1e-15 : 3e-7));
        assert_true(ws <= (rs == 8 ? 1e-13 : 1e-4));
    }
}

/* A sphere pressed on a wall below yield (no damping, no adhesion): MDR's profile of a sphere (A = 4R, B = 2R) gives
 * F = 2 E* R^2 h(delta/4R) (M7, M9) times the wall magnifier (M39), and tends to Hertz, 4/3 E* sqrt(R) delta^(3/2):
 * h's series makes F/Hertz = 1 - 3/40 delta/R - 3/896 (delta/R)^2 ..., so the deviation over delta/R lies in
 * [0.0745, 0.0752] from 0.3 % to 3 % of R */
static void test_elastic_wall(void **st)
{
    (void)st;
    read_cases();
    const walk_case *c = &cases[0];
    double head[13];
    memcpy(head, c->head, sizeof head);
    head[10] = 0, head[12] = 0; /* gamma 0, no damping */
    double r = head[0], es = head[5];
    enum { N = 400 };
    static double u[N + 1];
    for (int k = 0; k <= N; k++) /* to 3 % of R, below yield (4.3 % of R for these E and Y) */
        u[k] = 0.03 * r * k / N;
    for (int rs = 8; rs >= 4; rs -= 4) {
        walk_out o = walk_ref(rs, WALK_WALL, N, u, head, NULL);
        double wf = 0, wh = 0, wl = 1;
        for (int k = 1; k <= N; k++) {
            long double d = o.delta[k], uu = d / (4 * r); /* the overlap the law saw (fp32: R - u rounds) */
            long double h = acosl(1 - 2 * uu) - 2 * (1 - 2 * uu) * sqrtl(uu * (1 - uu));
            long double mag = 1 + expl(10.7L * d / r - 10);
            long double form = 2 * (long double)es * r * r * h * mag;
            long double hertz = 4.0L / 3 * es * sqrtl(r) * d * sqrtl(d) * mag;
            if (k < N / 10)
                continue;
            wf = fmax(wf, (double)fabsl((o.f[k] - form) / form));
            double dev = (double)(fabsl((o.f[k] - hertz) / hertz) / (d / r));
            wh = fmax(wh, dev), wl = fmin(wl, dev);
        }
        printf("  %s: elastic wall contact to 3 %% of R: |F/closed form - 1| %.1e at most (from 0.3 %% of R), "
               "|F/Hertz - 1| from %.5f to %.5f delta/R (series: 3/40 + 3/896 delta/R)\n", rs == 8 ? "fp64" : "fp32",
               wf, wl, wh);
        assert_true(wf <= (rs == 8 ? 1e-12 : 1e-5));
        assert_true(wl >= 0.0745 && wh <= 0.0752);
        free(o.delta);
    }
}

/* Every case against the Python reference */
static void test_against_reference(void **st)
{
    (void)st;
    read_cases();
    for (int i = 0; i < ncases; i++) {
        const walk_case *c = &cases[i];
        for (int rs = 8; rs >= 4; rs -= 4) {
            walk_out o = walk_ref(rs, c->kind, c->n, c->u, c->head, NULL);
            double peak = 0, least = 0, wf = 0, wr = 0, wp = 0, wt = 0;
            for (int k = 0; k <= c->n; k++)
                peak = fmax(peak, fabs(c->f[k])), least = least < c->f[k] ? least : c->f[k];
            for (int k = 0; k <= c->n; k++) {
                double d = fabs(o.f[k] - c->f[k]);
                wf = fmax(wf, d / peak);
                if (least < 0 && fmin(o.f[k], c->f[k]) < 0 && fabs(c->f[k]) < 0.01 * peak) /* the tensile branch */
                    wt = fmax(wt, d / -least);
                wr = fmax(wr, fabs(o.r[k] - c->r[k]) / c->head[0]);
                wp = fmax(wp, fabs(o.psi[k] - c->psi[k]));
            }
            printf("  %s %-10s peak %8.4f N: |F - F_python| %.1e of the peak at most%s, radius %.1e R, psi %.1e\n",
                   rs == 8 ? "fp64" : "fp32", c->name, peak, wf, least < 0 ? "" : " (no tension)", wr, wp);
            if (least < 0)
                printf("       tensile branch (least force %.4g N): %.1e of it\n", least, wt);
            /* fp64: the two differ in exp (libm against F1), h's rounding and the tensile root (bisection against
             * F4's Newton steps): 3e-15 of the peak, 2e-13 of the pull-off measured; fp32 rounds the overlap
             * R - u (5e-4 m to 3e-11 m): 3.4e-4 of the peak measured (7.2e-4 in wall_deep, 0.99 R deep), and
             * 1e-4 to 2.3e-3 of the pull-off with adhesion - but for the unequal pair, which lets go a step apart
             * (0.25 of the pull-off) */
            assert_true(wf <= (rs == 8 ? 1e-13 : 1e-3));
            assert_true(wr <= (rs == 8 ? 1e-14 : 2e-4));
            assert_true(wp <= (rs == 8 ? 1e-14 : 5e-4));
            if (rs == 8 && least < 0)
                assert_true(wt <= 1e-12);
            if (rs == 4 && c->head[10] > 0 && c->head[0] == c->head[1]) /* adhesion, equal spheres or a wall */
                assert_true(wt <= 5e-3);
            free(o.delta);
        }
    }
}

/* What the law must show whatever its numbers: a dent (zero force while the spheres still overlap) after a plastic
 * load without adhesion; a contact pressed deeper than ever before never pushes back less (down to 1.24 R of apparent
 * overlap in wall_deep: a falling force there would be a negative stiffness in a compact); with adhesion a pull many
 * times the damping's (the only tension without it) before the contact lets go; the bulk response (psi below psi_b)
 * in the box */
static void test_dent_and_pull(void **st)
{
    (void)st;
    read_cases();
    for (int rs = 8; rs >= 4; rs -= 4) {
        double least[3] = {0, 0, 0}; /* the least force without adhesion, per kind */
        for (int pass = 0; pass < 2; pass++)
            for (int i = 0; i < ncases; i++) {
                const walk_case *c = &cases[i];
                if ((c->head[10] > 0) != pass) /* the cases without adhesion first */
                    continue;
                walk_out o = walk_ref(rs, c->kind, c->n, c->u, c->head, NULL);
                int dent = 0, fresh = 0, softer = 0;
                double psi_min = 1, fmin_ = 0, umax = c->u[0];
                for (int k = 1; k <= c->n; k++) {
                    dent += o.delta[k] > 0 && o.f[k] == 0;
                    fmin_ = fmin_ < o.f[k] ? fmin_ : o.f[k];
                    psi_min = fmin(psi_min, o.psi[k]);
                    /* pressed past its deepest so far, at the same speed as the step before: it pushes back harder */
                    if (c->u[k] > umax && c->u[k - 1] >= umax && k > 1 && o.f[k - 1] > 0) {
                        fresh++;
                        softer += o.f[k] < o.f[k - 1];
                    }
                    umax = fmax(umax, c->u[k]);
                }
                printf("  %s %-10s steps overlapping without force %d; least force %.4g N; psi down to %.3f; "
                       "pressed deeper %d steps, force fell in %d\n",
                       rs == 8 ? "fp64" : "fp32", c->name, dent, fmin_, psi_min, fresh, softer);
                if (c->head[10] == 0) /* without adhesion (its first touch pulls the contact in) */
                    assert_true(fresh > 0 && softer == 0);
                if (!pass) {
                    least[c->kind] = fmin(least[c->kind], fmin_); /* the damping's pull, the largest of the kind */
                    if (c->kind != WALK_BOX)
                        assert_true(dent > 0);
                } else {
                    assert_true(fmin_ < 10 * least[c->kind]);
                }
                if (c->kind == WALK_BOX)
                    assert_true(psi_min < c->head[11]);
                free(o.delta);
            }
    }
}

static const char *walk_src =
    "#include \"laws/mdr_core.h\"\n"
    "__kernel void walk(int kind, int n, __global const real *u, __global const real *mat, real r, real r2,\n"
    "                   real m1, real m2, real dt, __global real *out)\n"
    "{\n"
    "    mdr_material m = mdr_material_from(mat);\n"
    "    mdr_walk(kind, n, u, &m, r, r2, m1, m2, dt, out, out + n + 1, out + 2 * (n + 1), out + 3 * (n + 1));\n"
    "}\n"
    "__kernel void fixed(int which, int n, __global const real *x, __global real *y)\n"
    "{\n"
    "    mdr_fixed(which, n, x, y);\n"
    "}\n";

/* The same walks, and the fixed-count functions, in an OpenCL kernel: the reference's bits */
static void test_opencl_bits(void **st)
{
    (void)st;
    read_cases();
    for (int rs = 8; rs >= 4; rs -= 4) {
        size_t r = (size_t)rs;
        test_cl t;
        test_cl_open(&t, walk_src, "walk", rs);
        cl_command_queue q = t.queue;
        int same = 0;
        for (int i = 0; i < ncases; i++) {
            const walk_case *c = &cases[i];
            size_t m = (size_t)c->n + 1;
            unsigned char *ub = malloc(m * r), *mb = malloc(8 * r), *want = malloc(4 * m * r), *got = malloc(4 * m * r);
            for (size_t k = 0; k < m; k++)
                rs == 8 ? (void)(((double *)ub)[k] = c->u[k]) : (void)(((float *)ub)[k] = (float)c->u[k]);
            for (int k = 0; k < 8; k++)
                rs == 8 ? (void)(((double *)mb)[k] = c->head[5 + k]) : (void)(((float *)mb)[k] = (float)c->head[5 + k]);
            walk_out o = walk_ref(rs, c->kind, c->n, c->u, c->head, want);
            free(o.delta);
            cl_mem bu = test_cl_buffer(&t, m * r, ub), bm = test_cl_buffer(&t, 8 * r, mb);
            cl_mem bo = test_cl_buffer(&t, 4 * m * r, NULL);
            cl_kernel k = t.kernel;
            int n = c->n;
            clSetKernelArg(k, 0, sizeof(int), &c->kind), clSetKernelArg(k, 1, sizeof(int), &n);
            clSetKernelArg(k, 2, sizeof(cl_mem), &bu), clSetKernelArg(k, 3, sizeof(cl_mem), &bm);
            for (int a = 0; a < 5; a++) {
                double v = c->head[a];
                float vf = (float)v;
                assert_int_equal(clSetKernelArg(k, 4 + a, r, rs == 8 ? (void *)&v : (void *)&vf), CL_SUCCESS);
            }
            assert_int_equal(clSetKernelArg(k, 9, sizeof(cl_mem), &bo), CL_SUCCESS);
            size_t one = 1;
            assert_int_equal(clEnqueueNDRangeKernel(q, k, 1, NULL, &one, &one, 0, NULL, NULL), CL_SUCCESS);
            assert_int_equal(clEnqueueReadBuffer(q, bo, CL_TRUE, 0, 4 * m * r, got, 0, NULL, NULL), CL_SUCCESS);
            if (memcmp(want, got, 4 * m * r)) {
                size_t e = 0;
                while (!memcmp(want + e * r, got + e * r, r))
                    e++;
                fail_msg("%s %s: OpenCL differs from the reference at output %zu of %zu (array %zu, step %zu)",
                         rs == 8 ? "fp64" : "fp32", c->name, e, 4 * m, e / m, e % m);
            }
            same++;
            clReleaseMemObject(bu), clReleaseMemObject(bm), clReleaseMemObject(bo);
            free(ub), free(mb), free(want), free(got);
        }
        /* the fixed-count functions over their ranges */
        cl_int e;
        cl_kernel kf = clCreateKernel((cl_program)t.program, "fixed", &e);
        assert_int_equal(e, CL_SUCCESS);
        enum { N = 4001 };
        static double x[N], y[N];
        for (int which = 0; which < 5; which++) {
            unsigned char xb[N * 8], want[N * 8], got[N * 8];
            for (int k = 0; k < N; k++) {
                double v = which == FIXED_EXP    ? -80 + 100.0 * k / (N - 1)
                           : which == FIXED_H    ? 0.5 * pow(10, -16 + 16.0 * k / (N - 1))
                           : which == FIXED_CBRT ? pow(10, -30 + 60.0 * k / (N - 1))
                                                 : -1 + 2.0 * k / (N - 1);
                x[k] = rs == 8 ? v : (double)(float)v;
                rs == 8 ? (void)(((double *)xb)[k] = v) : (void)(((float *)xb)[k] = (float)v);
            }
            fixed_ref(rs, which, N, x, y);
            for (int k = 0; k < N; k++)
                rs == 8 ? (void)(((double *)want)[k] = y[k]) : (void)(((float *)want)[k] = (float)y[k]);
            cl_mem bx = test_cl_buffer(&t, N * r, xb), by = test_cl_buffer(&t, N * r, NULL);
            int n = N;
            clSetKernelArg(kf, 0, sizeof(int), &which), clSetKernelArg(kf, 1, sizeof(int), &n);
            clSetKernelArg(kf, 2, sizeof(cl_mem), &bx), clSetKernelArg(kf, 3, sizeof(cl_mem), &by);
            size_t one = 1;
            assert_int_equal(clEnqueueNDRangeKernel(q, kf, 1, NULL, &one, &one, 0, NULL, NULL), CL_SUCCESS);
            assert_int_equal(clEnqueueReadBuffer(q, by, CL_TRUE, 0, N * r, got, 0, NULL, NULL), CL_SUCCESS);
            if (memcmp(want, got, N * r))
                fail_msg("%s fixed-count function %d: OpenCL differs from the reference", rs == 8 ? "fp64" : "fp32",
                         which);
            clReleaseMemObject(bx), clReleaseMemObject(by);
        }
        clReleaseKernel(kf);
        test_cl_close(&t);
        printf("  OpenCL %s: %d walks and 5 fixed-count functions, the reference's bits\n", rs == 8 ? "fp64" : "fp32",
               same);
    }
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_fixed_count), cmocka_unit_test(test_elastic_wall),
                                       cmocka_unit_test(test_against_reference), cmocka_unit_test(test_dent_and_pull),
                                       cmocka_unit_test(test_opencl_bits)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
