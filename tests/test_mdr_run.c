/* test_mdr_run.c - the MDR law in a run (common/laws/mdr.h, common/mdr_particle.h) against its one-contact core
 * walked along the same path (common/laws/mdr_core.h mdr_walk, which tests/test_mdr.c checks against the Python
 * reference of docs/laws/mdr.md and `make peer-mdr` against LAMMPS itself):
 *   - two spheres (equal, and 0.5/0.3 mm with adhesion) on held velocities loaded, unloaded, reloaded and pulled
 *     apart; the velocities reversed between phases through dem_state_get/dem_state_set (so each phase also starts
 *     from a restored state);
 *   - a sphere on held velocity pressed on a plane wall, with adhesion, the same phases;
 *   - a fixed sphere between six planes closing in (Part II: the bulk response, the mean surface displacement and the
 *     radius update act), its first plane's force;
 *   - the same sphere walked round square loops by its x and y planes once the bulk response acts: each loop's work
 *     against LAMMPS's figures (tools/peer_mdr/energy_loop.py; docs/laws/mdr.md "Energy");
 *   - a fixed sphere between two planes closing in at psi_b 0 until its radius meets (M34)'s cap of 1.5 R_o, and the
 *     step dem_mdr_capped names (docs/laws/mdr.md "Range");
 *   - bonds (docs/laws/mdr.md "Bonds"): a bonded pair pulled, pressed further and pulled again, against the closed
 *     forms of F_b and the tension's slope; the same pair sheared until it slides at mu (F_n + F_b), then pulled
 *     without a bond; an unequal pair whose bridge breaks as a whole;
 *   - an MDR packing (with bonds) under a moving lid: the OpenCL run equal to the reference bit for bit, skins,
 *     storage order and a restart bit for bit.
 * The walk is fed the approach the run's own positions give at each step, so the two see the same overlaps; the
 * force on the run's first body is compared with the walk's at every step (fp64 to 1e-9 of the path's peak force,
 * fp32 to 2e-3), the apparent radius at the end, and on OpenCL every step's force bit for bit with the reference's. */
#include "test_util.h"
#include "ref_kernels.h" /* dem_mdr_walk_f32/_f64 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { WALK_PAIR = 0, WALK_WALL = 1, WALK_BOX = 2 }; /* mdr_core.h's MDR_WALK_* */

/* Zunker et al.'s MCC as make peer-mdr runs it (docs/laws/mdr.md "Against LAMMPS") */
#define E_MCC 5e9
#define NU_MCC 0.4
#define Y_MCC 1.9e8
#define RHO_MCC 1560.0
#define PSI_B 0.5
#define ETA_D 0.2
#define R1 5e-4
#define DT 1e-6

static dem_material mcc(double gamma)
{
    dem_material m = {RHO_MCC, E_MCC, NU_MCC, 1.0, 0.0, 0.0, 0.0, Y_MCC};
    m.surface_energy = gamma, m.bulk_fraction = PSI_B, m.mdr_damping = ETA_D;
    return m;
}

/* The walk's 8 material reals (mdr_material_from's order) in double */
static void walk_material(double gamma, double mat[8])
{
    mat[0] = E_MCC / (1 - NU_MCC * NU_MCC), mat[1] = E_MCC / (2 * (1 + NU_MCC)), mat[2] = E_MCC / (3 * (1 - 2 * NU_MCC));
    mat[3] = NU_MCC, mat[4] = Y_MCC, mat[5] = gamma, mat[6] = PSI_B, mat[7] = ETA_D;
}

static double mass_of(double r) { return RHO_MCC * 4.0 / 3.0 * M_PI * r * r * r; }

/* The path: phases of held approach speed (m/s, negative: apart) and their steps */
typedef struct {
    int nphase;
    double speed[4];
    long steps[4];
} path;

/* The run's side of one case: per step the approach u (from positions), the normal force on the first body, and the
 * raw force bits (to compare backends); and the first body's apparent radius at the end */
typedef struct {
    long n;
    double *u, *f;
    double r_end;
    unsigned char *bits; /* 3 reals of particle 0's force per step, the run's precision */
} run_out;

/* Reverses the held velocities (every particle's v negated, then scaled to the next phase's speed) through the state */
static void set_speed(dem_sim *s, double old_speed, double new_speed)
{
    dem_state st;
    if (dem_state_get(s, &st))
        fail_msg("dem_state_get: %s", dem_error(s));
    dem_state_array *v = dem_state_find(&st, "v");
    assert_non_null(v);
    for (size_t k = 0; k < v->count; k++) {
        if (st.real_size == 8)
            ((double *)v->data)[k] *= new_speed / old_speed;
        else
            ((float *)v->data)[k] = (float)(((float *)v->data)[k] * (new_speed / old_speed));
    }
    if (dem_state_set(s, &st))
        fail_msg("dem_state_set: %s", dem_error(s));
    dem_state_free(&st);
}

/* kind WALK_PAIR: spheres of radii r1, r2 touching at t = 0 on the x axis, 0 at -r1 moving +v/2 and 1 at +r2 moving
 * -v/2; WALK_WALL: sphere r1 at x = r1 moving -v onto the plane x = 0 */
static run_out run_path(const backend_case *bc, int kind, double r1, double r2, double gamma, const path *pa)
{
    dem_sim *s = dem_create();
    dem_material m = mcc(gamma), steel = {7800, INFINITY, 0.3, 1.0, 0.0};
    steel.surface_energy = gamma; /* a wall takes its material's surface energy (as LAMMPS) */
    int mat = dem_add_material(s, &m), wmat = dem_add_material(s, &steel);
    double v0 = pa->speed[0];
    if (kind == WALK_PAIR) {
        dem_add_particle(s, (double[3]){-r1, 0, 0}, (double[3]){0.5 * v0, 0, 0}, r1, mat);
        dem_add_particle(s, (double[3]){r2, 0, 0}, (double[3]){-0.5 * v0, 0, 0}, r2, mat);
        dem_set_particle_flags(s, 0, DEM_PARTICLE_HOLD_V);
        dem_set_particle_flags(s, 1, DEM_PARTICLE_HOLD_V);
    } else {
        dem_add_particle(s, (double[3]){r1, 0, 0}, (double[3]){-v0, 0, 0}, r1, mat);
        dem_set_particle_flags(s, 0, DEM_PARTICLE_HOLD_V);
        dem_wall w = {0};
        w.kind = DEM_WALL_PLANE, w.normal[0] = 1, w.material = wmat;
        if (dem_add_wall(s, &w) < 0)
            fail_msg("%s", dem_error(s));
    }
    dem_set_domain(s, (double[3]){-8 * r1, -8 * r1, -8 * r1}, (double[3]){8 * r1, 8 * r1, 8 * r1});
    unsigned fx = DEM_EFFECT_HERTZ | DEM_EFFECT_DAMPING | DEM_EFFECT_MDR | DEM_EFFECT_CONSTRAINTS |
                  (kind == WALK_WALL ? DEM_EFFECT_WALLS : 0);
    if (dem_set_effects(s, fx) || dem_set_dt(s, DT))
        fail_msg("%s", dem_error(s));
    dem_config c = cfg_of(bc->backend, bc->precision);
    c.force_dt = 1; /* LAMMPS's step of make peer-mdr: above half the Rayleigh time, harmless on held velocities */
    start_or_fail(s, &c);
    run_out o;
    o.n = 0;
    for (int k = 0; k < pa->nphase; k++)
        o.n += pa->steps[k];
    o.u = calloc((size_t)o.n + 1, sizeof(double));
    o.f = calloc((size_t)o.n + 1, sizeof(double));
    o.bits = calloc((size_t)o.n + 1, 3 * (size_t)bc->precision);
    assert_true(o.u && o.f && o.bits);
    double x[6], f[6];
    long step = 0;
    for (int ph = 0; ph < pa->nphase; ph++) {
        if (ph)
            set_speed(s, pa->speed[ph - 1], pa->speed[ph]);
        for (long k = 0; k < pa->steps[ph]; k++) {
            step_or_fail(s, 1);
            step++;
            if (dem_get_field(s, DEM_FIELD_X, x) || dem_get_field(s, DEM_FIELD_FORCE, f) ||
                dem_get_raw(s, DEM_FIELD_FORCE, o.bits + (size_t)step * 3 * bc->precision, 3 * (size_t)bc->precision))
                fail_msg("%s", dem_error(s));
            /* the approach the walk takes: R1 + R2 - d (a pair), R1 - d (a wall) */
            o.u[step] = kind == WALK_PAIR ? (r1 + r2) - (x[3] - x[0]) : r1 - x[0];
            o.f[step] = kind == WALK_PAIR ? -f[0] : f[0]; /* the normal force, positive when repulsive */
        }
    }
    dem_state st;
    if (dem_state_get(s, &st))
        fail_msg("%s", dem_error(s));
    dem_state_array *mp = dem_state_find(&st, "mdr_particle");
    assert_non_null(mp);
    o.r_end = st.real_size == 8 ? ((double *)mp->data)[1] : ((float *)mp->data)[1];
    double rf[2]; /* the public field DEM_FIELD_RADIUS reads the same apparent radius */
    if (dem_get_field(s, DEM_FIELD_RADIUS, rf) || rf[0] != o.r_end)
        fail_msg("DEM_FIELD_RADIUS gives %.17g m, the particle's row %.17g m", rf[0], o.r_end);
    dem_state_free(&st);
    dem_destroy(s);
    return o;
}

/* The walk (mdr_core.h mdr_walk) of approach u over steps 0..n in the reference of precision p, with the walk's
 * material of surface energy gamma and damping eta_d: its rows delta, radius, psi, force, each n + 1 long, in one
 * block (free it) */
