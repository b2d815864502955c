/* test_bonds.c - the solid bridge a yielded Thornton-Ning contact forms (common/laws/thornton_ning.h,
 * dem_material.bond_strength sigma_b), against closed forms typed in here, not taken from the library:
 *   a contact that yielded holds the plastic contact radius a_p of its largest load F_m,
 *     a_p^2 = (2 F_m + F_y) / (2 pi p_y)                                  (Thornton and Ning 1998),
 *   and, once unloaded past its dent delta_p, is a flat circular contact of radius a_p pulled apart: stiffness
 *     k_b = 2 E* a_p (the flat punch's), force F = k_b (delta - delta_p) < 0,
 *   until the tension reaches F_b = sigma_b pi a_p^2 (the bridge's strength over the plastic area), where the bond
 *   breaks: no tension after it until the contact yields further (a new bond over its new plastic area).
 * Cases:
 *   - a fixed sphere pressed plastically by a plane that bonds, pulled back past its dent until the bond breaks,
 *     pressed again and pulled clear: the force at every step against the closed form (the paper's powers), the
 *     largest tension = F_b, none after the break, and the elastic energy the host reports in tension = F^2/(2 k_b);
 *     with the bond strength from both materials (the smaller), from the material pair, and from the sphere's alone
 *     (no bond: the plane's material gives none);
 *   - two spheres colliding at 5 V_y: the bond takes F_b^2 / (2 k_b) from the rebound, V_out^2 = V_0^2 -
 *     F_b^2 / (k_b m*), V_0 the rebound of the same collision without bonds; a bond stronger than the rebound's
 *     energy keeps the spheres together;
 *   - a bond held in tension and slid sideways: friction resists up to mu (f_n + F_b), then the slip breaks it;
 *   - a bond broken by pulling, pressed further (it yields anew) and pulled again: a new bond, of the new a_p;
 *   - bad bond strengths are refused.
 * Every case on the reference and on OpenCL (PoCL), in fp64 and fp32, the OpenCL state equal to the reference's at
 * every step (the pair's forces are exactly antisymmetric: the states compared include both spheres). */
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <string.h>

#define RHO 1500.0
#define YOUNG 5e9
#define NU 0.3
#define PY 2e8 /* p_y [Pa] */
#define R 1e-3

/* The papers' loading curve and unloading curve from dmax, and the bond, in double */
typedef struct {
    double es, rs, dy, fy, sigb;
} bond_closed;

static bond_closed bond_of(double es, double rs, double sigb)
{
    bond_closed t = {es, rs, pow(M_PI * PY / (2 * es), 2) * rs, 0, sigb};
    t.fy = 4.0 / 3.0 * es * sqrt(rs) * pow(t.dy, 1.5);
    return t;
}
static double fm_of(const bond_closed *t, double dmax) { return t->fy + M_PI * PY * t->rs * (dmax - t->dy); }
static double ap_of(const bond_closed *t, double dmax) { return sqrt((2 * fm_of(t, dmax) + t->fy) / (2 * M_PI * PY)); }
static double dp_of(const bond_closed *t, double dmax)
{
    double fm = fm_of(t, dmax), rp = 4 * t->es / (3 * fm) * pow(ap_of(t, dmax), 3);
    return dmax - pow(3 * fm / (4 * t->es * sqrt(rp)), 2.0 / 3.0);
}
static double fb_of(const bond_closed *t, double dmax) { return t->sigb * M_PI * pow(ap_of(t, dmax), 2); }
static double kb_of(const bond_closed *t, double dmax) { return 2 * t->es * ap_of(t, dmax); }

/* The force at d on the unloading curve from dmax (> delta_y); broken: the bond's state */
static double bond_force(const bond_closed *t, double d, double dmax, int broken)
{
    double fm = fm_of(t, dmax), rp = 4 * t->es / (3 * fm) * pow(ap_of(t, dmax), 3), dp = dp_of(t, dmax);
    if (d >= dmax)
        return fm_of(t, d);
    if (d > dp)
        return 4.0 / 3.0 * t->es * sqrt(rp) * pow(d - dp, 1.5);
    return broken ? 0 : kb_of(t, dmax) * (d - dp);
}

