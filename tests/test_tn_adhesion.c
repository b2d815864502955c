/* test_tn_adhesion.c - Thornton-Ning's law with JKR adhesion (DEM_EFFECT_ADHESION, common/laws/thornton_ning.h)
 * against closed forms typed in here, not taken from the library:
 *   JKR (Johnson, Kendall and Roberts 1971), a contact of radius a between spheres of effective radius rho:
 *     delta = a^2 / rho - sqrt(2 pi w a / E*),  F = 4 E* a^3 / (3 rho) - sqrt(8 pi w E* a^3),
 *     solved here for a by bisection on the stable branch a >= a_c = (pi w rho^2 / (8 E*))^(1/3), where a contact
 *     held by its ends lets go: delta_c = -3/4 (pi^2 w^2 rho / E*^2)^(1/3); the least force on that branch is the
 *     pull-off force -3/2 pi w rho;
 *   Thornton-Ning's plastic line in the contact radius (the Hertzian overlap a^2 / R*): F_H = F_y + pi p_y R*
 *     (a^2 / R* - delta_y) past a_y = pi p_y R* / (2 E*), and unloading as JKR of the flattened radius
 *     R_p = 4 E* a_m^3 / (3 F_H(a_m)) through the largest contact (delta_m, a_m), so the pull-off force grows with
 *     plastic deformation: -3/2 pi w R_p (F_cp = F_c R_p / R*);
 *   the energy an elastic JKR impact loses (a contact forms at zero overlap and lets go at delta_c; the branch between
 *     is conservative): the potential's work from delta = 0 to delta_c, computed here by quadrature, so two spheres
 *     stick below V_s = sqrt(2 dW / m*) and part at sqrt(V_i^2 - V_s^2) above it; V_s checked against Thornton and
 *     Ning's Eq. 54 (quoted from a digest of the paper; an independent check of ours derived the same 0.9355 F_c
 *     delta_c for dW).
 * Cases, each on the reference and on OpenCL (PoCL) in fp64 and fp32, the OpenCL state equal to the reference's at
 * every step: head-on impacts of two spheres below and above V_s (no yield), and far above yield; the same below and
 * above V_s of a sphere on a plane wall (held across the gap to the release, the wall's force and the contact network
 * checked there); the force at every step against the closed form, the step where they let go, the least force, the
 * rebound speed and the energy the host reports through the unloading. Friction with adhesion against Thornton and
 * Yin's mu (P + 2 P_c); damping on the JKR contact radius; the solver alone against a long-double bisection.
 * Refusals: adhesion without thornton_ning, without a surface energy, with bonds. */
#define DEM_REAL_SIZE 8
#include "laws/thornton_ning.h" /* tn_jkr_root, tn_jkr_sc: the solver alone, against a bisection (test_root) */
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define RHO 1500.0
#define YOUNG 5e9
#define NU 0.3
#define PY 1e8  /* p_y [Pa] */
#define W 0.5   /* work of adhesion [J/m^2] */
#define R 1e-4

typedef struct {
    double es, rs, w, ay, dy, fy;
} jkr_closed;

static jkr_closed jkr_of(double es, double rs)
{
    jkr_closed t = {es, rs, W, M_PI * PY * rs / (2 * es), 0, 0};
    t.dy = t.ay * t.ay / rs;
    t.fy = 4.0 / 3.0 * es * sqrt(rs) * pow(t.dy, 1.5);
    return t;
}