static double *walk_rows(dem_precision p, int kind, long n, const double *u, double r1, double r2, double gamma,
                         double eta_d)
{
    size_t m = (size_t)n + 1;
    double mat[8], *out = malloc(4 * m * sizeof(double));
    walk_material(gamma, mat);
    mat[7] = eta_d;
    assert_non_null(out);
    if (p == DEM_FP64) {
        dem_mdr_walk_f64(kind, (int)n, u, mat, r1, r2, mass_of(r1), mass_of(r2), DT, out, out + m, out + 2 * m,
                         out + 3 * m);
    } else {
        float *uf = malloc(m * sizeof(float)), matf[8], *b = malloc(4 * m * sizeof(float));
        assert_true(uf && b);
        for (size_t k = 0; k < m; k++)
            uf[k] = (float)u[k];
        for (int k = 0; k < 8; k++)
            matf[k] = (float)mat[k];
        dem_mdr_walk_f32(kind, (int)n, uf, matf, (float)r1, (float)r2, (float)mass_of(r1), (float)mass_of(r2),
                         (float)DT, b, b + m, b + 2 * m, b + 3 * m);
        for (size_t k = 0; k < 4 * m; k++)
            out[k] = b[k];
        free(uf), free(b);
    }
    return out;
}

/* The walk of the run's approach in the reference of the run's precision: its force on the first body per step and
 * the first sphere's radius at the end */
static double *walk_of(const backend_case *bc, int kind, double r1, double r2, double gamma, const run_out *o,
                       double *r_end)
{
    size_t m = (size_t)o->n + 1;
    double *out = walk_rows(bc->precision, kind, o->n, o->u, r1, r2, gamma, ETA_D);
    *r_end = out[m + o->n];
    return out + 3 * m; /* the forces (the block starts 3 m before) */
}

static void path_case(int kind, double r1, double r2, double gamma, const path *pa, const char *what)
{
    unsigned char *ref_bits[2] = {NULL, NULL};
    FOR_EACH_BACKEND(bc) {
        run_out o = run_path(bc, kind, r1, r2, gamma, pa);
        double r_walk;
        double *fw = walk_of(bc, kind, r1, r2, gamma, &o, &r_walk);
        double peak = 0, worst = 0, least = 0;
        long at = 0;
        for (long k = 0; k <= o.n; k++) {
            peak = fmax(peak, fabs(fw[k]));
            least = fmin(least, fw[k]);
        }
        for (long k = 0; k <= o.n; k++)
            if (fabs(o.f[k] - fw[k]) > worst)
                worst = fabs(o.f[k] - fw[k]), at = k;
        double tol = bc->precision == DEM_FP64 ? 1e-9 : 2e-3;
        printf("  %s, %s: %ld steps, peak %.4g N, least %.4g N, largest |F_run - F_walk| %.3g of the peak (step "
               "%ld), radius %.9g mm (walk %.9g)\n",
               what, bc->name, o.n, peak, least, worst / peak, at, o.r_end * 1e3, r_walk * 1e3);
        if (!(peak > 0) || !(worst <= tol * peak))
            fail_msg("%s, %s: the run's force departs from the walk's by %g of the peak %g N at step %ld (run %.17g, "
                     "walk %.17g)",
                     what, bc->name, worst / peak, peak, at, o.f[at], fw[at]);
        if (!(fabs(o.r_end - r_walk) <= (bc->precision == DEM_FP64 ? 1e-12 : 1e-5) * r1) || !(r_walk > r1))
            fail_msg("%s, %s: apparent radius %.17g m at the end, the walk's %.17g m (grown from %g)", what, bc->name,
                     o.r_end, r_walk, r1);
        if (gamma > 0 && !(least < -5e-4 * peak))
            fail_msg("%s, %s: adhesion never pulled (least force %g N of a peak %g N)", what, bc->name, least, peak);
        int p = bc->precision == DEM_FP64 ? 0 : 1;
        size_t bytes = ((size_t)o.n + 1) * 3 * (size_t)bc->precision;
        if (bc->backend == DEM_BACKEND_REFERENCE)
            ref_bits[p] = o.bits, o.bits = NULL;
        else if (!ref_bits[p] || memcmp(ref_bits[p], o.bits, bytes))
            fail_msg("%s, %s: the force is not the reference's bit for bit", what, bc->name);
        free(o.u), free(o.f), free(o.bits), free(fw - 3 * ((size_t)o.n + 1));
    }
    free(ref_bits[0]), free(ref_bits[1]);
}

/* Two equal spheres of 0.5 mm: 0.1 m/s approach, loaded to about 9 % of R per sphere, unloaded past zero force, reloaded
 * deeper and pulled apart; without adhesion */
static void test_pair_path(void **state)
{
    (void)state;
    path pa = {4, {0.1, -0.1, 0.1, -0.1}, {900, 500, 900, 1400}};
    path_case(WALK_PAIR, R1, R1, 0.0, &pa, "pair 0.5/0.5 mm");
}

/* 0.5 and 0.3 mm with adhesion (2 J/m^2): the flat off the middle (M3), the tensile branch */
static void test_unequal_adhesive_pair(void **state)
{
    (void)state;
    path pa = {4, {0.1, -0.1, 0.1, -0.1}, {700, 400, 700, 1200}};
    path_case(WALK_PAIR, R1, 3e-4, 2.0, &pa, "pair 0.5/0.3 mm, 2 J/m^2");
}

/* A sphere on a plane wall with adhesion (50 J/m^2) */
static void test_wall_path(void **state)
{
    (void)state;
    path pa = {4, {0.05, -0.05, 0.05, -0.05}, {900, 500, 900, 1500}};
    path_case(WALK_WALL, R1, R1, 50.0, &pa, "wall, 50 J/m^2");
}

/* Starts s, spheres of radius R1 near the origin, on bc's backend and precision: MDR with the effects extra (walls,
 * damping), dt DT, in a domain of 4 R1 about the origin */
static void start_mdr(dem_sim *s, const backend_case *bc, unsigned extra)
{
    dem_set_domain(s, (double[3]){-4 * R1, -4 * R1, -4 * R1}, (double[3]){4 * R1, 4 * R1, 4 * R1});
    if (dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_MDR | extra) || dem_set_dt(s, DT))
        fail_msg("%s", dem_error(s));
    dem_config c = cfg_of(bc->backend, bc->precision);
    c.force_dt = 1;
    start_or_fail(s, &c);
}

/* A fixed sphere of radius R1 at the origin between six planes (-x, +x, -y, +y, -z, +z), each touching it with its
 * normal inwards, started: plane k moves at vel[(k * nstages + q) * 3 ...] in its stage q, which lasts n[q] whole steps
 * (the walk and the loops are fed positions, so the steps are what count). test_box and the loops' planes_loop. */
static dem_sim *six_planes(const backend_case *bc, int nstages, const long *n, const double *vel)
{
    dem_sim *s = dem_create();
    dem_material m = mcc(0.0), steel = {7800, INFINITY, 0.3, 1.0, 0.0};
    int mat = dem_add_material(s, &m), wmat = dem_add_material(s, &steel);
    dem_add_particle(s, (double[3]){0, 0, 0}, (double[3]){0, 0, 0}, R1, mat);
    dem_set_particle_flags(s, 0, DEM_PARTICLE_FIXED);
    for (int k = 0; k < 6; k++) {
        dem_wall w = {0};
        int ax = k / 2, sg = k % 2 ? 1 : -1;
        w.kind = DEM_WALL_PLANE, w.material = wmat;
        w.point[ax] = sg * R1, w.normal[ax] = -sg;
        dem_stage st[DEM_MAX_STAGES];
        assert_true(nstages <= DEM_MAX_STAGES);
        memset(st, 0, sizeof st);
        for (int q = 0; q < nstages; q++) {
            st[q].duration = ((double)n[q] - 0.5) * DT;
            memcpy(st[q].velocity, vel + 3 * ((size_t)k * nstages + q), sizeof st[q].velocity);
        }
        int id = dem_add_wall(s, &w);
        if (id < 0 || dem_set_wall_motion(s, id, nstages, st))
            fail_msg("%s", dem_error(s));
    }
    start_mdr(s, bc, DEM_EFFECT_WALLS);
    return s;
}

/* A fixed sphere of 0.5 mm between six planes that close in together at 0.1 m/s: loaded to 20 % of R, unloaded to 12 %,
 * reloaded to 24 % and unloaded out of contact, without damping, as the walk's box (Part II's bulk response sets in
 * below psi_b = 0.5, near 19 %). The walk is fed the run's first plane's approach; its force is the first plane's. */
