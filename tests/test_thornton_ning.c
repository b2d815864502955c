/* test_thornton_ning.c - the elastic-perfectly plastic law of common/laws/thornton_ning.h against closed forms typed in
 * here from the papers (C. Thornton, J. Appl. Mech. 64 (1997) 383; Thornton and Ning, Powder Technol. 99 (1998) 154),
 * not taken from the library:
 *   yield at delta_y = (pi p_y / (2 E*))^2 R*, F_y = 4/3 E* sqrt(R*) delta_y^(3/2); loading F = F_y + pi p_y R*
 *   (delta - delta_y); unloading from (delta_m, F_m) along 4/3 E* sqrt(R_p) (delta - delta_p)^(3/2) with
 *   R_p = (4 E* / (3 F_m)) ((2 F_m + F_y) / (2 pi p_y))^(3/2) and delta_p = delta_m - (3 F_m / (4 E* sqrt(R_p)))^(2/3)
 *   (the papers' forms, with their powers: the library writes them without);
 *   the coefficient of restitution of an impact at V_i > V_y (Thornton 1997):
 *   e = sqrt(6 sqrt(3) / 5) sqrt(1 - (V_y/V_i)^2 / 6) [ (V_y/V_i) / (V_y/V_i + 2 sqrt(6/5 - (V_y/V_i)^2 / 5)) ]^(1/4),
 *   V_y the impact speed that just reaches yield (1/2 m* V_y^2 = 8/15 E* sqrt(R*) delta_y^(5/2)).
 * Cases: two spheres and a sphere on a wall colliding at 5 V_y (force at every step, the rebound speed, the energy the
 * host reports and the stress output on unloading); a fixed sphere pressed, released part way, pressed again past the
 * first maximum and released by a moving plane (the loading-unloading-reloading curve, from the wall's force); a
 * packing of plastic spheres under a moving lid, restarted from a saved state, run with another skin and stored anew
 * at every rebuild (the law's state must survive checkpoints, neighbour rebuilds and reordering bit for bit). Every
 * case on the reference and on OpenCL (PoCL), in fp64 and fp32, the OpenCL state equal to the reference's at every
 * step. */
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

#define RHO 1500.0
#define YOUNG 5e9
#define NU 0.3
#define PY 2e8 /* p_y [Pa] */
#define R 1e-3

/* The papers' law, in double, from E*, R*, p_y; dmax the largest overlap so far (the test keeps it) */
typedef struct {
    double es, rs, dy, fy;
} tn_closed;

static tn_closed tn_of(double es, double rs)
{
    tn_closed t = {es, rs, pow(M_PI * PY / (2 * es), 2) * rs, 0};
    t.fy = 4.0 / 3.0 * es * sqrt(rs) * pow(t.dy, 1.5);
    return t;
}

static double tn_force(const tn_closed *t, double d, double dmax)
{
    if (d <= 0)
        return 0;
    if (d >= dmax) /* loading */
        return d <= t->dy ? 4.0 / 3.0 * t->es * sqrt(t->rs) * pow(d, 1.5) : t->fy + M_PI * PY * t->rs * (d - t->dy);
    if (dmax <= t->dy)
        return 4.0 / 3.0 * t->es * sqrt(t->rs) * pow(d, 1.5);
    double fm = t->fy + M_PI * PY * t->rs * (dmax - t->dy);
    double rp = 4 * t->es / (3 * fm) * pow((2 * fm + t->fy) / (2 * M_PI * PY), 1.5);
    double dp = dmax - pow(3 * fm / (4 * t->es * sqrt(rp)), 2.0 / 3.0);
    return d > dp ? 4.0 / 3.0 * t->es * sqrt(rp) * pow(d - dp, 1.5) : 0;
}

static double tn_energy(const tn_closed *t, double d, double dmax) /* 2/5 F (delta - delta_p) */
{
    if (dmax <= t->dy)
        return 0.4 * tn_force(t, d, dmax) * d;
    double fm = t->fy + M_PI * PY * t->rs * (dmax - t->dy);
    double rp = 4 * t->es / (3 * fm) * pow((2 * fm + t->fy) / (2 * M_PI * PY), 1.5);
    double dp = dmax - pow(3 * fm / (4 * t->es * sqrt(rp)), 2.0 / 3.0);
    return d > dp ? 0.4 * tn_force(t, d, dmax) * (d - dp) : 0;
}