static double jkr_ac(const jkr_closed *t, double rho) { return cbrt(M_PI * t->w * rho * rho / (8 * t->es)); }
static double jkr_delta(const jkr_closed *t, double rho, double a) { return a * a / rho - sqrt(2 * M_PI * t->w * a / t->es); }
static double jkr_release(const jkr_closed *t, double rho) /* delta_c, < 0 */
{
    return -0.75 * cbrt(M_PI * M_PI * t->w * t->w * rho / (t->es * t->es));
}
static double jkr_force_a(const jkr_closed *t, double rho, double a)
{
    return 4 * t->es * a * a * a / (3 * rho) - sqrt(8 * M_PI * t->w * t->es * a * a * a);
}
/* a on the stable branch at delta d (>= delta_c): bisection */
static double jkr_a(const jkr_closed *t, double rho, double d)
{
    double lo = jkr_ac(t, rho), hi = lo;
    while (jkr_delta(t, rho, hi) < d)
        hi *= 2;
    for (int k = 0; k < 200; k++) {
        double mid = 0.5 * (lo + hi);
        if (jkr_delta(t, rho, mid) < d)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}
static double hertzian(const jkr_closed *t, double a) /* Thornton-Ning without adhesion, at delta_H = a^2 / R* */
{
    double dh = a * a / t->rs;
    return dh <= t->dy ? 4.0 / 3.0 * t->es * sqrt(t->rs) * pow(dh, 1.5) : t->fy + M_PI * PY * t->rs * (dh - t->dy);
}
/* The unloading branch from dmax: its radius and offset */
static void branch(const jkr_closed *t, double dmax, double *rho, double *dp)
{
    double am = jkr_a(t, t->rs, dmax);
    *rho = am <= t->ay ? t->rs : 4 * t->es * am * am * am / (3 * hertzian(t, am));
    *dp = dmax - jkr_delta(t, *rho, am);
}
/* The force at d given the largest overlap dmax; *gone = 1 where the contact has let go */
static double jkr_force(const jkr_closed *t, double d, double dmax, int *gone)
{
    *gone = 0;
    if (d >= dmax) {
        double a = jkr_a(t, t->rs, d);
        return hertzian(t, a) - sqrt(8 * M_PI * t->w * t->es * a * a * a);
    }
    double rho, dp;
    branch(t, dmax, &rho, &dp);
    if (d - dp < jkr_release(t, rho)) {
        *gone = 1;
        return 0;
    }
    return jkr_force_a(t, rho, jkr_a(t, rho, d - dp));
}
/* The work of the contact's force from overlap d to the release, along the branch from dmax (Simpson in a) */
static double jkr_potential(const jkr_closed *t, double d, double dmax)
{
    double rho, dp;
    branch(t, fmax(d, dmax), &rho, &dp);
    double a0 = jkr_ac(t, rho), a1 = jkr_a(t, rho, d - dp), sum = 0;
    int n = 2000;
    for (int k = 0; k <= n; k++) {
        double a = a0 + (a1 - a0) * k / n, h = 1e-7 * a;
        double dd = (jkr_delta(t, rho, a + h) - jkr_delta(t, rho, a - h)) / (2 * h); /* d delta / da */
        sum += (k == 0 || k == n ? 1 : k % 2 ? 4 : 2) * jkr_force_a(t, rho, a) * dd;
    }
    return sum * (a1 - a0) / (3 * n);
}

static double sphere_mass(void) { return RHO * 4.0 / 3.0 * M_PI * R * R * R; }

static dem_material powder(void)
{
    dem_material m = {RHO, YOUNG, NU, 1.0, 0.0, 0.0, 0.0, PY};
    m.surface_energy = W;
    return m;
}

#define FX_ADH (DEM_EFFECT_HERTZ | DEM_EFFECT_THORNTON_NING | DEM_EFFECT_ADHESION)

typedef struct {
    int stuck, released, yielded, steps_in;
    double worst, v_out, f_min, d_release, energy_drift, worst_energy, dmax, overlap_at_release;
    double worst_stress; /* the stress output against the closed form, in R F_c / V */
    int stress_gap;      /* steps across the gap where it was checked */
} impact_result;

/* The overlap of the head-on pair (x: both spheres' positions), or (wall 1) of the sphere at x[0..2] with the plane x = 0.
 * In fp32 as the kernels form it (contact_geometry.h): near the release the force's slope is unbounded, and fp32
 * resolves these positions to 1e-11 m */
static double overlap_of(const double *x, dem_precision prec, int wall)
{
    if (wall) /* the plane's r - (x - p) . n */
        return prec == DEM_FP32 ? (double)((float)R - (float)x[0]) : R - x[0];
    if (prec == DEM_FP64)
        return 2 * R - (x[3] - x[0]);
    float dx = (float)x[0] - (float)x[3], dy = (float)x[1] - (float)x[4], dz = (float)x[2] - (float)x[5];
    float dd = dx * dx + dy * dy;
    dd = dd + dz * dz;
    return (double)((float)R + (float)R - sqrtf(dd));
}

/* Two spheres meeting head-on at relative speed vi, or (wall 1) a sphere meeting a plane wall of the same material at
 * x = 0 (r* = R, m* = m); follows the contact until it lets go (or max_steps). The force on the sphere at +x (the
 * sphere, at the wall), compared with the closed form at every step in contact */
static impact_result impact(const jkr_closed *t, double vi, double dt, long max_steps, dem_precision prec, int wall)
{
    dem_material m = powder();
    const dem_material *wm = wall ? &m : NULL;
    unsigned fx = FX_ADH | (wall ? DEM_EFFECT_WALLS : 0u);
    dem_sim *cl = head_on_build(&m, wm, R, vi, fx, dt), *ref = head_on_build(&m, wm, R, vi, fx, dt);
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, prec), rc = cfg_of(DEM_BACKEND_REFERENCE, prec);
    c.contacts = wall; /* at a wall, the PoCL run keeps the wall forces (wall_block_kept) and the reference does not
                        * (wall_reduce_block): both ways of summing the wall's force meet twins_step's comparison */
    start_or_fail(cl, &c);
    start_or_fail(ref, &rc);
    int gap_seen = 0;
    impact_result r;
    memset(&r, 0, sizeof r);
    double dmax = 0, e_unload = NAN, ms = wall ? sphere_mass() : sphere_mass() / 2;
    int pi = wall ? 0 : 3; /* the sphere whose force is compared */
    double fscale = 1.5 * M_PI * t->w * t->rs; /* the pull-off force F_c */
    double escale = -jkr_potential(t, 0, 0);   /* the energy an elastic contact holds at zero overlap */
    int in = 0;
    for (long k = 0; k < max_steps; k++) {
        twins_step(cl, ref, 1, "adhesive impact, PoCL vs reference");
        double x[6], f[6], v[6];
        assert_int_equal(dem_get_field(ref, DEM_FIELD_X, x), 0);
        assert_int_equal(dem_get_field(ref, DEM_FIELD_FORCE, f), 0);
        assert_int_equal(dem_get_field(ref, DEM_FIELD_V, v), 0);
        double d = overlap_of(x, prec, wall);
        if (!in && d <= 0)
            continue;
        in = 1;
        dmax = fmax(dmax, d);
        int gone;
        double want = jkr_force(t, d, dmax, &gone), got = f[pi];
        if (gone) { /* the library lets go at the same step, unless d sits at the release to rounding */
            double rho, dp;
            branch(t, dmax, &rho, &dp);
            if (fabs(d - dp - jkr_release(t, rho)) > 1e-6 * fabs(jkr_release(t, rho)))
                assert_true(got == 0);
            r.released = 1;
            r.d_release = d - dp;
            r.v_out = wall ? v[0] : v[3] - v[0];
            r.overlap_at_release = d;
            /* then nothing more: no force while the spheres part (a yielded pair lets go while they still overlap:
             * its dent is deeper), and the speed it left with, to the bit, 500 steps after they no longer overlap */
            long apart = -1;
            for (long q = k + 1; q < max_steps && (apart < 0 || q < apart + 500); q++) {
                twins_step(cl, ref, 1, "adhesive impact after the release, PoCL vs reference");
                assert_int_equal(dem_get_field(ref, DEM_FIELD_X, x), 0);
                assert_int_equal(dem_get_field(ref, DEM_FIELD_FORCE, f), 0);
                assert_int_equal(dem_get_field(ref, DEM_FIELD_V, v), 0);
                assert_true(f[0] == 0 && (wall || f[3] == 0));
                if (apart < 0 && (wall ? x[0] > R : x[3] - x[0] > 2 * R))
                    apart = q;
            }
            assert_true(apart > 0);
            assert_true((wall ? v[0] : v[3] - v[0]) == r.v_out);
            break;
        }
        assert_true(got != 0); /* still in contact */
        if (d < 0 || k % 256 == 0) { /* the stress output (particle_stress.h), across the gap too: seed 000's
                                     * -(r - a_c) F / V n (x) n with a_c = d/2 (a pair) or d (a wall), n along x */
            double sg[12], sr[12], vol = 4.0 / 3.0 * M_PI * R * R * R;
            assert_int_equal(dem_get_field(cl, DEM_FIELD_STRESS, sg), 0);
            assert_int_equal(dem_get_field(ref, DEM_FIELD_STRESS, sr), 0);
            assert_memory_equal(sg, sr, sizeof(double) * (wall ? 6 : 12));
            double sxx = -(R - (wall ? d : 0.5 * d)) * want / vol;
            r.worst_stress = fmax(r.worst_stress, fabs(sr[6 * (pi / 3)] - sxx) / (R * fscale / vol));
            for (int q = 1; q < 6; q++)
                assert_true(sr[6 * (pi / 3) + q] == 0);
            r.stress_gap += d < 0;
        }
        if (wall) { /* the wall received minus the sphere's force, along its normal +x, across the gap too */
            double fw[3], fwn;
            assert_int_equal(dem_wall_force(cl, 0, fw), 0);
            assert_int_equal(dem_wall_normal_force(cl, 0, &fwn), 0);
            assert_true(fw[0] == -got && fwn == got);
            if (d < 0 && !gap_seen) { /* the contact network lists it, with its negative overlap */
                dem_contact *cs;
                long count, npairs;
                assert_int_equal(dem_contacts_get(cl, &cs, &count, &npairs), 0);
                assert_true(count == 1 && npairs == 0 && cs[0].j == -1 && cs[0].overlap < 0);
                /* (fp32: d is the kernels' float overlap, the network's is formed in double from float positions) */
                assert_true(fabs(cs[0].overlap - d) < (prec == DEM_FP64 ? 1e-13 : 3e-11));
                free(cs);
                gap_seen = 1;
            }
        }
        r.steps_in++;
        r.worst = fmax(r.worst, fabs(got - want) / fscale);
        r.f_min = fmin(r.f_min, got);
        r.yielded |= jkr_a(t, t->rs, dmax) > t->ay;
        if (d < dmax) { /* unloading: kinetic + the contact's potential (the host's energy) stays constant */
            dem_energy_t en;
            assert_int_equal(dem_energy(ref, &en), 0);
            double vrel = wall ? v[0] : v[3] - v[0], e = 0.5 * ms * vrel * vrel + en.elastic;
            if (isnan(e_unload))
                e_unload = e;
            r.energy_drift = fmax(r.energy_drift, fabs(e - e_unload));
            /* the host's energy is the closed form's potential */
            r.worst_energy = fmax(r.worst_energy, fabs(en.elastic - jkr_potential(t, d, dmax)) / escale);
        }
    }
    r.stuck = !r.released;
    assert_true(!wall || !r.released || gap_seen); /* a wall contact that let go was held across the gap first */
    r.dmax = dmax;
    dem_destroy(cl);
    dem_destroy(ref);
    return r;
}