static void test_box(void **state)
{
    (void)state;
    double v = 0.1, rt[4] = {0.2, 0.08, 0.12, 0.26}; /* each phase's travel, in R */
    long steps[4];
    double vel[6][4][3] = {{{0}}};
    for (int k = 0; k < 4; k++)
        steps[k] = lround(rt[k] * R1 / (v * DT));
    for (int k = 0; k < 6; k++) /* in, out, in, out */
        for (int q = 0; q < 4; q++)
            vel[k][q][k / 2] = (q % 2 ? 1 : -1) * (k % 2 ? 1 : -1) * v;
    unsigned char *ref_bits[2] = {NULL, NULL};
    FOR_EACH_BACKEND(bc) {
        dem_sim *s = six_planes(bc, 4, steps, &vel[0][0][0]);
        long n = steps[0] + steps[1] + steps[2] + steps[3];
        double *u = calloc((size_t)n + 1, sizeof(double)), *f = calloc((size_t)n + 1, sizeof(double));
        size_t rs = (size_t)bc->precision;
        unsigned char *bits = calloc((size_t)n + 1, 3 * rs);
        assert_true(u && f && bits);
        for (long k = 1; k <= n; k++) {
            double p[3], wf[3 * 6];
            step_or_fail(s, 1);
            if (dem_wall_position(s, 0, p) || dem_get_field(s, DEM_FIELD_WALL_FORCE, wf) ||
                dem_get_raw(s, DEM_FIELD_WALL_FORCE, bits + (size_t)k * 3 * rs, 3 * rs))
                fail_msg("%s", dem_error(s));
            u[k] = R1 + p[0];  /* plane 0 at x = -(R - u) */
            f[k] = -wf[0];     /* the -x plane receives -F along x */
        }
        size_t m1 = (size_t)n + 1;
        /* the walk's box has no damping (and the run none: no damping effect) */
        double *out = walk_rows(bc->precision, WALK_BOX, n, u, R1, R1, 0.0, 0.0);
        double *fw = out + 3 * m1, *psi = out + 2 * m1, peak = 0, worst = 0, psi_min = 1;
        long at = 0;
        for (long k = 0; k <= n; k++) {
            peak = fmax(peak, fabs(fw[k]));
            psi_min = fmin(psi_min, psi[k]);
            if (fabs(f[k] - fw[k]) > worst)
                worst = fabs(f[k] - fw[k]), at = k;
        }
        dem_state st;
        if (dem_state_get(s, &st))
            fail_msg("%s", dem_error(s));
        dem_state_array *mp = dem_state_find(&st, "mdr_particle");
        assert_non_null(mp);
        double r_end = st.real_size == 8 ? ((double *)mp->data)[1] : ((float *)mp->data)[1];
        dem_state_free(&st);
        printf("  six planes, %s: %ld steps, peak %.4g N, least psi %.3f, largest |F_run - F_walk| %.3g of the peak "
               "(step %ld), radius %.9g mm (walk %.9g)\n",
               bc->name, n, peak, psi_min, worst / peak, at, r_end * 1e3, out[m1 + n] * 1e3);
        double tol = bc->precision == DEM_FP64 ? 1e-9 : 2e-3;
        if (!(peak > 0) || !(worst <= tol * peak))
            fail_msg("six planes, %s: the run's force departs from the walk's by %g of the peak %g N at step %ld (run "
                     "%.17g, walk %.17g)", bc->name, worst / peak, peak, at, f[at], fw[at]);
        if (!(psi_min < PSI_B))
            fail_msg("six planes, %s: psi stayed at %g or above: Part II's bulk response was not reached", bc->name,
                     psi_min);
        if (dem_mdr_capped(s, NULL) != -1) /* the radius ends 1.044-fold here: far from the cap */
            fail_msg("six planes, %s: the run says a radius met MDR's cap (step %ld)", bc->name, dem_mdr_capped(s, NULL));
        if (!(fabs(r_end - out[m1 + n]) <= (bc->precision == DEM_FP64 ? 1e-12 : 1e-5) * R1))
            fail_msg("six planes, %s: apparent radius %.17g m, the walk's %.17g m", bc->name, r_end, out[m1 + n]);
        int pp = bc->precision == DEM_FP64 ? 0 : 1;
        if (bc->backend == DEM_BACKEND_REFERENCE)
            ref_bits[pp] = bits, bits = NULL;
        else if (!ref_bits[pp] || memcmp(ref_bits[pp], bits, m1 * 3 * rs))
            fail_msg("six planes, %s: the wall force is not the reference's bit for bit", bc->name);
        free(u), free(f), free(bits), free(out);
        dem_destroy(s);
    }
    free(ref_bits[0]), free(ref_bits[1]);
}

/* ---- work round a closed loop with the bulk response on (docs/laws/mdr.md "Energy") ----
 * The fixed sphere between six planes (six_planes); plane k (-x, +x, -y, +y, -z, +z) moves by the velocities
 * vel[k][q] of its stages, each q lasting n[q] steps: first the planes close in (stage 0, n0 = n[0] steps), then
 * LOOP_N loops of 4 legs each. *w gets the work the planes put into the sphere over each loop (trapezoidal rule on
 * each plane's inward travel and the normal force it receives). */
enum { LOOP_N = 3, LOOP_STAGES = 1 + 4 * LOOP_N };
static void planes_loop(const backend_case *bc, const double vel[6][LOOP_STAGES][3], const long n[LOOP_STAGES],
                        double w[LOOP_N])
{
    dem_sim *s = six_planes(bc, LOOP_STAGES, n, &vel[0][0][0]);
    long steps = 0;
    for (int q = 0; q < LOOP_STAGES; q++)
        steps += n[q];
    double in_prev[6] = {0}, f_prev[6] = {0}, acc = 0;
    long n0 = n[0], per = steps - n0;
    per /= LOOP_N;
    for (long k = 1; k <= steps; k++) {
        double wf[3 * 6];
        step_or_fail(s, 1);
        if (dem_get_field(s, DEM_FIELD_WALL_FORCE, wf))
            fail_msg("%s", dem_error(s));
        for (int q = 0; q < 6; q++) {
            int ax = q / 2, sg = q % 2 ? 1 : -1;
            double p[3];
            if (dem_wall_position(s, q, p))
                fail_msg("%s", dem_error(s));
            double in = R1 - sg * p[ax], f = sg * wf[3 * q + ax]; /* its travel inwards; the force it gets outwards */
            if (k > n0)
                acc += 0.5 * (f + f_prev[q]) * (in - in_prev[q]);
            in_prev[q] = in, f_prev[q] = f;
        }
        if (k > n0 && (k - n0) % per == 0)
            w[(k - n0) / per - 1] = acc, acc = 0;
    }
    dem_destroy(s);
}

/* The squeeze loops of tools/peer_mdr/energy_loop.py at speed v: the planes close in together by U0 = 0.21 R (psi
 * below psi_b from about 0.19 R), then walk square loops of side 0.01 R in (u_x, u_y): the x planes in, the y planes
 * in, the x planes out, the y planes out. */
static void box_loop(const backend_case *bc, double v, double w[LOOP_N])
{
    long n[LOOP_STAGES];
    double vel[6][LOOP_STAGES][3];
    memset(vel, 0, sizeof vel);
    n[0] = lround(0.21 * R1 / (v * DT));
    for (int k = 0; k < 6; k++)
        vel[k][0][k / 2] = (k % 2 ? -v : v); /* inwards */
    for (int q = 1; q < LOOP_STAGES; q++) {
        int leg = (q - 1) % 4; /* 0: x in, 1: y in, 2: x out, 3: y out */
        n[q] = lround(0.01 * R1 / (v * DT));
        for (int k = 0; k < 4; k++)
            if (k / 2 == leg % 2)
                vel[k][q][k / 2] = (k % 2 ? -v : v) * (leg < 2 ? 1 : -1);
    }
    planes_loop(bc, vel, n, w);
}

/* The translation loops of tools/peer_mdr/energy_loop.py at speed v: the planes close in to unequal depths (+x, -x,
 * +y, -y, +z, -z: 0.25, 0.17, 0.22, 0.20, 0.23, 0.19 R) in 1250 steps, then the sphere moves round squares of side
 * 0.01 R in (x, y) relative to them (all six planes move the other way): forward +x, +y, -x, -y; reverse +y, +x, -y,
 * -x. */
static void translate_loop(const backend_case *bc, double v, int reverse, double w[LOOP_N])
{
    static const double depth[6] = {0.17, 0.25, 0.20, 0.22, 0.19, 0.23}; /* -x, +x, -y, +y, -z, +z [R] */
    long n[LOOP_STAGES];
    double vel[6][LOOP_STAGES][3];
    memset(vel, 0, sizeof vel);
    n[0] = 1250;
    for (int k = 0; k < 6; k++)
        vel[k][0][k / 2] = (k % 2 ? -1 : 1) * depth[k] * R1 / (1250 * DT);
    for (int q = 1; q < LOOP_STAGES; q++) {
        int leg = (q - 1) % 4, ax = (leg % 2) ^ (reverse != 0), sg = leg < 2 ? 1 : -1;
        n[q] = lround(0.01 * R1 / (v * DT));
        for (int k = 0; k < 6; k++)
            if (k / 2 == ax)
                vel[k][q][ax] = -sg * v; /* the sphere moves by +sg along ax relative to them */
    }
    planes_loop(bc, vel, n, w);
}

/* LAMMPS's figures for the loops (tools/peer_mdr/energy_loop.py, out/peer_mdr/energy_loop.txt; LAMMPS 22 Jul 2025
 * Update 4, the same path at 1e-7 and 5e-8 m a step): the first loop yields the x and y sides further and takes work;
 * every later loop walks the same states and gives work back, in proportion to the step: (M35)'s A_con and V_geo are
 * the last step's (M36). The run must give LAMMPS's work to 1e-6 (fp64) or 1e-2 (fp32) of the first loop's, and the
 * later loops' work must halve with the step. */
static void test_box_loop(void **state)
{
    (void)state;
    const double lmp[2][LOOP_N] = {{2.801284988e-04, -6.756004317e-06, -6.755662197e-06},
                                   {2.838432342e-04, -3.439087915e-06, -3.439001824e-06}};
    FOR_EACH_BACKEND(bc) {
        double w[2][LOOP_N];
        for (int h = 0; h < 2; h++) {
            box_loop(bc, h ? 0.05 : 0.1, w[h]);
            double tol = (bc->precision == DEM_FP64 ? 1e-6 : 1e-2) * lmp[h][0];
            printf("  loops, %s, %g m a step: work %.9e, %.9e, %.9e J (LAMMPS %.9e, %.9e, %.9e)\n", bc->name,
                   h ? 5e-8 : 1e-7, w[h][0], w[h][1], w[h][2], lmp[h][0], lmp[h][1], lmp[h][2]);
            for (int q = 0; q < LOOP_N; q++)
                if (!(fabs(w[h][q] - lmp[h][q]) <= tol))
                    fail_msg("loops, %s: loop %d at %g m a step put %.9e J in, LAMMPS %.9e J", bc->name, q + 1,
                             h ? 5e-8 : 1e-7, w[h][q], lmp[h][q]);
        }
        double ratio = w[0][2] / w[1][2];
        if (!(w[0][2] < 0 && ratio > 1.9 && ratio < 2.1))
            fail_msg("loops, %s: the third loop's work %g J at 1e-7 m a step, %g J at 5e-8: not a gain in proportion "
                     "to the step", bc->name, w[0][2], w[1][2]);
    }
}