static dem_material powder(double sigb)
{
    dem_material m = {RHO, YOUNG, NU, 1.0, 0.0, 0.0, 0.0, PY, 0.0, sigb};
    return m;
}

/* How the plane's bond strength is set: both materials give sigma_b (the pair takes the smaller, the plane's being
 * larger); the plane's material gives none and the material pair gives sigma_b (dem_set_material_pair); the plane's
 * gives none and nothing else (no bond: the smaller of the two) */
enum { BOND_MATERIALS, BOND_PAIR, BOND_NONE };

/* A fixed sphere at the origin; a rigid plane from +x, moved by the stages: press to d1, back to d_back (past the
 * break, still overlapping), press to d_again, back clear */
static dem_sim *pull_build(double sigb, int how, double mu, double dt, int nst, const double *dur, const double *vel,
                           const double *vel_y)
{
    dem_sim *s = dem_create();
    dem_material m = powder(sigb), w = {7800, INFINITY, 0.3, 1.0, 0.0, 0.0, 0.0, 0.0, 0.0,
                                        how == BOND_MATERIALS ? 3 * sigb : 0.0};
    m.friction = 2 * mu; /* the pair takes the mean with the plane's 0: mu */
    int id = dem_add_material(s, &m);
    dem_wall pl;
    memset(&pl, 0, sizeof pl);
    pl.kind = DEM_WALL_PLANE;
    pl.material = dem_add_material(s, &w);
    if (how == BOND_PAIR)
        assert_int_equal(dem_set_material_pair(s, id, pl.material, &(dem_material_pair){NAN, NAN, NAN, sigb, NAN}), 0);
    pl.point[0] = R;
    pl.normal[0] = -1;
    pl.nstages = nst;
    for (int k = 0; k < nst; k++) {
        pl.stages[k].duration = dur[k];
        pl.stages[k].velocity[0] = vel[k];
        pl.stages[k].velocity[1] = vel_y ? vel_y[k] : 0;
    }
    assert_true(dem_add_wall(s, &pl) >= 0);
    int p = dem_add_particle(s, (double[3]){0, 0, 0}, (double[3]){0, 0, 0}, R, id);
    dem_set_particle_flags(s, p, DEM_PARTICLE_FIXED);
    double L = 8 * R;
    dem_set_domain(s, (double[3]){-L, -L, -L}, (double[3]){L, L, L});
    unsigned fx = DEM_EFFECT_HERTZ | DEM_EFFECT_THORNTON_NING | DEM_EFFECT_WALLS | (mu > 0 ? DEM_EFFECT_FRICTION : 0);
    if (dem_set_effects(s, fx))
        fail_msg("%s", dem_error(s));
    dem_set_dt(s, dt);
    return s;
}