/* wall 1: the sphere against a plane wall of the same material: r* = R, m* = m, and a contact that holds across the gap
 * to its release as a pair's does (before 2026-12-06 a wall let go at zero overlap, at -8/9 F_c: this case failed) */
static void elastic_impacts(dem_precision prec, int wall)
{
    jkr_closed t = jkr_of(YOUNG / (2 * (1 - NU * NU)), wall ? R : R / 2);
    double ms = wall ? sphere_mass() : sphere_mass() / 2;
    /* the energy lost between forming at zero overlap and letting go: the potential's value at delta = 0 */
    double dw = -jkr_potential(&t, 0, 0), vs = sqrt(2 * dw / ms);
    /* Thornton and Ning's sticking speed for elastic adhesive spheres (their Eq. 54, as a digest of the paper quotes
     * it: V_s = (14.18 / m*)^(1/2) (w^5 R*^4 / E*^2)^(1/6); our quadrature gives the same to its rounded 14.18) */
    double vs_tn = sqrt(14.18 / ms) * pow(pow(W, 5) * pow(t.rs, 4) / (t.es * t.es), 1.0 / 6.0);
    assert_true(fabs(vs / vs_tn - 1) < 1e-3);
    double tc = 2.87 * pow(ms * ms / (t.rs * t.es * t.es * vs), 0.2), dt = tc / 3000;
    double tol = prec == DEM_FP64 ? 1e-9 : 1e-4;
    impact_result slow = impact(&t, 0.9 * vs, dt, 3 * 3000, prec, wall); /* three contact times: it stays */
    impact_result fast = impact(&t, 1.2 * vs, dt, 8 * 3000, prec, wall);
    double vout_want = sqrt(1.44 - 1) * vs, fc = 1.5 * M_PI * W * t.rs;
    printf("  elastic, %s%s: V_s %.5g m/s; at 0.9 V_s %s after %d steps in contact (worst force %.2g F_c); at 1.2 V_s "
           "parted after %d steps at delta - delta_c %.3g m, at %.6g m/s (energy balance: %.6g), least force %.6f F_c "
           "(JKR: -1), worst force %.2g F_c, host's energy against the closed form %.2g dW, energy drift through the "
           "unloading %.2g dW\n",
           wall ? "at a wall, " : "", prec == DEM_FP64 ? "fp64" : "fp32", vs, slow.stuck ? "stuck" : "PARTED", slow.steps_in, slow.worst,
           fast.steps_in, fast.d_release - jkr_release(&t, t.rs), fast.v_out, vout_want, fast.f_min / fc, fast.worst,
           fast.worst_energy, fast.energy_drift / dw);
    assert_true(slow.stuck && slow.steps_in > 8900 && !slow.yielded);
    assert_true(fast.released && !fast.yielded);
    assert_true(slow.worst < tol && fast.worst < tol);
    /* the stress output across the gap (before 2026-12-06 it left such contacts out: 0 where JKR pulls) */
    printf("  stress output, %s: worst %.2g R F_c / V over the contact, %d steps across the gap checked\n",
           prec == DEM_FP64 ? "fp64" : "fp32", fmax(slow.worst_stress, fast.worst_stress), fast.stress_gap);
    assert_true(fast.stress_gap > 10);
    assert_true(slow.worst_stress < tol && fast.worst_stress < tol);
    assert_true(fabs(fast.f_min / fc + 1) < 2e-3); /* sampled near the pull-off force */
    assert_true(fast.worst_energy < (prec == DEM_FP64 ? 1e-6 : 1e-2));
    /* the rebound and the energy through the unloading, in fp64 only: a step moves these spheres 6e-12 m, less than
     * fp32's spacing of their positions (7e-12 m at 1e-4 m), so an fp32 run's motion is rounded away (its rebound
     * was 2.7 % fast) while its force at each step's overlap is the law's (above) */
    if (prec == DEM_FP64) {
        assert_true(fabs(fast.v_out / vout_want - 1) < 5e-3);
        assert_true(fast.energy_drift < 1e-3 * dw);
    }
}