/* LAMMPS's figures for the translation loops (tools/peer_mdr/energy_loop.py, the same paths at 1e-7 and 5e-8 m a
 * step). Walked in the two senses, a loop's work is the part in proportion to the step (the lag, as above) plus a part
 * that does not shrink with the step and changes sign with the sense: about +-1.28e-7 J, from 2 W(h/2) - W(h) at
 * 5e-8 and 2.5e-8 m in LAMMPS. The bulk response's stiffness is not symmetric (docs/laws/mdr.md "Energy"). The run
 * must give LAMMPS's work to 1e-6 (fp64) or 1e-2 (fp32) of the first loop's, and the third loops' limits
 * 2 W(5e-8) - W(1e-7) must have opposite signs (the forward sense takes work, the reverse gives it) and sizes within
 * 10 % of each other (measured: 1.281e-7 and -1.274e-7 J in fp64, 1.279e-7 and -1.265e-7 J in fp32). */
static void test_translate_loop(void **state)
{
    (void)state;
    const double lmp[2][2][LOOP_N] = {{{1.846887762e-04, 2.992454504e-07, 2.992396703e-07},
                                       {1.846775000e-04, 2.136716388e-07, 2.136668219e-07}},
                                      {{1.790639319e-04, 4.401622444e-08, 4.403796414e-08},
                                       {1.790462677e-04, -4.168102197e-08, -4.167220607e-08}}};
    FOR_EACH_BACKEND(bc) {
        double w[2][2][LOOP_N], lim[2];
        for (int r = 0; r < 2; r++) {
            for (int h = 0; h < 2; h++) {
                translate_loop(bc, h ? 0.05 : 0.1, r, w[r][h]);
                double tol = (bc->precision == DEM_FP64 ? 1e-6 : 1e-2) * lmp[r][h][0];
                printf("  translation loops, %s, %s, %g m a step: work %.9e, %.9e, %.9e J (LAMMPS %.9e, %.9e, "
                       "%.9e)\n", bc->name, r ? "reverse" : "forward", h ? 5e-8 : 1e-7, w[r][h][0], w[r][h][1],
                       w[r][h][2], lmp[r][h][0], lmp[r][h][1], lmp[r][h][2]);
                for (int q = 0; q < LOOP_N; q++)
                    if (!(fabs(w[r][h][q] - lmp[r][h][q]) <= tol))
                        fail_msg("translation loops, %s, %s: loop %d at %g m a step put %.9e J in, LAMMPS %.9e J",
                                 bc->name, r ? "reverse" : "forward", q + 1, h ? 5e-8 : 1e-7, w[r][h][q],
                                 lmp[r][h][q]);
            }
            lim[r] = 2 * w[r][1][2] - w[r][0][2];
        }
        printf("  translation loops, %s: third loop's work without the part in proportion to the step %.4e J "
               "forward, %.4e J reverse\n", bc->name, lim[0], lim[1]);
        if (!(lim[0] > 0 && lim[1] < 0 && fabs(lim[0] + lim[1]) < 0.1 * lim[0]))
            fail_msg("translation loops, %s: limits %g J forward, %g J reverse: not the same work of opposite signs",
                     bc->name, lim[0], lim[1]);
    }
}

/* The cap of (M34) (docs/laws/mdr.md "Range"): a fixed sphere between two planes closing in along z at 0.1 m/s each,
 * with psi_b = 0 (no bulk response while psi >= 0: the radius alone keeps the volume) and no adhesion. Its volume
 * needs an apparent radius of 1.5 R_o once the gap is about 0.6 R_o (caps of depth 1.2 R_o on R = 1.5 R_o hold
 * 4/3 pi R_o^3): the radius must meet the cap before the planes have travelled 0.85 R_o each; dem_mdr_capped must say
 * so at the step whose start first held the radius (unchanged from the step before, within 0.1 % below 1.5 R_o) and
 * not before; and in the 200 steps after it the radius must not pass 1.5 R_o by more than its last growth step. The
 * same step on every backend of a precision. */
static void test_cap(void **state)
{
    (void)state;
    double v = 0.1;
    long nmax = lround(0.85 * R1 / (v * DT)), at_of[BACKEND_CASES];
    int k_case = 0;
    FOR_EACH_BACKEND(bc) {
        dem_sim *s = dem_create();
        dem_material m = mcc(0.0), steel = {7800, INFINITY, 0.3, 1.0, 0.0};
        m.bulk_fraction = 0.0;
        int mat = dem_add_material(s, &m), wmat = dem_add_material(s, &steel);
        dem_add_particle(s, (double[3]){0, 0, 0}, (double[3]){0, 0, 0}, R1, mat);
        dem_set_particle_flags(s, 0, DEM_PARTICLE_FIXED);
        for (int k = 0; k < 2; k++) { /* -z, +z: touching, normals inwards, closing in */
            dem_wall w = {0};
            int sg = k ? 1 : -1;
            w.kind = DEM_WALL_PLANE, w.material = wmat;
            w.point[2] = sg * R1, w.normal[2] = -sg;
            dem_stage st = {0};
            st.duration = 1.0, st.velocity[2] = -sg * v;
            w.nstages = 1;
            int id = dem_add_wall(s, &w);
            if (id < 0 || dem_set_wall_motion(s, id, 1, &st))
                fail_msg("%s", dem_error(s));
        }
        start_mdr(s, bc, DEM_EFFECT_WALLS);
        double r = R1, r_prev = R1, r_max = R1, grow = 0;
        long at = -1, who = -2, k;
        for (k = 1; k <= nmax && at < 0; k++) {
            step_or_fail(s, 1);
            r_prev = r;
            if (dem_get_field(s, DEM_FIELD_RADIUS, &r))
                fail_msg("%s", dem_error(s));
            grow = r > r_prev ? r - r_prev : grow; /* the last step's growth that was not held */
            at = dem_mdr_capped(s, &who);
        }
        for (long q = 0; at >= 0 && q < 200; q++) { /* held there */
            step_or_fail(s, 1);
            double rq;
            if (dem_get_field(s, DEM_FIELD_RADIUS, &rq))
                fail_msg("%s", dem_error(s));
            r_max = fmax(r_max, rq);
        }
        printf("  cap, %s: met at step %ld (planes in by %.4g R_o each), radius then %.9g R_o (last growth %.3g R_o), "
               "largest in the 200 steps after %.9g R_o\n", bc->name, at, (double)at * v * DT / R1, r / R1, grow / R1,
               r_max / R1);
        if (at < 0)
            fail_msg("cap, %s: no radius met the cap in %ld steps (radius %.9g R_o)", bc->name, nmax, r / R1);
        if (at != k - 1 || who != 0)
            fail_msg("cap, %s: dem_mdr_capped says step %ld, particle %ld; the step taken was %ld, particle 0", bc->name,
                     at, who, k - 1);
        if (!(r == r_prev && r < 1.5 * R1 && r >= 1.499 * R1))
            fail_msg("cap, %s: at step %ld the radius is %.17g R_o (the step before %.17g R_o): not held at the cap",
                     bc->name, at, r / R1, r_prev / R1);
        if (!(r_max <= 1.5 * R1 + grow))
            fail_msg("cap, %s: the radius grew on to %.17g R_o past the cap", bc->name, r_max / R1);
        at_of[k_case++] = at;
        dem_destroy(s);
    }
    for (int q = 1; q < k_case; q++)
        for (int p = 0; p < q; p++) /* each case against every earlier one of its precision */
            if (at_of[q] != at_of[p] && backend_cases[q].precision == backend_cases[p].precision)
                fail_msg("cap: %s met it at step %ld, %s at %ld", backend_cases[q].name, at_of[q],
                         backend_cases[p].name, at_of[p]);
}

/* Two spheres of MCC of surface energy gamma and yield stress y (bond strength sigb, friction mu), 0.5 mm and r2,
 * touching at the origin, on held velocities v/2 towards each other (no damping: the effects leave it out), started
 * on bc's backend and precision */
static dem_sim *pressed_pair_r(const backend_case *bc, double gamma, double y, double v, double sigb, double mu,
                               unsigned extra, double r2)
{
    dem_sim *s = dem_create();
    dem_material m = mcc(gamma);
    m.yield_stress = y, m.bond_strength = sigb, m.friction = mu;
    int mat = dem_add_material(s, &m);
    dem_add_particle(s, (double[3]){-R1, 0, 0}, (double[3]){0.5 * v, 0, 0}, R1, mat);
    dem_add_particle(s, (double[3]){r2, 0, 0}, (double[3]){-0.5 * v, 0, 0}, r2, mat);
    dem_set_particle_flags(s, 0, DEM_PARTICLE_HOLD_V);
    dem_set_particle_flags(s, 1, DEM_PARTICLE_HOLD_V);
    dem_set_domain(s, (double[3]){-8 * R1, -8 * R1, -8 * R1}, (double[3]){8 * R1, 8 * R1, 8 * R1});
    if (dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_MDR | DEM_EFFECT_CONSTRAINTS | extra) || dem_set_dt(s, DT))
        fail_msg("%s", dem_error(s));
    dem_config c = cfg_of(bc->backend, bc->precision);
    c.force_dt = 1;
    start_or_fail(s, &c);
    return s;
}
static dem_sim *pressed_pair(const backend_case *bc, double gamma, double y, double v)
{
    return pressed_pair_r(bc, gamma, y, v, 0.0, 0.0, 0, R1);
}
static dem_sim *pressed_pair_fx(const backend_case *bc, double gamma, double y, double v, double sigb, double mu,
                                unsigned extra)
{
    return pressed_pair_r(bc, gamma, y, v, sigb, mu, extra, R1);
}

/* The elastic energy (laws/mdr.h, mdr_core.h mdr_side_energy) against the work of the run's own force, by the
 * trapezoid rule over its steps: two spheres of 0.5 mm on held velocities, no damping, no adhesion. Loading a material
 * that does not yield (Y = 100 GPa): the energy at every step is the work done so far. Loading MCC past yield, then
 * unloading: the energy at each unloading step is the work the contact gives back from there to where its force
 * ends, and far less than the work put in (the rest went into the dent). Each step's energy from the device's sampled
 * row (contact_pairs) and from the host (dem_energy, from the stored rows) alike. */