static void pull(dem_precision prec, int how)
{
    double sigb = 0.2 * PY;
    bond_closed t = bond_of(YOUNG / (1 - NU * NU), R, sigb);
    double d1 = 6 * t.dy, dp = dp_of(&t, d1), fb = fb_of(&t, d1), kb = kb_of(&t, d1), stretch = fb / kb;
    assert_true(dp > 3 * stretch); /* the bond breaks while the sphere still overlaps the plane */
    double dback = dp - 2 * stretch, dagain = 0.5 * (dp + d1), dt = 1e-6;
    double u = stretch / (100 * dt); /* 100 steps across the tension branch */
    double vel[4] = {-u, u, -u, u};
    double dur[4] = {d1 / u, (d1 - dback) / u, (dagain - dback) / u, (dagain + 0.1 * d1) / u};
    dem_sim *cl = pull_build(sigb, how, 0, dt, 4, dur, vel, NULL), *ref = pull_build(sigb, how, 0, dt, 4, dur, vel, NULL);
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, prec), rc = cfg_of(DEM_BACKEND_REFERENCE, prec);
    start_or_fail(cl, &c);
    start_or_fail(ref, &rc);
    long total = (long)((dur[0] + dur[1] + dur[2] + dur[3]) / dt);
    double dmax = 0, worst = 0, fmax_seen = 0, tension_max = 0, worst_e = 0, tension_after = 0, dbreak = 0;
    int broken = 0, tension_steps = 0, phase = 0; /* phase: 0 first press, 1 back, 2 again, 3 clear */
    double dprev = 0;
    for (long k = 0; k < total; k++) {
        twins_step(cl, ref, 1, "bond pulled, PoCL vs reference");
        double pa[3], f[3];
        assert_int_equal(dem_wall_position(ref, 0, pa), 0);
        assert_int_equal(dem_get_field(ref, DEM_FIELD_FORCE, f), 0);
        double d = R - pa[0], got = -f[0];
        if (d < dprev && phase % 2 == 0)
            phase++;
        else if (d > dprev && phase % 2 == 1)
            phase++;
        dprev = d;
        if (d > dmax)
            dmax = d;
        if (d <= 0 || dmax <= t.dy)
            continue;
        double want = bond_force(&t, d, dmax, broken || how == BOND_NONE);
        fb = fb_of(&t, dmax), kb = kb_of(&t, dmax); /* of the overlap reached (the wall's steps pass d1 by < 1e-3) */
        if (!broken && want < -fb) { /* the closed form breaks here; so must the library, to a rounding of F_b */
            broken = 1;
            dbreak = d;
            want = 0;
            if (got != 0 && fabs(got + fb) < 1e-3 * fb) /* the library breaks a rounding later: the same step */
                want = got;
        }
        fmax_seen = fmax(fmax_seen, fabs(want));
        worst = fmax(worst, fabs(got - want));
        if (got < 0) {
            tension_steps++;
            tension_max = fmax(tension_max, -got);
            if (broken)
                tension_after = fmax(tension_after, -got);
            dem_energy_t en;
            assert_int_equal(dem_energy(ref, &en), 0);
            worst_e = fmax(worst_e, fabs(en.elastic - got * got / (2 * kb)) / (fb * fb / (2 * kb)));
        }
    }
    printf("  bond pulled from a plane (%s), %s: a_p %.4g m, delta_p %.4g m, F_b %.4g N (stretch %.3g m); %d steps in "
           "tension, largest tension %.6g F_b, broke at %.6g m (closed form %.6g); worst force %.2g, tension's energy "
           "%.2g (relative); reloaded to %.4g m\n",
           how == BOND_MATERIALS ? "both materials bond" : how == BOND_PAIR ? "the pair's bond strength" : "no bond",
           prec == DEM_FP64 ? "fp64" : "fp32", ap_of(&t, d1), dp, fb, stretch, tension_steps, tension_max / fb, dbreak,
           dp - stretch, worst / fmax_seen, worst_e, dagain);
    assert_true(phase == 3 && dmax >= d1 * (1 - 1e-6) && dmax < d1 * (1 + 1e-3));
    if (how == BOND_NONE) { /* the plane's material bonds to nothing: the pair has no bond */
        assert_true(tension_steps == 0);
    } else {
        assert_true(broken && tension_steps > 50);
        assert_true(tension_max / fb > 0.98 && tension_max / fb <= 1 + (prec == DEM_FP64 ? 1e-9 : 1e-3));
        assert_true(tension_after == 0); /* broken: no tension on the second pull, which does not pass the first press */
    }
    assert_true(worst / fmax_seen < (prec == DEM_FP64 ? 1e-6 : 5e-3));
    assert_true(worst_e < (prec == DEM_FP64 ? 1e-6 : 1e-2));
    dem_destroy(cl);
    dem_destroy(ref);
}

static void test_pull_fp64(void **st) { (void)st; pull(DEM_FP64, BOND_MATERIALS); }
static void test_pull_fp32(void **st) { (void)st; pull(DEM_FP32, BOND_MATERIALS); }
/* A bond held in tension T < F_b and slid sideways: friction resists up to mu (f_n + F_b) = mu (F_b - T), where a
 * contact without a bond, in tension, would slide freely (mu max(f_n, 0) = 0); the step it slides, the bond breaks,
 * and the contact, inside its dent, then carries nothing. Reference and PoCL, fp64. */
