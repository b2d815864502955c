/* test_mc_validation.c - the multi-contact models against seed 000's validation cases (section 3.3, 3.4).
 *  - 3 and 5 spheres (hydrogel, rubber; r = 1 cm, 10 m/s, dt 1e-5 / 2e-5 s): the multi-contact models reach the
 *    central particle's largest overlap earlier than classical DEM and MC-stress has the lowest largest overlap.
 *  - 5 spheres squeezed in a box from [-0.03,0.03]^2 to [-0.025,0.025]^2 at constant engineering strain: MC-stress
 *    against the quasi-static closed form derived in docs/multicontact.md, within 1 %.
 *  - one rubber sphere between rigid plates to d/r = 0.4 (gamma 0.55, beta 1.71): Hertz below d/r = 0.1 for every
 *    model, both multi-contact models stiffer above it.
 * Numbers measured here are printed so the closing note can quote them. */
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { CLASSIC, MC_STRESS, MC_STRAIN, MC_STRAIN_IT, NMODEL };
static const char *model_name[NMODEL] = {"classical", "MC-stress", "MC-strain lagged", "MC-strain iterated"};

static void set_model(dem_sim *s, unsigned base, int model)
{
    unsigned fx = base | (model == MC_STRESS ? DEM_EFFECT_MC_STRESS : model >= MC_STRAIN ? DEM_EFFECT_MC_STRAIN : 0);
    assert_int_equal(dem_set_effects(s, fx), 0);
    if (model == MC_STRAIN_IT)
        assert_int_equal(dem_set_mc_strain(s, 50, 1e-8), 0);
}

static const dem_material hydrogel = {11.5, 23.3e3, 0.5, 0.95, 0.03, 1.65, 1.12};
static const dem_material rubber = {2000, 1.85e6, 0.46, 0.7, 0.5, 1.71, 0.55};

typedef struct {
    double max_overlap, t_max; /* central particle's overlap with its +x neighbour, as the normal law sees it */
    double max_geometric;      /* the geometric overlap alone */
    double ke_min;             /* smallest kinetic energy during the collision [J] */
} collision;

/* n = 3: spheres at x = -2r, 0, 2r, the outer ones moving in at 10 m/s; n = 5 adds two on the y axis. */
static collision spheres(const dem_material *m, int n, int model, double dt)
{
    const double r = 0.01, v = 10;
    dem_sim *s = dem_create();
    int mat = dem_add_material(s, m);
    double pos[5][3] = {{0, 0, 0}, {2 * r, 0, 0}, {-2 * r, 0, 0}, {0, 2 * r, 0}, {0, -2 * r, 0}};
    for (int i = 0; i < n; i++) {
        double vel[3] = {-v * pos[i][0] / (2 * r), -v * pos[i][1] / (2 * r), 0};
        dem_add_particle(s, pos[i], vel, r, mat);
    }
    dem_set_domain(s, (double[3]){-0.1, -0.1, -0.1}, (double[3]){0.1, 0.1, 0.1});
    dem_set_dt(s, dt);
    set_model(s, DEM_EFFECT_HERTZ | DEM_EFFECT_DAMPING | DEM_EFFECT_FRICTION, model);
    dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    start_or_fail(s, &c);
    collision col = {0, 0, 0, INFINITY};
    for (int step = 1; step <= 600; step++) {
        step_or_fail(s, 1);
        double x[15];
        assert_int_equal(dem_get_field(s, FIELD_X, x), 0);
        double g = 2 * r - sqrt((x[3] - x[0]) * (x[3] - x[0]) + (x[4] - x[1]) * (x[4] - x[1]) +
                                (x[5] - x[2]) * (x[5] - x[2]));
        double d = g;
        if (model >= MC_STRAIN && g > 0) { /* MC-strain adds the induced displacements of both particles (Eq. 8) */
            int cnt[5], list[5 * 64], maxn = dem_neighbor_capacity(s);
            double disp[5 * 64];
            assert_true(maxn <= 64);
            assert_int_equal(dem_get_raw(s, FIELD_NBR_COUNT, cnt, sizeof(int) * n), 0);
            assert_int_equal(dem_get_raw(s, FIELD_NBR_LIST, list, sizeof(int) * n * maxn), 0);
            assert_int_equal(dem_get_field(s, FIELD_MC_DISP, disp), 0);
            for (int k = 0; k < cnt[0]; k++)
                if (list[k] == 1)
                    d += disp[k];
            for (int k = 0; k < cnt[1]; k++)
                if (list[maxn + k] == 0)
                    d += disp[maxn + k];
        }
        col.max_geometric = fmax(col.max_geometric, g);
        if (d > col.max_overlap) {
            col.max_overlap = d;
            col.t_max = dem_time(s);
        }
        dem_energy_t e;
        assert_int_equal(dem_energy(s, &e), 0);
        col.ke_min = fmin(col.ke_min, e.kinetic);
        if (d < 0 && step > 10)
            break; /* separated */
    }
    dem_destroy(s);
    return col;
}