static void plastic_impact(dem_precision prec)
{
    jkr_closed t = jkr_of(YOUNG / (2 * (1 - NU * NU)), R / 2);
    double ms = sphere_mass() / 2;
    double vy = sqrt(2 * 0.4 * t.fy * t.dy / ms), vi = 5 * vy; /* the speed that just yields, without adhesion */
    double tc = 2.87 * pow(ms * ms / (t.rs * t.es * t.es * vi), 0.2), dt = tc / 3000;
    impact_result r = impact(&t, vi, dt, 10 * 3000, prec, 0);
    /* the flattened radius of the largest contact, and its pull-off force -3/2 pi w R_p */
    double rho, dp;
    branch(&t, r.dmax, &rho, &dp);
    double fcp = 1.5 * M_PI * W * rho;
    printf("  plastic, %s: V_y %.4g m/s, V_i %.4g; delta_max %.4g m (delta_y %.4g), R_p / R* %.4f; %s after %d steps "
           "at overlap %.4g m (delta - delta_p - delta_c %.3g m) at %.6g m/s; least force %.6f F_cp (-1: JKR of R_p), worst force %.2g F_c, "
           "host's energy %.2g dW (%.2g of the kinetic energy in), energy drift through the unloading %.2g of the kinetic energy in\n",
           prec == DEM_FP64 ? "fp64" : "fp32", vy, vi, r.dmax, t.dy, rho / t.rs, r.released ? "parted" : "STUCK",
           r.steps_in, r.overlap_at_release, r.d_release - jkr_release(&t, rho), r.v_out, r.f_min / fcp, r.worst, r.worst_energy,
           r.worst_energy * -jkr_potential(&t, 0, 0) / (0.25 * ms * vi * vi),
           r.energy_drift / (0.25 * ms * vi * vi));
    assert_true(r.yielded && r.released && rho > 1.5 * t.rs);
    assert_true(r.worst < (prec == DEM_FP64 ? 1e-9 : 1e-3));
    assert_true(r.worst_stress < (prec == DEM_FP64 ? 1e-9 : 1e-3)); /* the stress output on R_p's branch */
    assert_true(fabs(r.f_min / fcp + 1) < 2e-3); /* Thornton and Ning's F_cp = F_c R_p / R* */
    /* (dW is small beside this contact's energy: the host's energy against the kinetic energy in) */
    double ein = 0.25 * ms * vi * vi, dw = -jkr_potential(&t, 0, 0);
    assert_true(r.worst_energy * dw < (prec == DEM_FP64 ? 1e-9 : 1e-4) * ein);
    if (prec == DEM_FP64)
        assert_true(r.energy_drift < 1e-6 * 0.25 * ms * vi * vi);
}