static void test_friction_bonded(void **st)
{
    (void)st;
    double sigb = 0.2 * PY, mu = 0.4;
    bond_closed t = bond_of(YOUNG / (1 - NU * NU), R, sigb);
    double d1 = 6 * t.dy, dp = dp_of(&t, d1), stretch = fb_of(&t, d1) / kb_of(&t, d1), dt = 1e-6;
    double u = stretch / (100 * dt), ut = 0.5 * u;
    double vel[3] = {-u, u, 0}, vel_y[3] = {0, 0, ut};
    double dur[3] = {d1 / u, (d1 - (dp - 0.5 * stretch)) / u, 40 * stretch / ut};
    dem_sim *cl = pull_build(sigb, BOND_MATERIALS, mu, dt, 3, dur, vel, vel_y);
    dem_sim *ref = pull_build(sigb, BOND_MATERIALS, mu, dt, 3, dur, vel, vel_y);
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, DEM_FP64), rc = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    start_or_fail(cl, &c);
    start_or_fail(ref, &rc);
    long total = (long)((dur[0] + dur[1] + dur[2]) / dt), after = 0, sliding_steps = 0;
    /* the overlap reached by the press is d1 to its last step's travel (1e-3 d1) */
    double fb = fb_of(&t, d1), ft_peak = 0, fn_at_peak = 0, f_after = 0;
    int broke = 0;
    for (long k = 0; k < total; k++) {
        twins_step(cl, ref, 1, "bond slid, PoCL vs reference");
        double f[3];
        assert_int_equal(dem_get_field(ref, DEM_FIELD_FORCE, f), 0);
        if (k * dt < dur[0] + dur[1])
            continue;
        sliding_steps++;
        if (broke) {
            after++;
            f_after = fmax(f_after, fabs(f[0]) + fabs(f[1]));
        } else if (fabs(f[1]) >= ft_peak) {
            ft_peak = fabs(f[1]), fn_at_peak = -f[0];
        } else {
            broke = 1; /* the tangential force fell: the step before slid and broke the bond */
            f_after = fmax(f_after, fabs(f[0]) + fabs(f[1]));
            after++;
        }
    }
    double want = mu * (fn_at_peak + fb);
    printf("  bond held at %.4g N (F_b %.4g N) and slid: largest tangential force %.6g N, mu (f_n + F_b) %.6g N; "
           "after it (%ld steps) the largest force %.3g N\n", fn_at_peak, fb, ft_peak, want, after, f_after);
    assert_true(fn_at_peak < -0.3 * fb && fn_at_peak > -0.7 * fb); /* held in tension */
    assert_true(fabs(ft_peak / want - 1) < 2e-3);
    assert_true(broke && after > 100 && f_after == 0); /* broken by the slip: no tension, no friction */
    assert_true(sliding_steps > after);
    dem_destroy(cl);
    dem_destroy(ref);
}

/* A bond broken by pulling, pressed past its largest overlap (it yields further: a new bond over the new plastic area)
 * and pulled again: the second pull's tension reaches the new F_b. Reference, fp64. */
static void test_rebond(void **st)
{
    (void)st;
    double sigb = 0.2 * PY;
    bond_closed t = bond_of(YOUNG / (1 - NU * NU), R, sigb);
    double d1 = 6 * t.dy, d2 = 9 * t.dy, dp1 = dp_of(&t, d1), s1 = fb_of(&t, d1) / kb_of(&t, d1), dt = 1e-6;
    double dp2 = dp_of(&t, d2), s2 = fb_of(&t, d2) / kb_of(&t, d2), u = s1 / (100 * dt);
    double back1 = dp1 - 2 * s1, back2 = dp2 - 2 * s2;
    double vel[4] = {-u, u, -u, u};
    double dur[4] = {d1 / u, (d1 - back1) / u, (d2 - back1) / u, (d2 - back2) / u};
    dem_sim *s = pull_build(sigb, BOND_MATERIALS, 0, dt, 4, dur, vel, NULL);
    dem_config rc = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    start_or_fail(s, &rc);
    long total = (long)((dur[0] + dur[1] + dur[2] + dur[3]) / dt);
    double tmax[2] = {0, 0};
    for (long k = 0; k < total; k++) {
        step_or_fail(s, 1);
        double f[3];
        assert_int_equal(dem_get_field(s, DEM_FIELD_FORCE, f), 0);
        int second = k * dt >= dur[0] + dur[1] + dur[2];
        tmax[second] = fmax(tmax[second], f[0]); /* tension pulls the sphere towards the plane: +x */
    }
    printf("  bond broken, pressed on to %.4g m and pulled again: largest tensions %.6g F_b(d1), %.6g F_b(d2)\n", d2,
           tmax[0] / fb_of(&t, d1), tmax[1] / fb_of(&t, d2));
    assert_true(tmax[0] / fb_of(&t, d1) > 0.98 && tmax[0] / fb_of(&t, d1) <= 1 + 1e-9);
    assert_true(tmax[1] / fb_of(&t, d2) > 0.98 && tmax[1] / fb_of(&t, d2) <= 1 + 1e-3);
    dem_destroy(s);
}