static double restitution_thornton(double vy, double vi)
{
    double r = vy / vi;
    return sqrt(6 * sqrt(3) / 5) * sqrt(1 - r * r / 6) * pow(r / (r + 2 * sqrt(6.0 / 5 - r * r / 5)), 0.25);
}

static double sphere_mass(void) { return RHO * 4.0 / 3.0 * M_PI * R * R * R; }

static dem_material powder(void)
{
    dem_material m = {RHO, YOUNG, NU, 1.0, 0.0, 0.0, 0.0, PY};
    return m;
}
static dem_material steel(void) /* rigid, does not yield: the pair is the sphere's */
{
    dem_material m = {7800, INFINITY, 0.3, 1.0, 0.0, 0.0, 0.0, 0.0};
    return m;
}

static dem_sim *collision_build(int wall, double v, double dt)
{
    dem_material m = powder(), w = steel();
    return head_on_build(&m, wall ? &w : NULL, R, v,
                         DEM_EFFECT_HERTZ | DEM_EFFECT_THORNTON_NING | (wall ? DEM_EFFECT_WALLS : 0), dt);
}

static void collide(int wall, dem_precision prec)
{
    double es = wall ? YOUNG / (1 - NU * NU) : YOUNG / (2 * (1 - NU * NU)), rs = wall ? R : R / 2;
    double ms = wall ? sphere_mass() : sphere_mass() / 2;
    tn_closed t = tn_of(es, rs);
    double vy = sqrt(2 * 0.4 * t.fy * t.dy / ms), vi = 5 * vy;
    /* Hertz's contact time at vi bounds this one from above (the plastic line is softer): 2000 steps in it */
    double tc = 2.87 * pow(ms * ms / (rs * es * es * vi), 0.2), dt = tc / 2000;
    double tol = prec == DEM_FP64 ? 1e-9 : 3e-3;
    dem_sim *cl = collision_build(wall, vi, dt), *ref = collision_build(wall, vi, dt);
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, prec), rc = cfg_of(DEM_BACKEND_REFERENCE, prec);
    start_or_fail(cl, &c);
    start_or_fail(ref, &rc);
    double dmax = 0, worst_f = 0, worst_e = 0, worst_s = 0, fscale = 0, dp_seen = -1;
    int was = 0, plastic = 0, unload = 0;
    for (int k = 0; k < 20000; k++) {
        twins_step(cl, ref, 1, wall ? "wall, PoCL vs reference" : "pair, PoCL vs reference");
        double x[6], f[6];
        assert_int_equal(dem_get_field(ref, DEM_FIELD_X, x), 0);
        assert_int_equal(dem_get_field(ref, DEM_FIELD_FORCE, f), 0);
        double d = wall ? R - x[0] : 2 * R - fabs(x[3] - x[0]);
        if (d <= 0) {
            if (was)
                break;
            continue;
        }
        was = 1;
        dmax = fmax(dmax, d);
        plastic += d > t.dy && d >= dmax;
        double want = tn_force(&t, d, dmax), got = (wall ? 1 : -1) * f[0];
        fscale = fmax(fscale, want);
        worst_f = fmax(worst_f, fabs(got - want));
        if (d < dmax) {
            unload++;
            dem_energy_t en;
            assert_int_equal(dem_energy(ref, &en), 0);
            worst_e = fmax(worst_e, fabs(en.elastic - tn_energy(&t, d, dmax)));
            /* the stress output: -(lever x elastic force) / V along the line of centres, the lever r - d/2 (a wall:
             * r - d), the force the unloading curve's (taken with the state of the step's force pass) */
            double sg[6], lever = wall ? R - d : R - 0.5 * d, vol = 4.0 / 3.0 * M_PI * R * R * R;
            assert_int_equal(dem_get_field(ref, DEM_FIELD_STRESS, sg), 0);
            worst_s = fmax(worst_s, fabs(sg[0] + lever * want / vol) * vol / R);
            if (want == 0 && dp_seen < 0)
                dp_seen = d;
        }
    }
    double v[6];
    assert_int_equal(dem_get_field(ref, DEM_FIELD_V, v), 0);
    double vout = wall ? v[0] : v[3] - v[0], e = vout / vi, e0 = restitution_thornton(vy, vi);
    double fm = t.fy + M_PI * PY * t.rs * (dmax - t.dy), emax = 0.4 * fm * dmax;
    printf("  %s, %s: V_y %.4g m/s, V_i %.4g; delta_y %.4g m, delta_max %.4g; %d plastic and %d unloading steps; "
           "restitution %.6f (Thornton 1997: %.6f); worst force %.2g, energy %.2g, stress %.2g (relative)\n",
           wall ? "sphere on a wall" : "two spheres", prec == DEM_FP64 ? "fp64" : "fp32", vy, vi, t.dy, dmax, plastic,
           unload, e, e0, worst_f / fscale, worst_e / emax, worst_s / fscale);
    assert_true(plastic > 100 && unload > 100);
    assert_true(dp_seen > 0); /* the spheres part with a permanent dent: no force while they still overlap */
    assert_true(worst_f / fscale < tol);
    assert_true(worst_e / emax < tol);
    assert_true(worst_s / fscale < tol);
    assert_true(fabs(e / e0 - 1) < (prec == DEM_FP64 ? 2e-3 : 5e-3));
    dem_destroy(cl);
    dem_destroy(ref);
}