static void test_elastic_fp64(void **st) { (void)st; elastic_impacts(DEM_FP64, 0); }
static void test_elastic_fp32(void **st) { (void)st; elastic_impacts(DEM_FP32, 0); }
static void test_wall_fp64(void **st) { (void)st; elastic_impacts(DEM_FP64, 1); }
static void test_wall_fp32(void **st) { (void)st; elastic_impacts(DEM_FP32, 1); }
static void test_plastic_fp64(void **st) { (void)st; plastic_impact(DEM_FP64); }
static void test_plastic_fp32(void **st) { (void)st; plastic_impact(DEM_FP32); }

/* Two spheres of material m at centres (-/+ half, 0, 0) with velocities va and vb (no walls, no gravity) */
static dem_sim *spheres_build(const dem_material *m, double half, const double va[3], const double vb[3], unsigned fx,
                           double dt)
{
    dem_sim *s = dem_create();
    int id = dem_add_material(s, m);
    dem_add_particle(s, (double[3]){-half, 0, 0}, va, R, id);
    dem_add_particle(s, (double[3]){half, 0, 0}, vb, R, id);
    double L = 8 * R;
    dem_set_domain(s, (double[3]){-L, -L, -L}, (double[3]){L, L, L});
    if (dem_set_effects(s, fx))
        fail_msg("%s", dem_error(s));
    dem_set_dt(s, dt);
    return s;
}

