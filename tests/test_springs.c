/* test_springs.c - the kernels spring_forces, channel_gather and their reference twins, on every backend x
 * precision: two particles on a spring oscillate with the period 2 pi sqrt(m_eff / k) (undamped, energy kept to the
 * integrator's error) and, damped with ratio gamma, lose amplitude by exp(-2 pi gamma / sqrt(1 - gamma^2)) per period
 * (seed 001 Eq. 6 read as a damped oscillator: common/springs.h); the two ends' forces are exact negations; a particle
 * on three springs gets them added in spring order (bitwise equal to the reference); a flat equilateral sheet of
 * springs has the 2D Young's modulus 2k/sqrt(3) and Poisson's ratio 1/3 (seed 001's sheet). The time-step bound
 * includes the spring period; springs need their effect. */
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

#define K_SPRING 50.0
#define R 0.001

static double mass0(void) { return 2500 * 4.0 / 3.0 * M_PI * R * R * R; }
static double period(void) { return 2 * M_PI * sqrt(0.5 * mass0() / K_SPRING); }

typedef struct {
    double gamma;
    double t_half[64];  /* times the extension rate changed sign */
    double peak[64];    /* |extension| there */
    int nturn;
    double e0, worst_e; /* energy at the start, largest relative change (undamped) */
} osc;

static dem_sim *build(void *ctx)
{
    const osc *o = ctx;
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0});
    int a = dem_add_particle(s, (double[3]){0, 0, 0}, NULL, R, m);
    int b = dem_add_particle(s, (double[3]){0.05, 0, 0}, NULL, R, m);
    assert_int_equal(dem_add_spring(s, a, b, K_SPRING, 0.04, o->gamma), 0); /* stretched by 1 cm */
    dem_set_domain(s, (double[3]){-0.1, -0.1, -0.1}, (double[3]){0.2, 0.1, 0.1});
    dem_set_dt(s, period() / 400);
    return s;
}

static void check(dem_sim *s, const backend_case *bc, void *ctx)
{
    osc *o = ctx;
    double T = period(), dt = dem_dt(s), x[6], v[6], f[6], prev_rate = 0;
    o->nturn = 0, o->worst_e = 0;
    dem_energy_t e;
    assert_int_equal(dem_energy(s, &e), 0);
    o->e0 = e.total;
    /* the extension 0.01 m is a difference of coordinates near 0.05 m: rounded to 5 eps of that, twice in the square */
    assert_true(fabs(e.elastic - 0.5 * K_SPRING * 0.01 * 0.01) < 20 * bc->eps * 5 * e.elastic);
    for (long k = 0; k < 2400 && o->nturn < 64; k++) { /* 6 periods */
        step_or_fail(s, 1);
        dem_get_field(s, DEM_FIELD_X, x);
        dem_get_field(s, DEM_FIELD_V, v);
        dem_get_field(s, DEM_FIELD_FORCE, f);
        for (int q = 0; q < 3; q++)
            assert_true(f[q] == -f[3 + q]); /* the ends' forces are exact negations */
        double ext = (x[3] - x[0]) - 0.04, rate = v[3] - v[0];
        if (k > 0 && ((prev_rate > 0) != (rate > 0))) { /* a turning point, interpolated */
            double a = prev_rate / (prev_rate - rate);
            o->t_half[o->nturn] = dem_time(s) - dt + a * dt;
            o->peak[o->nturn++] = fabs(ext);
        }
        prev_rate = rate;
        if (o->gamma == 0 && k % 40 == 0) {
            assert_int_equal(dem_energy(s, &e), 0);
            o->worst_e = fmax(o->worst_e, fabs(e.total / o->e0 - 1));
        }
    }
    assert_true(o->nturn >= 8);
    double measured = 2 * (o->t_half[o->nturn - 1] - o->t_half[1]) / (o->nturn - 2);
    double Td = T / sqrt(1 - o->gamma * o->gamma);
    printf("  %s, gamma %.2f: period %.8g s (closed form %.8g s, relative %.2g)", bc->name, o->gamma, measured, Td,
           measured / Td - 1);
    /* undamped: velocity Verlet's period error (omega dt)^2 / 24 = 1e-5 at 400 steps per period; damped: the
     * damping reads the half-step velocity, a first-order shift of about gamma omega dt = 8e-4 */
    assert_true(fabs(measured / Td - 1) < (o->gamma == 0 ? 1e-4 : 2e-3));
    if (o->gamma == 0) {
        printf(", energy kept to %.2g\n", o->worst_e);
        assert_true(o->worst_e < 1e-3);
    } else { /* amplitude over one period: two turning points apart */
        double ratio = o->peak[4] / o->peak[2], want = exp(-2 * M_PI * o->gamma / sqrt(1 - o->gamma * o->gamma));
        printf(", amplitude ratio per period %.6f (closed form %.6f)\n", ratio, want);
        assert_true(fabs(ratio / want - 1) < 0.01);
    }
}