static void collisions(const char *what, const dem_material *m, double dt)
{
    for (int n = 3; n <= 5; n += 2) {
        collision c[NMODEL];
        for (int k = 0; k < NMODEL; k++) {
            c[k] = spheres(m, n, k, dt);
            printf("# %s, %d spheres, %-18s: max overlap %.4f mm (geometric %.4f mm) at t = %.3f ms, min kinetic "
                   "energy %.4g J\n", what, n, model_name[k], 1e3 * c[k].max_overlap, 1e3 * c[k].max_geometric,
                   1e3 * c[k].t_max, c[k].ke_min);
        }
        for (int k = 1; k < NMODEL; k++) {
            assert_true(c[k].t_max < c[CLASSIC].t_max);                  /* the peak comes earlier */
            assert_true(c[k].max_geometric < c[CLASSIC].max_geometric); /* the particles resist more */
        }
        /* seed 000 section 3.4: MC-stress has the lowest largest overlap, MC-strain (whose law adds overlap) the
         * highest */
        assert_true(c[MC_STRESS].max_overlap < c[CLASSIC].max_overlap);
        assert_true(c[MC_STRESS].max_overlap < c[MC_STRAIN].max_overlap);
        assert_true(c[MC_STRESS].max_overlap < c[MC_STRAIN_IT].max_overlap);
        assert_true(c[MC_STRAIN].max_overlap > c[CLASSIC].max_overlap);
    }
}

static void test_three_five_spheres(void **st)
{
    (void)st;
    collisions("hydrogel", &hydrogel, 1e-5);
    collisions("rubber", &rubber, 2e-5);
}

/* ---- five spheres in a shrinking box: MC-stress against its closed form ----
 * Quasi-static equilibrium of an outer sphere: centre contact (r* = r/2, E*_pp) and wall contact (r* = r, E*_pw)
 * carry the same force, with overlaps dc + dw = s (the wall travel). With t_c = (r - dc/2) f_c / V and
 * t_w = (r - dw) f_w / V the trace terms (sign dropped: pressures), the centre's pressure without contact c is
 * 3 t_c / 3 = t_c' (three other centre contacts), the outer sphere's without c is t_w / 3 and without w is t_c / 3:
 *   F_c = f_H(dc, r/2) + pi beta nu (r/2) dc (3 t_c / 3 + t_w / 3) / 2
 *   F_w = f_H(dw, r)   + pi beta nu r dw (t_c / 3)
 * (appendix /6 = mean of the two pressures; each contact's own term removed; docs/multicontact.md). */
static double hertz(double estar, double rstar, double d) { return 4.0 / 3.0 * estar * sqrt(rstar * d) * d; }

static void box_closed_form(double s, double r, double epp, double epw, double bnu, double *fc_out, double *fw_out)
{
    double V = 4.0 / 3.0 * M_PI * r * r * r, lo = 0, hi = s;
    double fc = 0, fw = 0;
    for (int it = 0; it < 200; it++) { /* bisection on dc: F_c(dc) - F_w(s - dc) is increasing */
        double dc = 0.5 * (lo + hi), dw = s - dc;
        double hc = hertz(epp, r / 2, dc), hw = hertz(epw, r, dw);
        double tc = (r - dc / 2) * hc / V, tw = (r - dw) * hw / V;
        fc = hc + M_PI * bnu * (r / 2) * dc * (tc + tw / 3) / 2;
        fw = hw + M_PI * bnu * r * dw * (tc / 3);
        if (fc > fw)
            hi = dc;
        else
            lo = dc;
    }
    *fc_out = fc;
    *fw_out = fw;
}