/* Friction with adhesion: Thornton and Yin's sliding criterion for an adhesive contact, |T| = mu (P + 2 P_c) with P_c
 * JKR's pull-off force 3/2 pi w R* (adhesion raises the load that friction resists). Two spheres set at JKR's
 * zero-force overlap (a0^3 = 9 pi w R*^2 / (2 E*)), sliding past each other at 1 m/s: the normal force stays near zero
 * (the pair orbits, a small tension), so without the adhesive term the Coulomb limit mu P would be about 0. At every
 * step the tangential force (from the sphere's total force, split along the line of centres) is at most
 * mu (P + 2 P_c), and it slides at that limit */
static void friction_case(dem_precision prec)
{
    jkr_closed t = jkr_of(YOUNG / (2 * (1 - NU * NU)), R / 2);
    double mu = 0.5, vt = 1.0, dt = 2e-9, fc = 1.5 * M_PI * W * t.rs;
    double a0 = cbrt(9 * M_PI * W * t.rs * t.rs / (2 * t.es)), d0 = jkr_delta(&t, t.rs, a0);
    assert_true(fabs(jkr_force_a(&t, t.rs, a0)) < 1e-12 * fc && d0 > 0);
    dem_material m = powder();
    m.friction = mu;
    unsigned fx = FX_ADH | DEM_EFFECT_FRICTION;
    double va[3] = {0, -0.5 * vt, 0}, vb[3] = {0, 0.5 * vt, 0}, half = R - 0.5 * d0;
    dem_sim *cl = spheres_build(&m, half, va, vb, fx, dt), *ref = spheres_build(&m, half, va, vb, fx, dt);
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, prec), rc = cfg_of(DEM_BACKEND_REFERENCE, prec);
    start_or_fail(cl, &c);
    start_or_fail(ref, &rc);
    double tol = prec == DEM_FP64 ? 1e-12 : 1e-5, worst = 0, fn_hi = -INFINITY, fn_lo = INFINITY, ft_lo = INFINITY;
    long sliding = 0;
    for (int k = 0; k < 3000; k++) {
        twins_step(cl, ref, 1, "sliding adhesive contact, PoCL vs reference");
        double x[6], f[6], u[3], dist = 0, fn = 0, ft2 = 0;
        assert_int_equal(dem_get_field(ref, DEM_FIELD_X, x), 0);
        assert_int_equal(dem_get_field(ref, DEM_FIELD_FORCE, f), 0);
        for (int q = 0; q < 3; q++)
            dist += (x[3 + q] - x[q]) * (x[3 + q] - x[q]);
        dist = sqrt(dist);
        for (int q = 0; q < 3; q++) {
            u[q] = (x[3 + q] - x[q]) / dist; /* from a to b: the force on b along it is the normal force P */
            fn += f[3 + q] * u[q];
        }
        for (int q = 0; q < 3; q++)
            ft2 += (f[3 + q] - fn * u[q]) * (f[3 + q] - fn * u[q]);
        double ft = sqrt(ft2), lim = mu * (fn + 2 * fc);
        assert_true(dist < 2 * R + 1e-9); /* still held */
        worst = fmax(worst, ft / lim - 1);
        if (ft >= (1 - tol) * lim) {
            sliding++;
            fn_hi = fmax(fn_hi, fn), fn_lo = fmin(fn_lo, fn), ft_lo = fmin(ft_lo, ft);
        }
    }
    printf("  friction with adhesion, %s: %ld of 3000 steps sliding at mu (P + 2 P_c) (worst excess %.2g), P from "
           "%.3f to %.3f P_c there, |T| at least %.4f mu P_c (without adhesion's term the limit would be mu max(P, 0) "
           "<= %.3f mu P_c)\n",
           prec == DEM_FP64 ? "fp64" : "fp32", sliding, worst, fn_lo / fc, fn_hi / fc, ft_lo / (mu * fc),
           fmax(fn_hi, 0) / fc);
    assert_true(worst <= tol);
    assert_true(sliding > 2000);
    /* the limit sliding met is adhesion's: above mu max(P, 0) by at least mu P_c (it is 2 mu P_c above mu P) */
    assert_true(ft_lo > mu * (fmax(fn_hi, 0) + fc));
    dem_destroy(cl);
    dem_destroy(ref);
}
static void test_friction_fp64(void **st) { (void)st; friction_case(DEM_FP64); }
static void test_friction_fp32(void **st) { (void)st; friction_case(DEM_FP32); }

/* Damping with adhesion: the normal force is JKR's plus Hertz-Mindlin's damping with the stiffness of the JKR contact,
 * S_n = 2 E* a (a JKR's contact radius, not Hertz's sqrt(R* delta)): -c sqrt(S_n m*) v_n, c the factor calibrated for
 * the restitution (dem_damping_for_restitution), v_n the approach speed at the half step the forces see (velocity
 * Verlet: v(t + dt) - dt/2 F / m), bounded below by -3 pi w R* (-2 P_c). A head-on impact at 2 V_s with restitution 0.5,
 * checked at every step in contact against that closed form. */