static void energy_path(const backend_case *bc, double y, long load, long unload, double *worst_rel, double *kept)
{
    double v = 0.1;
    dem_sim *s = pressed_pair(bc, 0.0, y, v);
    long n = load + unload;
    double *u = calloc((size_t)n + 1, sizeof(double)), *f = calloc((size_t)n + 1, sizeof(double));
    double *e = calloc((size_t)n + 1, sizeof(double));
    assert_true(u && f && e);
    unsigned char want = 1;
    double hd = 0, emax = 0;
    long hk = 0;
    for (long k = 1; k <= n; k++) {
        if (k == load + 1)
            set_speed(s, v, -v);
        dem_sample row;
        dem_energy_t host;
        double x[6], fo[6];
        if (dem_step_sampled(s, 1, &want, &row) || dem_energy(s, &host) || dem_get_field(s, DEM_FIELD_X, x) ||
            dem_get_field(s, DEM_FIELD_FORCE, fo))
            fail_msg("%s", dem_error(s));
        u[k] = 2 * R1 - (x[3] - x[0]), f[k] = -fo[0], e[k] = row.energy.elastic;
        if (k == load && unload > 0) { /* the stress output: -(R - delta/2) F / V along x, from the contact's force */
            double st6[12], rr[2]; /* the apparent radii (DEM_FIELD_RADIUS) give the overlap and the lever */
            if (dem_get_field(s, DEM_FIELD_STRESS, st6) || dem_get_field(s, DEM_FIELD_RADIUS, rr))
                fail_msg("%s", dem_error(s));
            double delta = rr[0] + rr[1] - (x[3] - x[0]);
            double want = -(rr[0] - 0.5 * delta) * f[k] / (4.0 / 3.0 * M_PI * R1 * R1 * R1);
            printf("  stress, %s: sigma_xx %.9g Pa, from the force %.9g Pa\n", bc->name, st6[0], want);
            if (!(fabs(st6[0] - want) <= (bc->precision == DEM_FP64 ? 1e-12 : 1e-5) * fabs(want)) || !(want < 0))
                fail_msg("%s: the stress output %.17g Pa, the contact's -(R - delta/2) F / V %.17g Pa", bc->name, st6[0],
                         want);
        }
        if (fabs(host.elastic - e[k]) > hd)
            hd = fabs(host.elastic - e[k]), hk = k;
        emax = fmax(emax, e[k]);
    }
    /* the host's energy (in double from the stored state) and the device row's (the run's precision) */
    if (!(hd <= (bc->precision == DEM_FP64 ? 1e-13 : 1e-5) * emax))
        fail_msg("%s: step %ld, the host's energy and the device row's differ by %g J (largest energy %g J)", bc->name,
                 hk, hd, emax);
    /* the work from step a to step b, trapezoids */
    double worst = 0;
    if (unload == 0) {
        double w = 0;
        for (long k = 1; k <= n; k++) {
            w += 0.5 * (f[k] + f[k - 1]) * (u[k] - u[k - 1]);
            if (k > 50)
                worst = fmax(worst, fabs(e[k] - w) / e[n]);
        }
        *kept = w;
    } else {
        long end = load; /* the last unloading step still carrying a force */
        while (end < n && f[end + 1] > 0)
            end++;
        assert_true(end > load + 10 && end < n);
        /* E(a) - E(end) against the work between them, from the second step of the unloading on: the first starts with
         * the radius the last loading step grew (M34), which changes the curve once */
        for (long a = load + 2; a < end - 10; a += 10) {
            double w = 0;
            for (long k = a + 1; k <= end; k++)
                w += 0.5 * (f[k] + f[k - 1]) * (u[k - 1] - u[k]);
            worst = fmax(worst, fabs(e[a] - e[end] - w) / e[load]);
        }
        /* and what is left at the last step with a force is what its force gives along the curve's last steps:
         * F ~ (delta - delta_p)^(3/2) near its end, so E ~ 2/5 F (delta - delta_p) there, delta - delta_p from the
         * last two forces */
        double q = pow(f[end - 1] / f[end], 2.0 / 3.0), dp = (u[end] * q - u[end - 1]) / (q - 1);
        worst = fmax(worst, fabs(e[end] - 0.4 * f[end] * (u[end] - dp)) / e[load]);
        double put = 0;
        for (long k = 1; k <= load; k++)
            put += 0.5 * (f[k] + f[k - 1]) * (u[k] - u[k - 1]);
        *kept = e[load] / put;
    }
    *worst_rel = worst;
    free(u), free(f), free(e);
    dem_destroy(s);
}

/* The adhesive springs' energy (mdr_side_energy, M21): a pair that does not yield (Y = 100 GPa), of surface energy
 * 120 J/m^2, pressed 10 um (5 um per side) and pulled back. The springs are held at a ~ 35 um where the depth is
 * g ~ 2.45 um, and may stretch l(a) ~ 2.1 um (M23): more than the 2/3 g at which the force turns tensile, less than g,
 * so the held phase (M24) goes into tension and ends with the radius receding (M25) while the pair still overlaps.
 * While each side's springs stay at the radius they held (a_adh unchanged from step to step; before that the
 * compressive unloading, M22) the force is conservative, and the energy at each step is the energy at the turn less
 * the work given back since; the first step whose radius recedes ends the comparison (the springs let go there set
 * energy free). The host's energy (dem_energy, from the stored rows) against the device row's at every step.
 * Returns the largest |E - (E_turn - W)| over E_turn; *pull the least force reached within the compared steps. */
static double energy_adhesive(const backend_case *bc, long *held, double *pull)
{
    double v = 0.1;
    dem_sim *s = pressed_pair(bc, 120.0, 1e11, v);
    enum { LOAD = 100, UNLOAD = 200 };
    double u[LOAD + UNLOAD + 1] = {0}, f[LOAD + UNLOAD + 1] = {0}, e[LOAD + UNLOAD + 1] = {0}, adh[2] = {-1, -1};
    unsigned char want = 1;
    long end = -1;
    double emax = 0;
    for (long k = 1; k <= LOAD + UNLOAD && end < 0; k++) {
        if (k == LOAD + 1)
            set_speed(s, v, -v);
        dem_sample row;
        dem_energy_t host;
        double x[6], fo[6];
        dem_state st;
        if (dem_step_sampled(s, 1, &want, &row) || dem_get_field(s, DEM_FIELD_X, x) ||
            dem_get_field(s, DEM_FIELD_FORCE, fo) || dem_state_get(s, &st) || dem_energy(s, &host))
            fail_msg("%s", dem_error(s));
        u[k] = 2 * R1 - (x[3] - x[0]), f[k] = -fo[0], e[k] = row.energy.elastic;
        emax = fmax(emax, e[k]);
        if (!(fabs(host.elastic - e[k]) <= (bc->precision == DEM_FP64 ? 1e-13 : 1e-5) * emax))
            fail_msg("%s: step %ld, the host's energy %.17g J, the device row's %.17g J", bc->name, k, host.elastic,
                     e[k]);
        if (k > LOAD && st.npairs == 0)
            fail_msg("%s: step %ld, the pair came apart before a radius receded", bc->name, k);
        assert_true(st.npairs <= 1 && (!st.npairs || (st.has_law == 25 && st.pair_law)));
        int held_now = 1; /* both sides' a_adh (row 2 + 8 and 13 + 8) as at the last step */
        for (int q = 0; q < 2; q++) {
            int at = q ? 21 : 10;
            double a = !st.npairs ? -1 : st.real_size == 8 ? ((double *)st.pair_law)[at] : ((float *)st.pair_law)[at];
            held_now &= a == adh[q];
            adh[q] = a;
        }
        dem_state_free(&st);
        if (k > LOAD + 1 && held_now)
            *held += 1;
        else if (k > LOAD + 1 && *held > 0)
            end = k - 1; /* a radius moved after having been held: receding (M25) */
    }
    assert_true(end > LOAD);
    double w = 0, worst = 0;
    *pull = 0;
    for (long k = LOAD + 1; k <= end; k++) {
        w += 0.5 * (f[k] + f[k - 1]) * (u[k - 1] - u[k]);
        worst = fmax(worst, fabs(e[k] - (e[LOAD] - w)) / e[LOAD]);
        *pull = fmin(*pull, f[k]);
        if (!(e[k] >= 0))
            fail_msg("%s: step %ld, a negative elastic energy %g J", bc->name, k, e[k]);
    }
    dem_destroy(s);
    return worst;
}

static void test_energy(void **state)
{
    (void)state;
    FOR_EACH_BACKEND(bc) {
        double worst, kept;
        energy_path(bc, 1e11, 900, 0, &worst, &kept);
        printf("  energy, %s, elastic loading: work %.6g J, largest |E - W| %.3g of it\n", bc->name, kept, worst);
        double tol = bc->precision == DEM_FP64 ? 1e-5 : 1e-3;
        if (!(worst <= tol))
            fail_msg("%s: an elastic contact's energy departs from the work put in by %g of it", bc->name, worst);
        energy_path(bc, Y_MCC, 900, 600, &worst, &kept);
        printf("  energy, %s, unloading after yield: largest |E - W_back| %.3g of E at the turn, which is %.3g of "
               "the work put in\n", bc->name, worst, kept);
        if (!(worst <= 10 * tol) || !(kept > 0.01 && kept < 0.5))
            fail_msg("%s: a yielded contact's energy departs from the work it gives back by %g (it keeps %g of the "
                     "work put in)", bc->name, worst, kept);
        long held = 0;
        double pull;
        worst = energy_adhesive(bc, &held, &pull);
        printf("  energy, %s, adhesive springs held for %ld steps, down to %.4g N: largest |E - (E_turn - W)| %.3g of "
               "E_turn\n", bc->name, held, pull, worst);
        if (!(worst <= 3 * tol) || held < 5 || !(pull < 0))
            fail_msg("%s: the held springs' energy departs from the work given back by %g of it (%ld steps held, least "
                     "force %g N)", bc->name, worst, held, pull);
    }
}