static void test_undamped_period(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    {
        osc o = {0};
        backend_run(bc, build, 0, check, &o);
    }
}

static void test_damped_decay(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    {
        osc o = {0.05};
        backend_run(bc, build, 0, check, &o);
    }
}

/* A particle on three springs (a star of four), run 300 steps: the channel adds each particle's records in spring
 * order, so OpenCL equals the reference bit for bit (backend_run compares the states). */
static dem_sim *build_star(void *ctx)
{
    (void)ctx;
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0});
    int c = dem_add_particle(s, (double[3]){0, 0, 0}, (double[3]){0.01, -0.02, 0.03}, R, m);
    double ends[3][3] = {{0.02, 0.001, 0}, {-0.011, 0.017, 0.002}, {0.003, -0.009, -0.018}};
    for (int k = 0; k < 3; k++) {
        int e = dem_add_particle(s, ends[k], NULL, R, m);
        assert_int_equal(dem_add_spring(s, c, e, K_SPRING * (1 + k), -1, 0.1 * k), k); /* rest: the start */
    }
    dem_set_domain(s, (double[3]){-0.05, -0.05, -0.05}, (double[3]){0.05, 0.05, 0.05});
    dem_set_dt(s, period() / 400);
    return s;
}

static void check_star(dem_sim *s, const backend_case *bc, void *ctx)
{
    (void)ctx;
    double f[12];
    assert_int_equal(dem_get_field(s, DEM_FIELD_FORCE, f), 0);
    double sum[3] = {0, 0, 0}, big = 0;
    for (int i = 0; i < 4; i++)
        for (int q = 0; q < 3; q++)
            sum[q] += f[3 * i + q], big = fmax(big, fabs(f[3 * i + q]));
    for (int q = 0; q < 3; q++) /* the total of internal forces vanishes up to the centre's rounded sum */
        assert_true(fabs(sum[q]) <= 8 * bc->eps * big);
    assert_true(big > 0);
}

static void test_star_order(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    backend_run(bc, build_star, 300, check_star, NULL);
}

/* Seed 001's stretching law on a flat equilateral sheet: springs of stiffness k on the edges of a
 * triangular lattice of spacing a make a 2D elastic sheet of Young's modulus 2k/sqrt(3) (= E d for the paper's
 * k = (sqrt(3)/2) E d) and Poisson's ratio 1/3. The sheet is given the affine strain (ex, ey); the force across a cut
 * is the sum of the forces on the vertices on one side of it (the springs inside a side cancel), which is exact for
 * an affine strain - no boundary layer. Two values of ey give, by linear interpolation, the ey at which the force
 * across a horizontal cut vanishes (uniaxial stress: nu = -ey / ex) and the force across a vertical cut there
 * (E2D = force / (height ex)). */
#define SHEET_NX 12
#define SHEET_NY 9
#define SHEET_A 0.01
#define SHEET_EX 1e-3

typedef struct {
    double ey;
    double fx_cut, fy_cut; /* force on the right half along x, on the top half along y [N] */
} sheet;

static dem_sim *build_sheet(void *ctx)
{
    const sheet *sh = ctx;
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0});
    double h = SHEET_A * sqrt(3) / 2, x0 = -SHEET_A * SHEET_NX / 2, y0 = -h * SHEET_NY / 2;
    for (int j = 0; j < SHEET_NY; j++)
        for (int i = 0; i < SHEET_NX; i++) {
            double p[3] = {(x0 + SHEET_A * (i + 0.5 * (j % 2))) * (1 + SHEET_EX), (y0 + h * j) * (1 + sh->ey), 0};
            dem_add_particle(s, p, NULL, 0.1 * SHEET_A, m);
        }