static void damping_case(dem_precision prec)
{
    jkr_closed t = jkr_of(YOUNG / (2 * (1 - NU * NU)), R / 2);
    double ms = sphere_mass() / 2, mass = sphere_mass(), vs = sqrt(-2 * jkr_potential(&t, 0, 0) / ms);
    double tc = 2.87 * pow(ms * ms / (t.rs * t.es * t.es * vs), 0.2), dt = tc / 3000, fc = 1.5 * M_PI * W * t.rs;
    dem_material m = powder();
    m.restitution = 0.5;
    double cdamp = dem_damping_for_restitution(0.5);
    unsigned fx = FX_ADH | DEM_EFFECT_DAMPING;
    dem_sim *cl = head_on_build(&m, NULL, R, 2 * vs, fx, dt), *ref = head_on_build(&m, NULL, R, 2 * vs, fx, dt);
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, prec), rc = cfg_of(DEM_BACKEND_REFERENCE, prec);
    start_or_fail(cl, &c);
    start_or_fail(ref, &rc);
    double dmax = 0, worst = 0, dmp_max = 0, tol = prec == DEM_FP64 ? 1e-9 : 1e-4;
    int in = 0, released = 0, steps_in = 0;
    for (int k = 0; k < 3 * 3000 && !released; k++) {
        twins_step(cl, ref, 1, "damped adhesive impact, PoCL vs reference");
        double x[6], f[6], v[6];
        assert_int_equal(dem_get_field(ref, DEM_FIELD_X, x), 0);
        assert_int_equal(dem_get_field(ref, DEM_FIELD_FORCE, f), 0);
        assert_int_equal(dem_get_field(ref, DEM_FIELD_V, v), 0);
        double d = overlap_of(x, prec, 0);
        if (!in && d <= 0)
            continue;
        in = 1;
        dmax = fmax(dmax, d);
        int gone;
        double fel = jkr_force(&t, d, dmax, &gone);
        if (gone) {
            released = 1;
            break;
        }
        double a = jkr_a(&t, t.rs, d); /* no yield at 2 V_s: every branch is JKR of R* */
        double vn = (v[3] - 0.5 * dt * f[3] / mass) - (v[0] - 0.5 * dt * f[0] / mass); /* < 0: approaching */
        double dmp = -cdamp * sqrt(2 * t.es * a * ms) * vn;
        double want = fmax(fel + dmp, -2 * fc);
        worst = fmax(worst, fabs(f[3] - want) / fc);
        dmp_max = fmax(dmp_max, fabs(dmp) / fc);
        steps_in++;
    }
    printf("  damping with adhesion, %s: %d steps in contact at 2 V_s, restitution 0.5 (c %.4f); damping force up to "
           "%.3f P_c; worst normal force against JKR + c sqrt(2 E* a m*) v_n: %.2g P_c; %s\n",
           prec == DEM_FP64 ? "fp64" : "fp32", steps_in, cdamp, dmp_max, worst, released ? "parted" : "stuck");
    assert_true(steps_in > 1000 && dmp_max > 0.1);
    assert_true(worst < tol);
    dem_destroy(cl);
    dem_destroy(ref);
}
static void test_damping_fp64(void **st) { (void)st; damping_case(DEM_FP64); }
static void test_damping_fp32(void **st) { (void)st; damping_case(DEM_FP32); }

/* The solver alone (tn_jkr_root, in double as the reference runs it): s = sqrt(a) on JKR's stable branch at overlaps from
 * 1e-14 |delta_c| past the release to 1e5 |delta_c|, against a bisection in long double. Next to the release the root
 * is double in s; the solver's start and steps are about the release, so the force there is right to rounding (until
 * 2026-12-06 12 Newton steps in s from far above left 5.7e-4 F_c at 1e-14 |delta_c|: this test failed) */