static void test_pull_pair_table(void **st)
{
    (void)st;
    pull(DEM_FP64, BOND_PAIR);
    pull(DEM_FP64, BOND_NONE);
}

/* Two spheres of material m at 5 V_y (effects fx; spinning at -+spin about y, rolling on each other, when fx has
 * friction); returns the separation speed after contact (or -1: still together at the end) and the largest overlap;
 * fails the test if a spin is not finite */
static double collide_with(const dem_material *m, unsigned fx, double spin, double *dmax_out, int *gap_out,
                           double *stress_out, dem_precision prec)
{
    double es = YOUNG / (2 * (1 - NU * NU)), rs = R / 2, ms = RHO * 4.0 / 3.0 * M_PI * R * R * R / 2;
    bond_closed t = bond_of(es, rs, m->bond_strength);
    double vy = sqrt(2 * 0.4 * t.fy * t.dy / ms), vi = 5 * vy;
    double tc = 2.87 * pow(ms * ms / (rs * es * es * vi), 0.2), dt = tc / 4000;
    dem_sim *cl = head_on_build(m, NULL, R, vi, fx, dt), *ref = head_on_build(m, NULL, R, vi, fx, dt);
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, prec), rc = cfg_of(DEM_BACKEND_REFERENCE, prec);
    start_or_fail(cl, &c);
    start_or_fail(ref, &rc);
    for (int k = 0; spin != 0 && k < 2; k++) {
        dem_sim *s = k ? ref : cl;
        dem_state sv;
        assert_int_equal(dem_state_get(s, &sv), 0);
        double *w = dem_state_find(&sv, "w")->data;
        w[1] = spin, w[4] = -spin;
        assert_int_equal(dem_state_set(s, &sv), 0);
        dem_state_free(&sv);
    }
    double dmax = 0, vout = -1;
    int was = 0, gap = 0;
    /* the worst stress across the gap against the closed form, in R F_b / V, and the worst energy, in F_b^2 / (2 k_b) */
    stress_out[0] = stress_out[1] = stress_out[2] = 0; /* [2]: the sampled series' energy, in F_b^2 / (2 k_b) */
    long n_sampled[1] = {0};
    for (int k = 0; k < 20000; k++) {
        /* across the gap every 8th step is sampled (dem_step_sampled: the series' row, summed by the kernels) */
        int sampled = gap > 0 && gap % 8 == 7;
        dem_sample row[2];
        if (sampled) {
            unsigned char want = 1;
            char msg[512];
            assert_int_equal(dem_step_sampled(cl, 1, &want, &row[0]), 0);
            assert_int_equal(dem_step_sampled(ref, 1, &want, &row[1]), 0);
            if (state_diff(cl, ref, msg, sizeof msg))
                fail_msg("bonded pair, PoCL vs reference, sampled step %ld: %s", dem_step_index(ref), msg);
        } else {
            twins_step(cl, ref, 1, "bonded pair, PoCL vs reference");
        }
        double x[6], v[6], f[6], w[6];
        assert_int_equal(dem_get_field(ref, DEM_FIELD_X, x), 0);
        assert_int_equal(dem_get_field(ref, DEM_FIELD_FORCE, f), 0);
        assert_int_equal(dem_get_field(ref, DEM_FIELD_W, w), 0);
        for (int d = 0; d < 6; d++)
            if (!isfinite(w[d]))
                fail_msg("step %d: spin %d is %g", k, d, w[d]);
        double d = 2 * R - fabs(x[3] - x[0]);
        if (d > 0) {
            was = 1;
            dmax = fmax(dmax, d);
        } else if (was && f[0] != 0) { /* the bond holds them across a gap */
            gap++;
            if (sampled) { /* the series' row counts the bond: one contact, its energy the closed form's */
                double fbd = bond_force(&t, d, dmax, 0), kb = kb_of(&t, dmax), fb = fb_of(&t, dmax);
                assert_true(row[0].energy.elastic == row[1].energy.elastic);
                assert_true(row[1].energy.contacts == 1);
                stress_out[2] = fmax(stress_out[2], fabs(row[1].energy.elastic - fbd * fbd / (2 * kb)) / (fb * fb / (2 * kb)));
                n_sampled[0]++;
            }
            if (gap > 400 && gap % 16) /* (a held pair: every 16th step after the first 400) */
                continue;
            /* the stress output (particle_stress.h) counts the bond's tension across the gap too: seed 000's
             * -(r - d/2) F / V n (x) n, F the closed form's at this separation (0 before 2026-12-06) */
            double sg[12], sr[12], vol = 4.0 / 3.0 * M_PI * R * R * R, fb = fb_of(&t, dmax);
            assert_int_equal(dem_get_field(cl, DEM_FIELD_STRESS, sg), 0);
            assert_int_equal(dem_get_field(ref, DEM_FIELD_STRESS, sr), 0);
            assert_memory_equal(sg, sr, sizeof sg);
            double sxx = -(R - 0.5 * d) * bond_force(&t, d, dmax, 0) / vol;
            stress_out[0] = fmax(stress_out[0], fabs(sr[6] - sxx) / (R * fb / vol));
            assert_true(sr[6] > 0 && sr[0] == sr[6]); /* tension, the same on both spheres */
            /* and the host's elastic energy, the stretched bond's F^2 / (2 k_b) (0 before 2026-12-06) */
            dem_energy_t en;
            assert_int_equal(dem_energy(ref, &en), 0);
            double fbd = bond_force(&t, d, dmax, 0), kb = kb_of(&t, dmax);
            stress_out[1] = fmax(stress_out[1], fabs(en.elastic - fbd * fbd / (2 * kb)) / (fb * fb / (2 * kb)));
        } else if (was) { /* apart */
            assert_int_equal(dem_get_field(ref, DEM_FIELD_V, v), 0);
            vout = v[3] - v[0];
            break;
        }
    }
    *dmax_out = dmax;
    *gap_out = gap;
    assert_true(gap < 8 || n_sampled[0] > 0); /* a gap held 8 steps was sampled */
    dem_destroy(cl);
    dem_destroy(ref);
    return vout;
}
static double collide(double sigb, double *dmax_out, int *gap_out, double *stress_out, dem_precision prec)
{
    dem_material m = powder(sigb);
    return collide_with(&m, DEM_EFFECT_HERTZ | DEM_EFFECT_THORNTON_NING, 0, dmax_out, gap_out, stress_out, prec);
}