static void test_five_in_box_closed_form(void **st)
{
    (void)st;
    const double r = 0.01, strain = 0.005 / 0.03; /* each x and y wall travels 5 mm */
    dem_material gel = hydrogel;
    dem_sim *s = dem_create();
    int mat = dem_add_material(s, &gel);
    double pos[5][3] = {{0, 0, 0}, {2 * r, 0, 0}, {-2 * r, 0, 0}, {0, 2 * r, 0}, {0, -2 * r, 0}};
    for (int i = 0; i < 5; i++)
        dem_add_particle(s, pos[i], NULL, r, mat);
    /* walls: x-, x+, y-, y+ move in at 1 cm/s for 0.5 s and rest 0.3 s; z planes stay */
    const double T = 0.5, u = 0.005 / T;
    int first = dem_add_box(s, (double[3]){-0.03, -0.03, -0.01}, (double[3]){0.03, 0.03, 0.01}, mat);
    for (int k = 0; k < 4; k++) {
        int axis = k / 2, upper = k % 2;
        dem_stage st2[2] = {{T, {0, 0, 0}}, {0.3, {0, 0, 0}}};
        st2[0].velocity[axis] = upper ? -u : u;
        assert_int_equal(dem_set_wall_motion(s, first + k, 2, st2), 0);
    }
    dem_set_domain(s, (double[3]){-0.05, -0.05, -0.05}, (double[3]){0.05, 0.05, 0.05});
    dem_set_dt(s, 1e-5);
    set_model(s, DEM_EFFECT_HERTZ | DEM_EFFECT_DAMPING | DEM_EFFECT_WALLS, MC_STRESS);
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, DEM_FP64);
    start_or_fail(s, &c);
    double es = 1 / (2 * (1 - 0.25) / 23.3e3); /* same material for particles and walls */
    double worst = 0;
    for (int k = 1; k <= 8; k++) { /* sample during the compression and at rest */
        long target = (long)llround((k <= 5 ? 0.1 * k : T + 0.1 * (k - 5)) / 1e-5);
        step_or_fail(s, target - dem_step_index(s));
        double p[3], f[3], fc, fw;
        dem_wall_position(s, first + 1, p);
        dem_wall_force(s, first + 1, f);
        double travel = 0.03 - p[0], fc0, fw0;
        box_closed_form(travel, r, es, es, 1.65 * 0.5, &fc, &fw);
        box_closed_form(travel, r, es, es, 0, &fc0, &fw0);
        double err = fabs(f[0] - fw) / fw; /* the x+ wall is pushed towards +x */
        printf("# five in a box: t %.2f s, strain %.4f: wall force %.6g N, closed form %.6g N (classical %.6g N), "
               "error %.3f %%\n", dem_time(s), travel / 0.03, f[0], fw, fw0, 100 * err);
        worst = fmax(worst, err);
        if (k >= 5) /* and at full strain the model is measurably not classical */
            assert_true(f[0] > 1.02 * fw0);
    }
    assert_true(fabs(0.03 - 0.025 - 0.005) < 1e-12 && strain > 0);
    assert_true(worst < 0.01);
    dem_destroy(s);
}

/* ---- one rubber sphere between rigid plates (section 3.3) ---- */
static void test_sphere_between_plates(void **st)
{
    (void)st;
    const double r = 0.01, total = 0.4 * r, T = 0.2, u = total / 2 / T;
    dem_material steel = {7800, 200e9, 0.3, 0.7, 0.5, 0, 0};
    double f_at[NMODEL][4];
    const double marks[4] = {0.05, 0.1, 0.2, 0.4}; /* d / r, d the sum of both plate travels */
    for (int model = 0; model < NMODEL; model++) {
        dem_sim *s = dem_create();
        int rub = dem_add_material(s, &rubber), pl = dem_add_material(s, &steel);
        dem_add_particle(s, (double[3]){0, 0, 0}, NULL, r, rub);
        dem_wall w = {DEM_WALL_PLANE, pl, {0, 0, -r}, {0, 0, 1}, 0, 1, {{T, {0, 0, u}}}};
        dem_add_wall(s, &w);
        dem_wall w2 = {DEM_WALL_PLANE, pl, {0, 0, r}, {0, 0, -1}, 0, 1, {{T, {0, 0, -u}}}};
        dem_add_wall(s, &w2);
        dem_set_domain(s, (double[3]){-0.05, -0.05, -0.05}, (double[3]){0.05, 0.05, 0.05});
        dem_set_dt(s, 2e-5);
        set_model(s, DEM_EFFECT_HERTZ | DEM_EFFECT_WALLS, model); /* undamped: by symmetry the sphere stays put */
        dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
        start_or_fail(s, &c);
        for (int k = 0; k < 4; k++) {
            long target = (long)llround(marks[k] / 0.4 * T / 2e-5);
            step_or_fail(s, target - dem_step_index(s));
            double f[3];
            dem_wall_force(s, 1, f);
            f_at[model][k] = f[2];
        }
        dem_destroy(s);
    }
    double es = 1 / ((1 - 0.46 * 0.46) / 1.85e6 + (1 - 0.09) / 200e9);
    for (int k = 0; k < 4; k++) {
        double h = hertz(es, r, marks[k] * r / 2);
        printf("# plates d/r = %.2f: Hertz %.4f N; classical %.4f, MC-stress %.4f, MC-strain %.4f, iterated %.4f N\n",
               marks[k], h, f_at[CLASSIC][k], f_at[MC_STRESS][k], f_at[MC_STRAIN][k], f_at[MC_STRAIN_IT][k]);
    }
    for (int k = 0; k < 4; k++) {
        double h = hertz(es, r, marks[k] * r / 2);
        assert_true(fabs(f_at[CLASSIC][k] - h) < 1e-6 * h);
        for (int m = 1; m < NMODEL; m++) {
            if (marks[k] <= 0.1)
                assert_true(fabs(f_at[m][k] - h) < 0.1 * h); /* close to Hertz at small deformation */
            assert_true(f_at[m][k] > h);                      /* stiffer, and more so ... */
        }
    }
    for (int m = 1; m < NMODEL; m++) /* ... at d/r = 0.4 than at 0.1, relative to Hertz */
        assert_true(f_at[m][3] / hertz(es, r, 0.2 * r) > f_at[m][1] / hertz(es, r, 0.05 * r));
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sphere_between_plates),
        cmocka_unit_test(test_three_five_spheres),
        cmocka_unit_test(test_five_in_box_closed_form),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