static void test_root(void **st)
{
    (void)st;
    double es = YOUNG / (2 * (1 - NU * NU)), k = sqrt(2 * M_PI * W / es), fc = 1.5 * M_PI * W * R / 2;
    double rels[] = {1e-14, 1e-12, 1e-10, 1e-8, 1e-6, 1e-4, 1e-2, 0.5, 1, 3, 10, 1e2, 1e3, 1e5};
    double worst_s = 0, worst_f = 0;
    for (int r = 0; r < 2; r++) {
        double rho = r ? 1.57 * R / 2 : R / 2; /* r*, and a flattened R_p */
        double sc = tn_jkr_sc(rho, k), dc = -0.75 * k * sc;
        long double scl = cbrtl((long double)k * rho / 4);
        for (unsigned q = 0; q < sizeof rels / sizeof *rels; q++) {
            double d = dc + fabs(dc) * rels[q];
            long double lo = scl, hi = 2 * scl;
            while (hi * hi * hi * hi / rho - k * hi < d)
                hi *= 2;
            for (int it = 0; it < 300; it++) {
                long double m = (lo + hi) / 2;
                if (m * m * m * m / rho - k * m < d)
                    lo = m;
                else
                    hi = m;
            }
            long double sr = (lo + hi) / 2, ar = sr * sr;
            double s = tn_jkr_root(rho, k, d, sc), a = s * s;
            long double fr = 4.0L / 3 * es * ar * ar * ar / rho - 2.0L * es * k * ar * sr;
            double f = 4.0 / 3 * es * a * a * a / rho - 2 * es * k * a * s;
            worst_s = fmax(worst_s, (double)fabsl((s - sr) / sr));
            if (rels[q] <= 10)
                worst_f = fmax(worst_f, (double)fabsl((f - fr) / fc));
        }
    }
    printf("  the root alone: s to %.2g (relative), the force within 10 |delta_c| of the release to %.2g F_c\n", worst_s,
           worst_f);
    /* (at 1e-14 |delta_c| the overlap's own rounding, and s_c's, move D = rho (delta - delta_c) by about 1 %: the root
     * is that ill-conditioned there: 5.8e-10 in s, 7.7e-10 F_c in the force at 1.57 r*, measured) */
    assert_true(worst_s < 3e-9);
    assert_true(worst_f < 3e-9);
}

/* A pair's own work of adhesion (dem_set_material_pair) acts as the materials' would: materials at 0 and the pair at
 * W run bit for bit as materials at W (sqrt(W W) = W exactly), and a pair set to 0 does not adhere */
static void test_pair_adhesion(void **st)
{
    (void)st;
    jkr_closed t = jkr_of(YOUNG / (2 * (1 - NU * NU)), R / 2);
    double ms = sphere_mass() / 2, vs = sqrt(-2 * jkr_potential(&t, 0, 0) / ms), dt = 1e-9;
    dem_material m = powder(), bare = powder();
    bare.surface_energy = 0;
    dem_sim *a = head_on_build(&m, NULL, R, 0.9 * vs, FX_ADH, dt), *b = head_on_build(&bare, NULL, R, 0.9 * vs, FX_ADH, dt);
    assert_int_equal(dem_set_material_pair(b, 0, 0, &(dem_material_pair){NAN, NAN, NAN, NAN, W}), 0);
    dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    start_or_fail(a, &c);
    start_or_fail(b, &c);
    twins_step(a, b, 3000, "a pair's work of adhesion against its materials'");
    dem_energy_t en; /* they met and stick (0.9 V_s): one contact, and the adhesive energy in it */
    assert_int_equal(dem_energy(b, &en), 0);
    assert_true(en.contacts == 1 && en.elastic < 0);
    dem_destroy(a);
    dem_destroy(b);
    /* a pair set to 0 of materials that adhere: nothing else adheres, so the run is refused */
    a = head_on_build(&m, NULL, R, 0.9 * vs, FX_ADH, dt);
    assert_int_equal(dem_set_material_pair(a, 0, 0, &(dem_material_pair){NAN, NAN, NAN, NAN, 0}), 0);
    assert_int_equal(dem_start(a, &c), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(a), "no pair of materials adheres"));
    dem_destroy(a);
}

static void test_refusals(void **st)
{
    (void)st;
    dem_sim *s = dem_create();
    assert_int_equal(dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_ADHESION), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "thornton_ning"));
    dem_destroy(s);
    /* no surface energy: refused at the start */
    dem_material m = powder();
    m.surface_energy = 0;
    s = head_on_build(&m, NULL, R, 0.1, FX_ADH, 1e-9);
    dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    assert_int_equal(dem_start(s, &c), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "no pair of materials adheres"));
    dem_destroy(s);
    /* adhesion and bonds on one pair */
    m = powder();
    m.bond_strength = 1e6;
    s = head_on_build(&m, NULL, R, 0.1, FX_ADH, 1e-9);
    assert_int_equal(dem_start(s, &c), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "one adhesion per pair"));
    dem_destroy(s);
}

int main(void)
{
    test_pocl_threads(); /* the suite's multi-thread runs of these laws (test_util.h) */
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_elastic_fp64), cmocka_unit_test(test_elastic_fp32), cmocka_unit_test(test_plastic_fp64),
        cmocka_unit_test(test_plastic_fp32), cmocka_unit_test(test_wall_fp64), cmocka_unit_test(test_wall_fp32),
        cmocka_unit_test(test_friction_fp64), cmocka_unit_test(test_friction_fp32), cmocka_unit_test(test_damping_fp64),
        cmocka_unit_test(test_damping_fp32), cmocka_unit_test(test_root), cmocka_unit_test(test_pair_adhesion),
        cmocka_unit_test(test_refusals),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