#define V(i, j) ((j) * SHEET_NX + (i))
    for (int j = 0; j < SHEET_NY; j++)
        for (int i = 0; i < SHEET_NX; i++) {
            if (i + 1 < SHEET_NX)
                dem_add_spring(s, V(i, j), V(i + 1, j), K_SPRING, SHEET_A, 0);
            if (j + 1 < SHEET_NY) {
                int other = j % 2 ? i + 1 : i - 1; /* the two neighbours in the row above */
                dem_add_spring(s, V(i, j), V(i, j + 1), K_SPRING, SHEET_A, 0);
                if (other >= 0 && other < SHEET_NX)
                    dem_add_spring(s, V(i, j), V(other, j + 1), K_SPRING, SHEET_A, 0);
            }
        }
#undef V
    dem_set_domain(s, (double[3]){-0.1, -0.1, -0.05}, (double[3]){0.1, 0.1, 0.05});
    dem_set_dt(s, period() / 400);
    return s;
}

static void check_sheet(dem_sim *s, const backend_case *bc, void *ctx)
{
    (void)bc;
    sheet *sh = ctx;
    int n = SHEET_NX * SHEET_NY;
    double x[3 * SHEET_NX * SHEET_NY], f[3 * SHEET_NX * SHEET_NY];
    assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
    assert_int_equal(dem_get_field(s, DEM_FIELD_FORCE, f), 0);
    sh->fx_cut = sh->fy_cut = 0;
    for (int i = 0; i < n; i++) { /* the cuts pass between vertices: x = -a/4 (strained), y = 0 between rows 4, 5 */
        if (x[3 * i] > -0.25 * SHEET_A)
            sh->fx_cut += f[3 * i];
        if (i / SHEET_NX >= SHEET_NY / 2 + 1)
            sh->fy_cut += f[3 * i + 1];
    }
}

static void test_sheet_moduli(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    {
        sheet a = {0}, b = {-0.5 * SHEET_EX};
        backend_run(bc, build_sheet, 0, check_sheet, &a);
        backend_run(bc, build_sheet, 0, check_sheet, &b);
        double t = a.fy_cut / (a.fy_cut - b.fy_cut);       /* where the horizontal cut carries nothing */
        double ey = a.ey + t * (b.ey - a.ey), fx = a.fx_cut + t * (b.fx_cut - a.fx_cut);
        double nu = -ey / SHEET_EX, height = SHEET_NY * SHEET_A * sqrt(3) / 2;
        double e2d = -fx / (height * SHEET_EX), want = 2 * K_SPRING / sqrt(3); /* tension pulls the right half left */
        printf("  %s: 2D Young's modulus %.6g N/m (2k/sqrt(3) = %.6g, relative %.2g), Poisson's ratio %.6f "
               "(1/3: relative %.2g)\n", bc->name, e2d, want, e2d / want - 1, nu, 3 * nu - 1);
        assert_true(fabs(e2d / want - 1) < 1e-2 && fabs(3 * nu - 1) < 1e-2);
    }
}

/* The time-step bound holds 10 steps per spring period; springs need their effect. */
static void test_bound_and_effect(void **st)
{
    (void)st;
    osc o = {0};
    dem_sim *s = build(&o);
    dem_time_scales ts;
    assert_int_equal(dem_time_scales_get(s, 0, &ts), 0);
    assert_true(fabs(ts.spring_period / period() - 1) < 1e-12);
    assert_true(ts.max_dt <= ts.spring_period / 10 * (1 + 1e-12) && ts.recommended_dt <= ts.spring_period / 50);
    dem_set_dt(s, period() / 5);
    dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    assert_int_equal(dem_start(s, &c), DEM_ERR_DT);
    dem_destroy(s);
    s = build(&o);
    assert_int_equal(dem_set_effects(s, DEM_EFFECT_HERTZ), 0);
    assert_int_equal(dem_start(s, &c), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "springs are defined but the effect 'springs' is off"));
    assert_int_equal(dem_add_spring(s, 0, 0, 1, 0, 0), DEM_ERR_ARG);
    assert_int_equal(dem_add_spring(s, 0, 1, -1, 0, 0), DEM_ERR_ARG);
    dem_destroy(s);
    /* particles a spring joins by id are not sorted (dem_sort_particles): refused, nothing moved */
    s = build(&o);
    assert_int_equal(dem_sort_particles(s), DEM_ERR_STATE);
    assert_non_null(strstr(dem_error(s), "before any spring"));
    assert_int_equal(dem_particle_source(s, 1), 1);
    assert_true(dem_particle_radius(s, 0) == R);
    dem_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_undamped_period),
        cmocka_unit_test(test_damped_decay),
        cmocka_unit_test(test_star_order),
        cmocka_unit_test(test_sheet_moduli),
        cmocka_unit_test(test_bound_and_effect),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