/* ---- bonds (mdr_core.h mdr_side_bond; docs/laws/mdr.md "Bonds") ----
 * Closed forms from the law's equations as the paper prints them, not from the code: at the turn of a loading on the
 * plastic line a side's indenter stands at half its height (M17), where (M7) gives F = pi p_y a_max^2, p_y of (M11)
 * Y (7/4 exp(-4.4 delta_m/R) + 1). The apparent radius grows once more after the turn (the first unloading step
 * takes the turn's sums, M34), which (M14) turns into a_max^2 + 2 delta_m dR. So the bond holds
 * F_b = sigma_b pi a_max^2 = sigma_b (F_turn / p_y + 2 pi delta_m dR), and pulled past the dent it is a flat circular
 * contact of radius a_max: 2 E* a_max on the indenter's depth, which (M17) maps to the overlap by 1/(1 + 2 dR_c/A),
 * dR_c the compliance of (M16) and A = 4 p_y a_max / E* (M14); a pair of equal sides, each taking half the approach,
 * pulls at E* a_max / (1 + 2 dR_c/A). */
#define SIGB 5e7

/* p_y of (M11) typed in: a side's largest MDR overlap dm on apparent radius r */
static double py_of(double dm, double r) { return Y_MCC * (1.75 * exp(-4.4 * dm / r) + 1); }

/* The pair's tension slope of the closed forms above: a side of largest MDR overlap dm and a_max^2 = am2 on apparent
 * radius r, (M14) and (M16) typed in */
static double bond_slope(double dm, double am2, double r)
{
    double es = E_MCC / (1 - NU_MCC * NU_MCC), g = E_MCC / (2 * (1 + NU_MCC)), py = py_of(dm, r), am = sqrt(am2);
    double a = 4 * py * am / es, zr = r - (dm - a / 2), q = sqrt(am2 + zr * zr);
    double dr = M_PI * py * am2 / (2 * M_PI * am2 * g * q) * (2 * am2 * (NU_MCC - 1) + (1 - 2 * NU_MCC) * zr * (q - zr));
    return es * am / (1 + 2 * dr / a);
}

typedef struct {
    double peak, pull, expect, slope, slope_expect, e_rel, e_last_rel, after_least;
    long tension, zero_after;
} bond_pull;

/* The pair's normal force (positive repulsive), its approach (radii as created), its apparent approach and the
 * first sphere's apparent radius */
static void pair_now(dem_sim *s, double *u, double *f, double *u_app, double *r_app)
{
    double x[6], fo[6], rr[2];
    if (dem_get_field(s, DEM_FIELD_X, x) || dem_get_field(s, DEM_FIELD_FORCE, fo) ||
        dem_get_field(s, DEM_FIELD_RADIUS, rr))
        fail_msg("%s", dem_error(s));
    *u = 2 * R1 - (x[3] - x[0]), *f = -fo[0], *u_app = rr[0] + rr[1] - (x[3] - x[0]);
    if (r_app)
        *r_app = rr[0];
}

/* Loads the held pair (moving at speed_now, m/s of approach) at 0.1 m/s until its approach passes u_to, then pulls
 * at 0.05 m/s until the bond breaks and 10 steps more: the turn's force, the largest tension, the closed forms' F_b
 * and slope, the energy against the work given back (host and device rows alike), what the force is after the
 * break. forces[] gets every step's force, *k their count. */
static bond_pull load_and_pull(const backend_case *bc, dem_sim *s, double speed_now, double u_to, double *forces,
                               long *k)
{
    bond_pull o = {0};
    enum { MAXS = 4000 };
    static double u[MAXS], f[MAXS], e[MAXS];
    long n = 0, turn = -1, brk = -1;
    double fu, uu, ua, ra, peak_uapp = 0, r_turn = 0;
    double emax = 1e-5; /* the scale of the energies compared (their turns: ~6e-4 J) */
    unsigned char want = 1;
    set_speed(s, speed_now, 0.1);
    for (;;) {
        dem_sample row;
        dem_energy_t host;
        if (dem_step_sampled(s, 1, &want, &row) || dem_energy(s, &host))
            fail_msg("%s", dem_error(s));
        pair_now(s, &uu, &fu, &ua, &ra);
        assert_true(n < MAXS);
        u[n] = uu, f[n] = fu, e[n] = row.energy.elastic;
        forces[(*k)++] = fu;
        emax = fmax(emax, e[n]);
        if (!(fabs(host.elastic - e[n]) <= (bc->precision == DEM_FP64 ? 1e-13 : 1e-5) * emax))
            fail_msg("%s: the host's energy %.17g J, the device row's %.17g J", bc->name, host.elastic, e[n]);
        n++;
        if (turn < 0 && uu >= u_to) {
            turn = n - 1, peak_uapp = ua, r_turn = ra;
            set_speed(s, 0.1, -0.05);
        } else if (turn >= 0 && brk < 0 && f[n - 2] < 0 && fu > 0.5 * f[n - 2]) {
            brk = n - 1; /* most of the tension gone in one step: the bridge let go */
        } else if (brk >= 0 && n - 1 >= brk + 10) {
            break;
        }
    }
    /* the side's largest MDR overlap: half the apparent approach at the turn (equal spheres, psi > psi_b: no bulk
     * part); the radius of the break, which the first unloading step grew once and which no later one changes */
    double dm = 0.5 * peak_uapp, r_end = ra;
    double am2 = f[turn] / (M_PI * py_of(dm, r_turn)) + 2 * dm * (r_end - r_turn);
    o.peak = f[turn];
    o.expect = SIGB * M_PI * am2;
    o.slope_expect = bond_slope(dm, am2, r_end);
    long first = turn; /* the first tensile step */
    while (!(f[first] < 0))
        first++;
    o.tension = brk - first;
    o.pull = 0;
    for (long q = first; q < brk; q++)
        o.pull = fmin(o.pull, f[q]);
    o.slope = (f[brk - 2] - f[brk - 1]) / (u[brk - 2] - u[brk - 1]);
    /* the energy: from each unloading step to the last one before the break, the work given back; and at that last
     * step a linear spring's F^2 / (2 k) (without adhesion) */
    long last = brk - 1;
    for (long a = turn + 2; a < last; a++) {
        double w = 0;
        for (long q = a + 1; q <= last; q++)
            w += 0.5 * (f[q] + f[q - 1]) * (u[q - 1] - u[q]);
        o.e_rel = fmax(o.e_rel, fabs(e[a] - e[last] - w) / e[turn]);
    }
    o.e_last_rel = fabs(e[last] - 0.5 * f[last] * f[last] / o.slope) / e[last];
    o.zero_after = 0;
    for (long q = brk; q < n && f[q] == 0; q++)
        o.zero_after++;
    o.after_least = 0;
    for (long q = brk; q < n; q++)
        o.after_least = fmin(o.after_least, f[q]);
    if (!(ua > 0))
        fail_msg("%s: the pair came apart (apparent approach %g m) within 10 steps of the break", bc->name, ua);
    return o;
}

/* gamma: the surface energy of the run (0: the bond alone, whose pull is then F_b exactly up to a step) */
static void check_pull(const backend_case *bc, const bond_pull *o, double gamma, const char *what)
{
    double tol = bc->precision == DEM_FP64 ? 1e-9 : 1e-4;
    double step_f = o->slope * 0.05 * DT; /* one step's change of tension */
    printf("  bond, %s, %s: turn %.6g N, tension held %ld steps down to %.6g N; closed form F_b %.6g N; slope %.7g "
           "N/m (closed form %.7g); energy %.2g, F^2/2k %.2g; after the break %ld steps at 0, least %.3g N\n",
           bc->name, what, o->peak, o->tension, o->pull, o->expect, o->slope, o->slope_expect, o->e_rel,
           o->e_last_rel, o->zero_after, o->after_least);
    if (gamma == 0 && (!(-o->pull <= o->expect * (1 + tol)) || !(-o->pull >= o->expect - 1.5 * step_f)))
        fail_msg("%s, %s: the largest tension %.17g N, the bond's F_b %.17g N (one step %g N)", bc->name, what,
                 -o->pull, o->expect, step_f);
    if (gamma > 0 && !(-o->pull >= o->expect - 1.5 * step_f)) /* the bridge and the adhesive springs together */
        fail_msg("%s, %s: the largest tension %.17g N, less than the bond's F_b %.17g N", bc->name, what, -o->pull,
                 o->expect);
    double stol = bc->precision == DEM_FP64 ? 1e-6 : 2e-2;
    if (!(o->tension > 20) || !(fabs(o->slope - o->slope_expect) <= stol * o->slope_expect))
        fail_msg("%s, %s: %ld steps in tension, slope %.9g N/m, the closed form's %.9g", bc->name, what, o->tension,
                 o->slope, o->slope_expect);
    /* with adhesion the springs' radius recedes (M25) on the way, which dissipates (6e-5 of E_turn here) */
    double etol = gamma > 0 ? 3e-4 : bc->precision == DEM_FP64 ? 1e-5 : 1e-4;
    if (!(o->e_rel <= etol) || (gamma == 0 && !(o->e_last_rel <= (bc->precision == DEM_FP64 ? 1e-6 : 1e-3))))
        fail_msg("%s, %s: the energy departs from the work given back by %g of E_turn; in tension from F^2/2k by %g",
                 bc->name, what, o->e_rel, o->e_last_rel);
    if (gamma == 0 && o->zero_after < 10)
        fail_msg("%s, %s: after the break the force was 0 for %ld steps only (no adhesion: none is left)", bc->name,
                 what, o->zero_after);
    if (gamma > 0 && !(o->after_least > -0.05 * o->expect))
        fail_msg("%s, %s: after the break a tension of %g N is left (the adhesive springs alone hold far less)",
                 bc->name, what, o->after_least);
}

/* Steps the held pair at speed (m/s of approach; from speed_now) for at most nmax steps, until its approach passes
 * u_to (speed > 0) or it comes apart (speed < 0): the least force met */
static double drive(dem_sim *s, double speed_now, double speed, double u_to, long nmax, double *forces, long *k)
{
    double uu, fu, ua, least = 0;
    set_speed(s, speed_now, speed);
    for (long q = 0; q < nmax; q++) {
        step_or_fail(s, 1);
        pair_now(s, &uu, &fu, &ua, NULL);
        if (forces)
            forces[(*k)++] = fu;
        least = fmin(least, fu);
        if (speed > 0 ? uu >= u_to : !(ua > 0))
            break;
    }
    return least;
}