static void test_pair_fp64(void **st) { (void)st; collide(0, DEM_FP64); }
static void test_pair_fp32(void **st) { (void)st; collide(0, DEM_FP32); }
static void test_wall_fp64(void **st) { (void)st; collide(1, DEM_FP64); }
static void test_wall_fp32(void **st) { (void)st; collide(1, DEM_FP32); }

/* A fixed sphere at the origin; a rigid plane coming from +x at speed u: in 4 stages it presses to d1, backs off to
 * d1/2, presses again to d2 > d1, backs off clear */
#define PRESS_STEPS 4000
static dem_sim *press_build(double u, double dt, const double stage_t[4])
{
    dem_sim *s = dem_create();
    dem_material m = powder(), w = steel();
    int id = dem_add_material(s, &m);
    dem_wall pl;
    memset(&pl, 0, sizeof pl);
    pl.kind = DEM_WALL_PLANE;
    pl.material = dem_add_material(s, &w);
    pl.point[0] = R;
    pl.normal[0] = -1;
    pl.nstages = 4;
    for (int k = 0; k < 4; k++) {
        pl.stages[k].duration = stage_t[k];
        pl.stages[k].velocity[0] = k % 2 ? u : -u;
    }
    assert_true(dem_add_wall(s, &pl) >= 0);
    int p = dem_add_particle(s, (double[3]){0, 0, 0}, (double[3]){0, 0, 0}, R, id);
    dem_set_particle_flags(s, p, DEM_PARTICLE_FIXED);
    double L = 8 * R;
    dem_set_domain(s, (double[3]){-L, -L, -L}, (double[3]){L, L, L});
    if (dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_THORNTON_NING | DEM_EFFECT_WALLS))
        fail_msg("%s", dem_error(s));
    dem_set_dt(s, dt);
    return s;
}

static void press(dem_precision prec)
{
    tn_closed t = tn_of(YOUNG / (1 - NU * NU), R);
    double d1 = 6 * t.dy, d2 = 12 * t.dy, dt = 1e-6;
    double u = (2 * d2) / (PRESS_STEPS * dt) * 1.5; /* the whole path in about PRESS_STEPS steps */
    double stage_t[4] = {d1 / u, 0.5 * d1 / u, (d2 - 0.5 * d1) / u, 1.2 * d2 / u};
    dem_sim *cl = press_build(u, dt, stage_t), *ref = press_build(u, dt, stage_t);
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, prec), rc = cfg_of(DEM_BACKEND_REFERENCE, prec);
    start_or_fail(cl, &c);
    start_or_fail(ref, &rc);
    double dmax = 0, worst = 0, fscale = 0, dfirst = 0, dmin = INFINITY;
    int reloaded = 0, phase = 0;
    long total = (long)((stage_t[0] + stage_t[1] + stage_t[2] + stage_t[3]) / dt);
    for (long k = 0; k < total; k++) {
        twins_step(cl, ref, 1, "press, PoCL vs reference");
        double pa[3], f[3];
        assert_int_equal(dem_wall_position(ref, 0, pa), 0);
        assert_int_equal(dem_get_field(ref, DEM_FIELD_FORCE, f), 0);
        /* the step's force pass sees the wall where the step moved it (the host moves the walls first) */
        double d = R - pa[0];
        if (d > dmax) {
            if (phase == 2)
                reloaded = 1;
            dmax = d;
        } else if (phase == 0 && d > 0 && d < dmax) {
            phase = 1, dfirst = dmax;
        } else if (phase == 1 && d > 0 && d < dfirst && d > 0.4 * dfirst && d >= dmin) {
            phase = 2;
        }
        if (phase == 1)
            dmin = fmin(dmin, d);
        double want = tn_force(&t, d, dmax);
        fscale = fmax(fscale, want);
        worst = fmax(worst, fabs(-f[0] - want));
    }
    printf("  press %s: first maximum %.4g m (delta_y %.4g), reloaded past it to %.4g; worst force %.2g (relative)\n",
           prec == DEM_FP64 ? "fp64" : "fp32", dfirst, t.dy, dmax, worst / fscale);
    assert_true(dfirst > 5 * t.dy && dmax > 11 * t.dy && reloaded);
    /* the wall's position is summed in double on the host from the stage velocities as here, so the overlap agrees
     * to rounding; fp32 rounds the overlap near R to R 2^-24, a part 1e-3 of it */
    assert_true(worst / fscale < (prec == DEM_FP64 ? 1e-6 : 5e-3));
    dem_destroy(cl);
    dem_destroy(ref);
}