static void bounce(dem_precision prec)
{
    double es = YOUNG / (2 * (1 - NU * NU)), rs = R / 2, ms = RHO * 4.0 / 3.0 * M_PI * R * R * R / 2, dm0, dm1, dm2;
    int gap0, gap1, gap2;
    double sw0[3], sw1[3], sw2[3], v0 = collide(0, &dm0, &gap0, sw0, prec);
    assert_true(v0 > 0);
    /* a bond that takes half the rebound's energy: sigma_b from E_b = F_b^2 / (2 k_b) = 1/4 m* v0^2 */
    bond_closed unit = bond_of(es, rs, 1.0);
    double fb1 = fb_of(&unit, dm0), kb = kb_of(&unit, dm0);
    double sigb = sqrt(0.25 * ms * v0 * v0 * 2 * kb) / fb1;
    bond_closed t = bond_of(es, rs, sigb);
    double v1 = collide(sigb, &dm1, &gap1, sw1, prec), fb = fb_of(&t, dm1);
    double want = sqrt(v0 * v0 - fb * fb / (kb_of(&t, dm1) * ms));
    /* four times stronger: 16 times the energy, more than the rebound has */
    double v2 = collide(4 * sigb, &dm2, &gap2, sw2, prec);
    printf("  bonded pair at 5 V_y, %s: sigma_b %.4g Pa (%.3g p_y); rebound %.6g m/s without bond, %.6g with "
           "(closed form %.6g; dent %.4g m, bond's stretch %.4g m: %d steps bonded across a gap), %s with 4 sigma_b\n",
           prec == DEM_FP64 ? "fp64" : "fp32", sigb, sigb / PY, v0, v1, want, dp_of(&t, dm1),
           fb / kb_of(&t, dm1), gap1, v2 < 0 ? "together" : "apart");
    assert_true(dm1 == dm0 || fabs(dm1 / dm0 - 1) < 1e-6); /* the loading does not feel the bond */
    assert_true(gap0 == 0 && gap1 > 10); /* this dent is shallower than the stretch: the bond holds across a gap */
    printf("  across the gap (%d and %d steps), against the closed form: stress output worst %.2g R F_b / V, host's "
           "elastic energy worst %.2g F_b^2 / (2 k_b), the sampled series' %.2g\n", gap1, gap2, fmax(sw1[0], sw2[0]),
           fmax(sw1[1], sw2[1]), fmax(sw1[2], sw2[2]));
    assert_true(fmax(sw1[0], sw2[0]) < (prec == DEM_FP64 ? 1e-9 : 1e-3));
    assert_true(fmax(sw1[1], sw2[1]) < (prec == DEM_FP64 ? 1e-9 : 1e-3));
    assert_true(fmax(sw1[2], sw2[2]) < (prec == DEM_FP64 ? 1e-9 : 1e-3));
    assert_true(v1 > 0 && fabs(v1 / want - 1) < 2e-3);
    assert_true(v2 < 0);
}