/* A pair of Zunker's MCC with bonds (sigma_b 50 MPa, no damping), held velocities: pressed to 80 um (it yields at
 * about 42 um) and pulled until the bond breaks; pressed again to 90 um, past its first largest approach (it yields
 * further: a new bond over the larger plastic area), and pulled again; pressed a third time only to 85 um, below its
 * largest (no new yield: no bond) and pulled apart without a tension. Without adhesion, and with LAMMPS's 2 J/m^2
 * beside the bridge. Every step's force of OpenCL equal to the reference's. Without bonds the same pair carries no
 * tension. */
static void test_bond(void **state)
{
    (void)state;
    static double fref[2][2][12000], fnow[12000];
    long nref[2][2] = {{0, 0}, {0, 0}};
    FOR_EACH_BACKEND(bc) {
        int pi = bc->precision == DEM_FP64 ? 0 : 1;
        for (int gi = 0; gi < 2; gi++) {
            double gamma = gi ? 2.0 : 0.0;
            long k = 0;
            dem_sim *s = pressed_pair_fx(bc, gamma, Y_MCC, -0.1, SIGB, 0.0, 0);
            bond_pull a = load_and_pull(bc, s, -0.1, 80e-6, fnow, &k);
            check_pull(bc, &a, gamma, gamma > 0 ? "first pull, 2 J/m^2" : "first pull");
            bond_pull b = load_and_pull(bc, s, -0.05, 90e-6, fnow, &k);
            check_pull(bc, &b, gamma, gamma > 0 ? "pressed further, pulled again, 2 J/m^2" : "pressed further, pulled again");
            if (!(b.expect > a.expect))
                fail_msg("%s: the second bond (%g N) is not stronger than the first (%g N)", bc->name, b.expect,
                         a.expect);
            drive(s, -0.05, 0.1, 85e-6, 3000, fnow, &k);
            double least = drive(s, 0.1, -0.05, 0, 3000, fnow, &k);
            printf("  bond, %s%s: pressed again below its largest approach and pulled apart: least force %.3g N\n",
                   bc->name, gamma > 0 ? ", 2 J/m^2" : "", least);
            if (!(least > (gamma > 0 ? -0.05 * b.expect : -1e-300)))
                fail_msg("%s: reloaded below its largest overlap, a broken bond pulled with %g N", bc->name, least);
            dem_destroy(s);
            if (bc->backend == DEM_BACKEND_REFERENCE) {
                memcpy(fref[pi][gi], fnow, (size_t)k * sizeof(double));
                nref[pi][gi] = k;
            } else if (k != nref[pi][gi] || memcmp(fref[pi][gi], fnow, (size_t)k * sizeof(double)))
                fail_msg("%s: the forces differ from the reference's (%ld and %ld steps)", bc->name, k, nref[pi][gi]);
        }
        /* no bonds: the same loading and pull never pulls */
        dem_sim *s = pressed_pair_fx(bc, 0.0, Y_MCC, -0.1, 0.0, 0.0, 0);
        drive(s, -0.1, 0.1, 80e-6, 3000, NULL, NULL);
        double least = drive(s, 0.1, -0.05, 0, 3000, NULL, NULL);
        if (least < 0)
            fail_msg("%s: a pair without bonds pulled with %g N", bc->name, least);
        dem_destroy(s);
    }
}

/* Unequal spheres (0.5 and 0.3 mm) with bonds, no adhesion: their sides' bonds differ (each F_b = sigma_b pi a_max^2 on
 * its own side), but the bridge breaks as a whole: once the tension falls at the break, the pair pulls no more (a side
 * left bonded would go on pulling with half its tension, (M4)) */
static void test_bond_unequal(void **state)
{
    (void)state;
    FOR_EACH_BACKEND(bc) {
        dem_sim *s = pressed_pair_r(bc, 0.0, Y_MCC, -0.1, SIGB, 0.0, 0, 3e-4);
        double uu, fu, ua, least = 0, prev = 0;
        set_speed(s, -0.1, 0.1);
        do {
            step_or_fail(s, 1);
            pair_now(s, &uu, &fu, &ua, NULL);
        } while (ua < 70e-6);
        set_speed(s, 0.1, -0.05);
        long brk = -1, after = 0, q;
        double after_least = 0;
        for (q = 0; q < 4000 && ua > 0; q++) {
            step_or_fail(s, 1);
            pair_now(s, &uu, &fu, &ua, NULL);
            least = fmin(least, fu);
            if (brk < 0 && prev < 0 && fu > prev) /* the first step whose tension falls: a bond broke */
                brk = q;
            else if (brk >= 0)
                after++, after_least = fmin(after_least, fu);
            prev = fu;
        }
        printf("  bond, %s, 0.5/0.3 mm: largest tension %.6g N, broke at step %ld of the pull; %ld steps after it, "
               "least force %g N, apart at step %ld\n", bc->name, -least, brk, after, after_least, q);
        if (brk < 0 || !(least < -1) || after < 10 || !(after_least == 0))
            fail_msg("%s: the unequal pair's bridge: largest tension %g N, break at %ld, then %g N over %ld steps",
                     bc->name, -least, brk, after_least, after);
        dem_destroy(s);
    }
}

/* Sets the two spheres' held velocities */
static void set_velocities(dem_sim *s, const double v[6])
{
    dem_state st;
    if (dem_state_get(s, &st))
        fail_msg("%s", dem_error(s));
    dem_state_array *va = dem_state_find(&st, "v");
    assert_non_null(va);
    for (int c = 0; c < 6; c++) {
        if (st.real_size == 8)
            ((double *)va->data)[c] = v[c];
        else
            ((float *)va->data)[c] = (float)v[c];
    }
    if (dem_state_set(s, &st))
        fail_msg("%s", dem_error(s));
    dem_state_free(&st);
}

/* A bonded pair sheared: the tangential force reaches mu (f_n + F_b) (friction 0.5) and the bond breaks, so the pull
 * that follows carries no tension. (The ratio is read from the positions after the step, whose line of centres has
 * turned by ~1e-4 rad from the one the force saw: to 1e-4, against F_b / f_n ~ 0.12 without the bond's term.)
 * Every step's force of OpenCL equal to the reference's. */
static void test_bond_slide(void **state)
{
    (void)state;
    static double fref[2][6000];
    long nref[2] = {0, 0};
    FOR_EACH_BACKEND(bc) {
        int pi = bc->precision == DEM_FP64 ? 0 : 1;
        static double fnow[6000];
        long k = 0;
        dem_sim *s = pressed_pair_fx(bc, 0.0, Y_MCC, -0.1, SIGB, 0.5, DEM_EFFECT_FRICTION);
        double uu, fu, ua, ra0, ra;
        drive(s, -0.1, 0.1, 80e-6, 3000, fnow, &k);
        pair_now(s, &uu, &fu, &ua, &ra0);
        double peak = fu, dm = 0.5 * ua;
        /* shear: sphere 1 moves along y at 0.1 m/s, sphere 0 still */
        set_velocities(s, (double[6]){0, 0, 0, 0, 0.1, 0});
        double ratio_max = 0, fb = 0;
        long slid = -1;
        for (long q = 0; q < 400 && slid < 0; q++) {
            double x[6], fo[6];
            step_or_fail(s, 1);
            if (dem_get_field(s, DEM_FIELD_X, x) || dem_get_field(s, DEM_FIELD_FORCE, fo))
                fail_msg("%s", dem_error(s));
            fnow[k++] = fo[0], fnow[k++] = fo[1];
            pair_now(s, &uu, &fu, &ua, &ra);
            /* the bond of the closed forms (test_bond) on this step's radius */
            fb = SIGB * M_PI * (peak / (M_PI * py_of(dm, ra0)) + 2 * dm * (ra - ra0));
            double e[3] = {x[3] - x[0], x[4] - x[1], x[5] - x[2]}, d = sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
            for (int c = 0; c < 3; c++)
                e[c] /= d;
            double fn = -(fo[0] * e[0] + fo[1] * e[1] + fo[2] * e[2]);
            double t[3] = {fo[0] + fn * e[0], fo[1] + fn * e[1], fo[2] + fn * e[2]};
            double ft = sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
            double ratio = ft / (0.5 * (fn + fb));
            ratio_max = fmax(ratio_max, ratio);
            if (ratio > 1 - (bc->precision == DEM_FP64 ? 1e-4 : 1e-3))
                slid = q;
        }
        printf("  bond, %s, sheared: |f_t| / mu (f_n + F_b) reached %.9f at step %ld (F_b %.6g N)\n", bc->name,
               ratio_max, slid, fb);
        if (slid < 0 || !(ratio_max <= 1 + (bc->precision == DEM_FP64 ? 1e-4 : 1e-3)))
            fail_msg("%s: the tangential force reached %.9g of mu (f_n + F_b), not 1", bc->name, ratio_max);
        /* stop the shear and pull apart: the bond is gone */
        set_velocities(s, (double[6]){-0.025, 0, 0, 0.025, 0, 0});
        double least = 0;
        for (long q = 0; q < 3000 && ua > 0; q++) {
            step_or_fail(s, 1);
            pair_now(s, &uu, &fu, &ua, NULL);
            fnow[k++] = fu;
            least = fmin(least, fu);
        }
        if (least < 0 || ua > 0)
            fail_msg("%s: after the bridge sheared off the pull carried %g N (apparent approach at the end %g m)",
                     bc->name, least, ua);
        dem_destroy(s);
        if (bc->backend == DEM_BACKEND_REFERENCE) {
            memcpy(fref[pi], fnow, (size_t)k * sizeof(double));
            nref[pi] = k;
        } else if (k != nref[pi] || memcmp(fref[pi], fnow, (size_t)k * sizeof(double)))
            fail_msg("%s: the forces differ from the reference's (%ld and %ld steps)", bc->name, k, nref[pi]);
    }
}

/* Fixed spheres A, B, C of 0.5 mm at t = 0 (the first force pass): B at the origin, A and C at 0.6 mm from it, the
 * angle at B 95 degrees, so that all three overlap pairwise and A-C, the farthest apart, runs through B. (M40): the
 * pair A-C carries the penalty 1/(1 + exp(-50 (alpha/pi - 1/2))) = 0.80, typed in here with the C library's acos and
 * exp, the other two none; and the force on A is A-B's alone plus (1 - p) times A-C's alone (runs of two spheres). */