static void test_press_fp64(void **st) { (void)st; press(DEM_FP64); }
static void test_press_fp32(void **st) { (void)st; press(DEM_FP32); }

/* A packing of plastic spheres (p_y low enough that many contacts yield) under a moving lid: saved and restored
 * mid-run (the law's states of pairs and walls travel in dem_state), and run with two skins (the states are carried
 * across neighbour rebuilds, which the skin sets), bit for bit */
static packing_opts plastic_packing(void)
{
    packing_opts o;
    packing_defaults(&o);
    o.side = 4;
    o.effects = DEM_EFFECT_CLASSICAL | DEM_EFFECT_THORNTON_NING;
    o.yield_stress = 2e6;
    o.lid_speed = 0.5;
    return o;
}

static void test_restart_and_skin(void **st)
{
    (void)st;
    packing_opts o = plastic_packing();
    FOR_EACH_BACKEND(bc) {
        dem_config c = cfg_of(bc->backend, bc->precision);
        dem_state sa;
        packing_restart_state(&o, &c, bc->name, &sa);
        long yielded = 0;
        for (long p = 0; p < sa.npairs; p++) {
            double dm = bc->precision == DEM_FP64 ? ((double *)sa.pair_law)[p] : ((float *)sa.pair_law)[p];
            yielded += dm > 0;
        }
        assert_true(sa.has_law && sa.npairs > 10 && yielded == sa.npairs);
        dem_state_free(&sa);
        /* two skins (other rebuild steps) and stored anew at every rebuild (the states move with their pairs): the
         * same bits, and the same states handed out in the callers' order */
        dem_sim *s1, *s3;
        skins_and_order_check(&o, &c, 600, bc->name, &s1, &s3);
        dem_state t1, t3;
        assert_int_equal(dem_state_get(s1, &t1), 0);
        assert_int_equal(dem_state_get(s3, &t3), 0);
        assert_true(t1.npairs == t3.npairs && t1.npairs > 10);
        size_t rs = (size_t)t1.real_size, np = (size_t)t1.npairs;
        assert_memory_equal(t1.pair_i, t3.pair_i, sizeof(int) * np);
        assert_memory_equal(t1.pair_j, t3.pair_j, sizeof(int) * np);
        assert_memory_equal(t1.pair_law, t3.pair_law, rs * np);
        dem_state_free(&t1);
        dem_state_free(&t3);
        dem_destroy(s1);
        dem_destroy(s3);
    }
}

/* Bad set-ups are refused with the reason */
static void test_refusals(void **st)
{
    (void)st;
    dem_sim *s = dem_create();
    dem_material m = powder();
    m.yield_stress = -1;
    assert_int_equal(dem_add_material(s, &m), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "yield stress"));
    assert_int_equal(dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_THORNTON_NING | DEM_EFFECT_MC_STRESS),
                     DEM_ERR_ARG);
    assert_int_equal(dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_THORNTON_NING | DEM_EFFECT_PATCHES), DEM_ERR_ARG);
    dem_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pair_fp64),  cmocka_unit_test(test_pair_fp32),  cmocka_unit_test(test_wall_fp64),
        cmocka_unit_test(test_wall_fp32),  cmocka_unit_test(test_press_fp64), cmocka_unit_test(test_press_fp32),
        cmocka_unit_test(test_restart_and_skin), cmocka_unit_test(test_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