static void test_bounce_fp64(void **st) { (void)st; bounce(DEM_FP64); }
static void test_bounce_fp32(void **st) { (void)st; bounce(DEM_FP32); }

/* The bonded collision with friction and the rolling spring (rolling.h): while the bond holds the spheres across a
 * gap, the spring's stiffness is taken at zero overlap - every spin stays finite (it was a NaN: the square root of a
 * negative overlap) - and both backends agree bit for bit */
static void test_bond_gap_rolling_spring(void **st)
{
    (void)st;
    double es = YOUNG / (2 * (1 - NU * NU)), rs = R / 2, ms = RHO * 4.0 / 3.0 * M_PI * R * R * R / 2, dm;
    bond_closed t = bond_of(es, rs, 1.0);
    int gap;
    double sw[3], v0 = collide(0, &dm, &gap, sw, DEM_FP64); /* the bond of test_bounce, which holds across a gap */
    dem_material m = powder(sqrt(0.25 * ms * v0 * v0 * 2 * kb_of(&t, dm)) / fb_of(&t, dm));
    m.friction = 0.5, m.rolling_friction = 0.1, m.rolling_damping = 0.3;
    unsigned fx = DEM_EFFECT_HERTZ | DEM_EFFECT_FRICTION | DEM_EFFECT_THORNTON_NING | DEM_EFFECT_ROLLING |
                  DEM_EFFECT_ROLLING_SPRING;
    collide_with(&m, fx, 10, &dm, &gap, sw, DEM_FP64); /* a relative spin, so that the spring winds */
    printf("  bonded pair with rolling springs: %d steps held across a gap, every spin finite\n", gap);
    assert_true(gap > 10);
}

static void test_refusals(void **st)
{
    (void)st;
    dem_sim *s = dem_create();
    dem_material m = powder(-1);
    assert_int_equal(dem_add_material(s, &m), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "bond strength"));
    m = powder(1e6);
    int a = dem_add_material(s, &m);
    assert_true(a >= 0);
    assert_int_equal(dem_set_material_pair(s, a, a, &(dem_material_pair){NAN, NAN, NAN, INFINITY, NAN}), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "bond strength"));
    dem_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pull_fp64),   cmocka_unit_test(test_pull_fp32), cmocka_unit_test(test_pull_pair_table),
        cmocka_unit_test(test_friction_bonded), cmocka_unit_test(test_rebond),
        cmocka_unit_test(test_bounce_fp64), cmocka_unit_test(test_bounce_fp32),
        cmocka_unit_test(test_bond_gap_rolling_spring), cmocka_unit_test(test_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