static dem_sim *penalty_run(const backend_case *bc, int with_b, int with_c, double f[3], dem_state *st)
{
    double d = 6e-4, half = 95.0 / 2 * M_PI / 180;
    dem_sim *s = dem_create();
    dem_material m = mcc(0.0);
    int mat = dem_add_material(s, &m), id = 0;
    double xa[3] = {-d * sin(half), d * cos(half), 0}, xc[3] = {d * sin(half), d * cos(half), 0};
    dem_add_particle(s, xa, (double[3]){0, 0, 0}, R1, mat);
    if (with_b)
        dem_add_particle(s, (double[3]){0, 0, 0}, (double[3]){0, 0, 0}, R1, mat);
    if (with_c)
        dem_add_particle(s, xc, (double[3]){0, 0, 0}, R1, mat);
    for (id = 0; id < dem_count(s); id++)
        dem_set_particle_flags(s, id, DEM_PARTICLE_FIXED);
    start_mdr(s, bc, DEM_EFFECT_DAMPING);
    double all[9];
    if (dem_get_field(s, DEM_FIELD_FORCE, all) || dem_state_get(s, st))
        fail_msg("%s", dem_error(s));
    memcpy(f, all, sizeof(double) * 3);
    return s;
}

static double row_real(const dem_state *st, long pair, int k)
{
    size_t at = (size_t)pair * DEM_MDR_LAW_REALS + (size_t)k;
    return st->real_size == 8 ? ((double *)st->pair_law)[at] : ((float *)st->pair_law)[at];
}

static void test_penalty(void **state)
{
    (void)state;
    double alpha = 95.0 * M_PI / 180, want = 1 / (1 + exp(-50 * (acos(cos(alpha)) / M_PI - 0.5)));
    FOR_EACH_BACKEND(bc) {
        double f3[3], fab[3], fac[3];
        dem_state s3, sab, sac;
        dem_sim *a = penalty_run(bc, 1, 1, f3, &s3), *b = penalty_run(bc, 1, 0, fab, &sab),
                *c = penalty_run(bc, 0, 1, fac, &sac);
        assert_int_equal(s3.npairs, 3);
        double pen[3], tol = bc->precision == DEM_FP64 ? 1e-13 : 1e-5;
        for (long p = 0; p < 3; p++) { /* A-B, A-C, B-C in the ids' order */
            assert_true(s3.pair_i[p] == (p < 2 ? 0 : 1) && s3.pair_j[p] == (p == 0 ? 1 : 2));
            pen[p] = row_real(&s3, p, 1);
        }
        printf("  penalty, %s: A-B %.3g, A-C %.17g (closed form %.17g), B-C %.3g\n", bc->name, pen[0], pen[1], want,
               pen[2]);
        if (pen[0] != 0 || pen[2] != 0 || !(fabs(pen[1] - want) <= tol * want))
            fail_msg("%s: penalties A-B %g, A-C %.17g, B-C %g; want 0, %.17g, 0", bc->name, pen[0], pen[1], pen[2],
                     want);
        double fmag = sqrt(f3[0] * f3[0] + f3[1] * f3[1]), worst = 0;
        for (int k = 0; k < 3; k++)
            worst = fmax(worst, fabs(f3[k] - (fab[k] + (1 - want) * fac[k])));
        printf("  penalty, %s: |F_A| %.6g N, |F_A - (F_AB + (1 - p) F_AC)| %.3g of it\n", bc->name, fmag, worst / fmag);
        if (!(fmag > 0) || !(worst <= (bc->precision == DEM_FP64 ? 1e-12 : 1e-5) * fmag))
            fail_msg("%s: the force on A is not A-B's plus the weighted A-C's (%g of |F|)", bc->name, worst / fmag);
        dem_state_free(&s3), dem_state_free(&sab), dem_state_free(&sac);
        dem_destroy(a), dem_destroy(b), dem_destroy(c);
    }
}

/* A packing of adhesive plastic spheres (two sizes) falling under gravity and pressed by a lid, with friction: PoCL =
 * reference bit for bit, restored mid-run, two skins and stored anew at every rebuild (the rows of pairs and wall slots,
 * the particles' rows and the grown radii carried through all of it) */
static void test_packing(void **st)
{
    (void)st;
    packing_opts o;
    packing_defaults(&o);
    o.side = 4;
    o.effects = DEM_EFFECT_CLASSICAL | DEM_EFFECT_MDR;
    o.yield_stress = 1e5, o.surface_energy = 0.5, o.bulk_fraction = PSI_B, o.mdr_damping = 0.3;
    o.lid_speed = 0.5;
    /* without bonds, and with (docs/laws/mdr.md "Bonds": some break, by tension or by sliding) */
    for (int bonds = 0; bonds < 2; bonds++)
    FOR_EACH_BACKEND(bc) {
        o.bond_strength = bonds ? 5e4 : 0;
        dem_config c = cfg_of(bc->backend, bc->precision);
        dem_state sa;
        packing_restart_state(&o, &c, bc->name, &sa);
        long yielded = 0, grown = 0, broken = 0;
        size_t rs = (size_t)sa.real_size;
        for (long p = 0; p < sa.npairs; p++)
            for (int k = 0; k < 2; k++) { /* each side's yield flag (dem_layout.h MDR_*; 2: its bond broke) */
                size_t at = (size_t)p * DEM_MDR_LAW_REALS + 2 + 11 * (size_t)k + 6;
                double flag = rs == 8 ? ((double *)sa.pair_law)[at] : ((float *)sa.pair_law)[at];
                yielded += flag > 0, broken += flag == 2;
            }
        dem_state_array *mp = dem_state_find(&sa, "mdr_particle");
        for (int i = 0; mp && i < sa.n; i++) {
            double ro = rs == 8 ? ((double *)mp->data)[14 * i] : ((float *)mp->data)[14 * i];
            double r = rs == 8 ? ((double *)mp->data)[14 * i + 1] : ((float *)mp->data)[14 * i + 1];
            grown += r > ro;
        }
        printf("  packing, %s: %ld touching pairs, %ld sides yielded (%ld of them with their bond broken), %ld of %d "
               "radii grown\n", bc->name, sa.npairs, yielded, broken, grown, sa.n);
        assert_true(sa.has_law == DEM_MDR_LAW_REALS && sa.npairs > 10 && yielded > 10 && grown > 10 &&
                    (bonds ? broken > 0 && broken < yielded : broken == 0));
        dem_state_free(&sa);
        skins_order_and_reference_check(&o, &c, 600, bc->name);
    }
}

/* What an MDR run refuses, each with its reason: a particle material that does not yield, two particle materials
 * that differ, a wall material that yields and is not the particles', and a saved state whose MDR rows do not fit */
static void test_refused(void **state)
{
    (void)state;
    for (int k = 0; k < 4; k++) {
        dem_sim *s = dem_create();
        dem_material m = mcc(0.0), other = mcc(0.0), steel = {7800, INFINITY, 0.3, 1.0, 0.0};
        other.yield_stress = 2 * Y_MCC;
        if (k == 0)
            m.yield_stress = 0;
        int a = dem_add_material(s, &m), b = dem_add_material(s, k == 1 || k == 2 ? &other : &m);
        int w = dem_add_material(s, k == 2 ? &other : &steel);
        dem_add_particle(s, (double[3]){-R1, 0, 0}, (double[3]){0, 0, 0}, R1, a);
        dem_add_particle(s, (double[3]){R1, 0, 0}, (double[3]){0, 0, 0}, R1, k == 1 ? b : a);
        dem_wall pl = {0};
        pl.kind = DEM_WALL_PLANE, pl.normal[2] = 1, pl.point[2] = -R1, pl.material = w;
        assert_true(dem_add_wall(s, &pl) >= 0);
        dem_set_domain(s, (double[3]){-4 * R1, -4 * R1, -4 * R1}, (double[3]){4 * R1, 4 * R1, 4 * R1});
        assert_int_equal(dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_MDR | DEM_EFFECT_WALLS), 0);
        dem_set_dt(s, DT);
        dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
        c.force_dt = 1;
        int rc = dem_start(s, &c);
        static const char *const why[3] = {"needs its material 0 to yield", "materials 0 and 1 differ",
                                           "wall 0: under the mdr law a wall's material does not yield"};
        if (k < 3) {
            if (rc != DEM_ERR_ARG || !strstr(dem_error(s), why[k]))
                fail_msg("case %d: status %d, message '%s' (want '%s')", k, rc, dem_error(s), why[k]);
        } else { /* a state whose particle row has shrunk below its radius as created */
            assert_int_equal(rc, 0);
            dem_state st;
            assert_int_equal(dem_state_get(s, &st), 0);
            dem_state_array *mp = dem_state_find(&st, "mdr_particle");
            assert_non_null(mp);
            ((double *)mp->data)[1] = 0.5 * R1;
            rc = dem_state_set(s, &st);
            if (rc != DEM_ERR_ARG || !strstr(dem_error(s), "MDR row of particle 0"))
                fail_msg("a shrunk radius: status %d, message '%s'", rc, dem_error(s));
            dem_state_free(&st);
        }
        dem_destroy(s);
    }
}

int main(void)
{
    test_pocl_threads(); /* the suite's multi-thread runs of these laws (test_util.h) */
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pair_path),
        cmocka_unit_test(test_unequal_adhesive_pair),
        cmocka_unit_test(test_wall_path),
        cmocka_unit_test(test_box),
        cmocka_unit_test(test_box_loop),
        cmocka_unit_test(test_translate_loop),
        cmocka_unit_test(test_cap),
        cmocka_unit_test(test_penalty),
        cmocka_unit_test(test_energy),
        cmocka_unit_test(test_bond),
        cmocka_unit_test(test_bond_slide),
        cmocka_unit_test(test_bond_unequal),
        cmocka_unit_test(test_packing),
        cmocka_unit_test(test_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
