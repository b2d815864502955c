/* test_wall_forces.c - walls: the inside of a cylinder (a die), planes, prescribed piecewise motion, and the force
 * each wall receives. 17 beads (seed 000 section 4.3 geometry: die 12 mm wide) settle under gravity on a floor
 * inside a cylinder: at rest, the floor and cylinder together carry the beads' weight; no bead leaves the die.
 * Then a piston comes down in two stages and its position follows the stages exactly. PoCL bitwise = reference. */
#define DEM_REAL_SIZE 8
#include "contact_geometry.h" /* wall_geometry_gap in double, as host/physics/wall_overlap.c compiles it (test_gap_geometry) */
#include "test_util.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define R_DIE 0.006
#define R_BEAD 0.002
#define RHO 2500.0

/* the die scene under a contact model: 0 classical, 1 MC-stress, 2 lagged MC-strain, 3 iterated MC-strain */
static dem_sim *die_model(int model)
{
    dem_sim *s = dem_create();
    double beta = model == 1 ? 0.3 : 0, gamma = model >= 2 ? 0.5 : 0;
    int m = dem_add_material(s, &(dem_material){RHO, 1e7, 0.24, 0.5, 0.2, beta, gamma});
    int steel = dem_add_material(s, &(dem_material){7800, 2e8, 0.3, 0.5, 0.2, beta, gamma});
    if (model)
        dem_set_effects(s, DEM_EFFECT_CLASSICAL | (model == 1 ? DEM_EFFECT_MC_STRESS : DEM_EFFECT_MC_STRAIN));
    if (model == 3)
        dem_set_mc_strain(s, 10, 1e-6);
    for (int k = 0; k < 17; k++) { /* a loose column, slightly off axis */
        double a = 2.1 * k, x[3] = {0.0025 * cos(a), 0.0025 * sin(a), 0.0025 + 0.0042 * k};
        dem_add_particle(s, x, NULL, R_BEAD, m);
    }
    dem_wall cyl = {.kind = DEM_WALL_CYLINDER, .material = steel, .point = {0, 0, 0}, .normal = {0, 0, 1},
                    .radius = R_DIE};
    dem_wall floor = {.kind = DEM_WALL_PLANE, .material = steel, .point = {0, 0, 0}, .normal = {0, 0, 1}};
    dem_wall piston = {.kind = DEM_WALL_PLANE, .material = steel, .point = {0, 0, 0.08}, .normal = {0, 0, -1}};
    piston.nstages = 3;
    piston.stages[0] = (dem_stage){0.30, {0, 0, 0}};       /* wait while the beads settle */
    piston.stages[1] = (dem_stage){0.32, {0, 0, -0.2}};    /* approach to z = 16 mm */
    piston.stages[2] = (dem_stage){0.175, {0, 0, -0.02}};  /* press to 12.5 mm (column top near 13 mm) */
    dem_add_wall(s, &cyl);
    dem_add_wall(s, &floor);
    dem_add_wall(s, &piston);
    dem_set_gravity(s, (double[3]){0, 0, -9.81});
    dem_set_domain(s, (double[3]){-0.01, -0.01, -0.01}, (double[3]){0.01, 0.01, 0.09});
    dem_time_scales ts;
    dem_time_scales_get(s, 0, &ts);
    dem_set_dt(s, ts.recommended_dt);
    return s;
}
static dem_sim *die(void) { return die_model(0); }

static void test_die(void **st)
{
    (void)st;
    dem_sim *s = die(), *ref = die();
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, DEM_FP64), rc = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    start_or_fail(s, &c);
    start_or_fail(ref, &rc);
    double dt = dem_dt(s);
    long settle = lround(0.29 / dt);
    step_or_fail(s, settle);
    step_or_fail(ref, settle);
    char msg[256];
    if (state_diff(s, ref, msg, sizeof msg))
        fail_msg("after settling, PoCL vs reference: %s", msg);
    double fc[3], ff[3], x[3 * 17];
    dem_wall_force(s, 0, fc);
    dem_wall_force(s, 1, ff);
    double weight = 17 * RHO * 4.0 / 3.0 * M_PI * pow(R_BEAD, 3) * 9.81;
    printf("  settled: floor %.5g N, cylinder %.5g N (z), weight %.5g N\n", -ff[2], -fc[2], weight);
    /* the walls are pushed down by the weight (cylinder friction may carry part of it); at rest the beads feel no net
     * horizontal force: what the cylinder receives sideways, the floor's friction takes back */
    printf("  settled: sideways cylinder %.3g, %.3g N, floor %.3g, %.3g N\n", fc[0], fc[1], ff[0], ff[1]);
    assert_true(fabs((-ff[2] - fc[2]) / weight - 1) < 0.01);
    assert_true(fabs(fc[0] + ff[0]) < 0.002 * weight && fabs(fc[1] + ff[1]) < 0.002 * weight);
    dem_get_field(s, DEM_FIELD_X, x);
    double top = 0;
    for (int i = 0; i < 17; i++)
        top = fmax(top, x[3 * i + 2] + R_BEAD);
    printf("  column top at %.4g m\n", top);
    for (int i = 0; i < 17; i++)
        assert_true(sqrt(x[3 * i] * x[3 * i] + x[3 * i + 1] * x[3 * i + 1]) < R_DIE - R_BEAD + 1e-4);
    /* the piston: rest, approach, press; its position follows the stages */
    long rest = lround(0.30 / dt), s1 = lround(0.32 / dt), s2 = lround(0.175 / dt);
    step_or_fail(s, rest + s1 - settle);
    double p[3], fp[3], fpeak = 0, below = 0;
    for (long k = 0; k < s2 + 100; k += 100) { /* the press: largest force on the piston, and the others then */
        step_or_fail(s, 100);
        dem_wall_force(s, 2, fp);
        if (fp[2] > fpeak) {
            fpeak = fp[2];
            dem_wall_force(s, 0, fc);
            dem_wall_force(s, 1, ff);
            below = -ff[2] - fc[2];
        }
    }
    dem_wall_position(s, 2, p);
    double expect = 0.08 - 0.2 * s1 * dt - 0.02 * s2 * dt;
    printf("  piston at %.9g m (expected %.9g), largest force while pressing %.4g N\n", p[2], expect, fpeak);
    assert_true(fabs(p[2] - expect) < 1e-12);
    /* the slow press is nearly quasi-static (within 5 %: the column is still being set in motion; measured 3.4 %):
     * at the piston's largest force, what the floor and the cylinder receive downwards is the beads' weight plus
     * what the piston receives (force balance on the beads) */
    double above = weight + fpeak;
    printf("  at the piston's largest force: floor + cylinder %.5g N, weight + piston %.5g N\n", below, above);
    assert_true(fpeak > 0.5 * weight);
    assert_true(fabs(below / above - 1) < 0.05);
    dem_destroy(s);
    dem_destroy(ref);
}

/* A servo stage (dem_stage.force): a plane lowered onto a fixed sphere from 10 um above comes down at its speed
 * limit, then settles where the sphere pushes back with the target force - to 1e-5 of it after 3000 steps - and
 * stays there; the second stage then lifts it at a set velocity. OpenCL moves it to the reference's bits. */
#define SERVO_F 2.0
static dem_sim *build_servo(void *ctx)
{
    (void)ctx;
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0.4});
    int a = dem_add_particle(s, (double[3]){0, 0, 0}, NULL, 0.005, m);
    dem_set_particle_flags(s, a, DEM_PARTICLE_FIXED);
    dem_wall lid = {DEM_WALL_PLANE, m, {0, 0, 0.00501}, {0, 0, -1}, 0, 2, {{0}}};
    lid.stages[0] = (dem_stage){3000e-6, {0, 0, 0}, SERVO_F, 0.5, 0.2};
    lid.stages[1] = (dem_stage){100e-6, {0, 0, 0.01}, 0, 0, 0};
    assert_int_equal(dem_add_wall(s, &lid), 0);
    dem_set_domain(s, (double[3]){-0.01, -0.01, -0.01}, (double[3]){0.01, 0.01, 0.01});
    dem_set_dt(s, 1e-6);
    return s;
}

static void check_servo(dem_sim *s, const backend_case *bc, void *ctx)
{
    (void)ctx;
    double f[3], p[3], p1[3];
    step_or_fail(s, 400); /* 10 um at 0.2 m/s: 50 steps to touch, then at most 0.2 m/s */
    dem_wall_force(s, 0, f);
    double early = f[2];
    step_or_fail(s, 2600);
    dem_wall_force(s, 0, f);
    dem_wall_position(s, 0, p);
    printf("  %s: servo lid at %.6f mm receives %.9g N after 3000 steps (target %g N; %.3g N after 400)\n",
           bc->name, 1e3 * p[2], f[2], SERVO_F, early);
    assert_true(fabs(f[2] / SERVO_F - 1) < 1e-5);
    assert_true(early > 0 && early < SERVO_F);
    step_or_fail(s, 100); /* the velocity stage lifts it 1 um */
    dem_wall_position(s, 0, p1);
    assert_true(fabs((p1[2] - p[2]) - 1e-6) < 1e-9);
}

static void test_servo(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    backend_run(bc, build_servo, 0, check_servo, NULL);
    dem_sim *s = dem_create(); /* a servo stage is refused on a cylinder and without a gain */
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0.4});
    dem_wall cyl = {DEM_WALL_CYLINDER, m, {0, 0, 0}, {0, 0, 1}, 0.01, 1, {{1e-3, {0, 0, 0}, 1, 1, 1}}};
    assert_int_equal(dem_add_wall(s, &cyl), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "a servo stage needs a plane wall"));
    dem_wall pl = {DEM_WALL_PLANE, m, {0, 0, 0}, {0, 0, 1}, 0, 1, {{1e-3, {0, 0, 0}, 1, 0, 1}}};
    assert_int_equal(dem_add_wall(s, &pl), DEM_ERR_ARG);
    dem_destroy(s);
}

/* Stages that end early (dem_stage.until_force, until_distance): a lid comes down at 0.1 m/s onto a fixed sphere
 * until it receives 1 N (at most 3 ms: it gets there after about 1600 steps), goes back up at 10 mm/s until it has
 * moved 0.495 um (at most 0.2 ms), then rests. The first stage ends after the first step whose force reached 1 N,
 * the lid going up from the next; the second after 50 steps of 0.01 um. OpenCL ends them at the reference's steps (its bits), and a restart from dem_state after the
 * first early end continues bit for bit. */
#define UNTIL_F 1.0
static dem_sim *build_until(void *ctx)
{
    (void)ctx;
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0.4});
    int a = dem_add_particle(s, (double[3]){0, 0, 0}, NULL, 0.005, m);
    dem_set_particle_flags(s, a, DEM_PARTICLE_FIXED);
    dem_wall lid = {DEM_WALL_PLANE, m, {0, 0, 0.00501}, {0, 0, -1}, 0, 3, {{0}}};
    lid.stages[0] = (dem_stage){.duration = 3000e-6, .velocity = {0, 0, -0.1}, .until_force = UNTIL_F};
    lid.stages[1] = (dem_stage){.duration = 200e-6, .velocity = {0, 0, 0.01}, .until_distance = 0.495e-6};
    lid.stages[2] = (dem_stage){.duration = 100e-6};
    assert_int_equal(dem_add_wall(s, &lid), 0);
    dem_set_domain(s, (double[3]){-0.01, -0.01, -0.01}, (double[3]){0.01, 0.01, 0.01});
    dem_set_dt(s, 1e-6);
    return s;
}

static void check_until(dem_sim *s, const backend_case *bc, void *ctx)
{
    long *ends = ctx;
    double f[3], p[3], prev = 0.00501;
    long hit = -1, up_end = -1;
    for (long k = 1; k <= 3300; k++) {
        step_or_fail(s, 1);
        dem_wall_force(s, 0, f);
        dem_wall_position(s, 0, p);
        double dz = p[2] - prev;
        prev = p[2];
        if (hit < 0) {
            assert_true(dz < 0); /* still coming down */
            if (f[2] >= UNTIL_F)
                hit = k;
        } else if (k == hit + 1) {
            assert_true(fabs(dz - 0.01e-6) < 1e-15); /* going up from the next step */
        } else if (up_end < 0 && fabs(dz) < 1e-15) {
            up_end = k - 1; /* the last step that moved */
        }
    }
    printf("  %s: the lid reached %g N at step %ld (it would have come down for 3000), went up for %ld steps\n",
           bc->name, UNTIL_F, hit, up_end - hit);
    assert_true(hit > 0 && hit < 3000);
    assert_int_equal(up_end - hit, 50);
    if (ends[0] < 0)
        ends[0] = hit;
    assert_int_equal(hit, ends[0]); /* the same step in every precision and backend: here the force is far from 1 N
                                       at the step before and after */
}

static void test_stage_ends(void **st)
{
    (void)st;
    long ends[1] = {-1};
    FOR_EACH_BACKEND(bc)
    backend_run(bc, build_until, 0, check_until, ends);
    FOR_EACH_BACKEND(bc)
    { /* a restart 5 steps after the first stage ended early */
        dem_config c = cfg_of(bc->backend, bc->precision);
        dem_sim *a = build_until(NULL), *b = build_until(NULL);
        restart_check(a, b, &c, ends[0] + 5, 200, bc->name);
        dem_destroy(a);
        dem_destroy(b);
    }
    dem_sim *s = dem_create(); /* an early end at a force needs a plane; the limits must be >= 0 and finite */
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0.4});
    dem_wall cyl = {DEM_WALL_CYLINDER, m, {0, 0, 0}, {0, 0, 1}, 0.01, 1, {{.duration = 1e-3, .until_force = 1}}};
    assert_int_equal(dem_add_wall(s, &cyl), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "until_force needs a plane wall"));
    dem_wall pl = {DEM_WALL_PLANE, m, {0, 0, 0}, {0, 0, 1}, 0, 1, {{.duration = 1e-3, .until_distance = -1}}};
    assert_int_equal(dem_add_wall(s, &pl), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "until_force and until_distance must be >= 0"));
    dem_destroy(s);
}

/* A velocity ramp and a stage that waits for another wall (dem_stage.ramp, after_wall): wall A comes down at 1 m/s for
 * 1 ms, its velocity ramping up from rest over the first 0.4 ms (0.8 mm in all: 0.4 ms x 0.5 m/s + 0.6 ms x 1 m/s);
 * wall B's one stage (up at 1 m/s for 0.5 ms) waits until A has run its stage: it rests 1000 steps, then rises
 * 0.5 mm. A sphere far from both keeps the run alive. Positions against those numbers; a restart during the wait and
 * one after it bit for bit. */
static dem_sim *build_ramp_after(void *ctx)
{
    (void)ctx;
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0.4});
    dem_add_particle(s, (double[3]){0, 0, 0.005}, NULL, 0.001, m);
    dem_wall a = {DEM_WALL_PLANE, m, {0, 0, 0.01}, {0, 0, -1}, 0, 1, {{0}}};
    a.stages[0] = (dem_stage){.duration = 1e-3, .velocity = {0, 0, -1}, .ramp = 0.4e-3};
    dem_wall b = {DEM_WALL_PLANE, m, {0, 0, 0}, {0, 0, 1}, 0, 1, {{0}}};
    b.stages[0] = (dem_stage){.duration = 0.5e-3, .velocity = {0, 0, 1}, .after_wall = 0, .after_stage = 1};
    assert_true(dem_add_wall(s, &a) == 0 && dem_add_wall(s, &b) == 1);
    dem_set_domain(s, (double[3]){-0.005, -0.005, -0.001}, (double[3]){0.005, 0.005, 0.011});
    dem_set_dt(s, 1e-6);
    return s;
}

static void check_ramp_after(dem_sim *s, const backend_case *bc, void *ctx)
{
    (void)ctx;
    double pa[3], pb[3];
    step_or_fail(s, 200); /* mid-ramp: sum over j < 200 of (j + 0.5) / 400 um = 200^2 / 800 um = 50 um */
    dem_wall_position(s, 0, pa);
    dem_wall_position(s, 1, pb);
    assert_true(fabs(pa[2] - (0.01 - 50e-6)) < 1e-12 && pb[2] == 0);
    step_or_fail(s, 799); /* A's last step still to come, B waiting */
    dem_wall_position(s, 1, pb);
    assert_true(pb[2] == 0);
    step_or_fail(s, 1);
    dem_wall_position(s, 0, pa);
    assert_true(fabs(pa[2] - (0.01 - 0.8e-3)) < 1e-12);
    step_or_fail(s, 600);
    dem_wall_position(s, 0, pa);
    dem_wall_position(s, 1, pb);
    printf("  %s: A at %.12f m after its stage (0.0092), B at %.12f m after its wait and stage (0.0005)\n", bc->name,
           pa[2], pb[2]);
    assert_true(fabs(pa[2] - (0.01 - 0.8e-3)) < 1e-12); /* A rests after its stage */
    assert_true(fabs(pb[2] - 0.5e-3) < 1e-12);
}

static void test_stage_ramp_after(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    if (bc->precision == DEM_FP64)
        backend_run(bc, build_ramp_after, 0, check_ramp_after, NULL);
    dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    for (int k = 0; k < 2; k++) { /* restarts in A's ramp (B waiting) and in B's stage */
        dem_sim *a = build_ramp_after(NULL), *b = build_ramp_after(NULL);
        restart_check(a, b, &c, k ? 1200 : 300, 400, "ramp and wait");
        dem_destroy(a);
        dem_destroy(b);
    }
    dem_sim *s = build_ramp_after(NULL); /* a ramp longer than its stage; a stage waiting for its own wall */
    dem_stage bad = {.duration = 1e-3, .velocity = {0, 0, 1}, .ramp = 2e-3};
    assert_int_equal(dem_set_wall_motion(s, 0, 1, &bad), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "ramp"));
    dem_stage self = {.duration = 1e-3, .after_wall = 1, .after_stage = 1};
    assert_int_equal(dem_set_wall_motion(s, 1, 1, &self), 0);
    dem_config rc = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    assert_int_equal(dem_start(s, &rc), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "other wall"));
    dem_destroy(s);
}

/* A stage that ends at a relative density (dem_stage.until_density): five spheres (r 1 mm) on the floor of a die
 * (R 3 mm), the punch coming down from 10 mm at 1 m/s until their volume fills 20 % of the bore below it; it must stop
 * after the first step at which the density it sees reached 0.2 (computed here from the positions), before touching
 * a sphere, at the same step on every backend. */
#define DENS_R 0.003
static dem_sim *build_density(void *ctx)
{
    int with_die = ctx ? *(int *)ctx : 1;
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0.4});
    for (int k = 0; k < 5; k++)
        dem_add_particle(s, (double[3]){0.0018 * cos(1.2566 * k), 0.0018 * sin(1.2566 * k), 0.00101}, NULL, 0.001,
                         m);
    if (with_die)
        dem_add_wall(s, &(dem_wall){DEM_WALL_CYLINDER, m, {0, 0, 0}, {0, 0, 1}, DENS_R});
    dem_add_wall(s, &(dem_wall){DEM_WALL_PLANE, m, {0, 0, 0}, {0, 0, 1}});
    dem_wall punch = {DEM_WALL_PLANE, m, {0, 0, 0.01}, {0, 0, -1}, 0, 2, {{0}}};
    punch.stages[0] = (dem_stage){.duration = 0.01, .velocity = {0, 0, -1}, .until_density = 0.2};
    punch.stages[1] = (dem_stage){.duration = 0.001};
    assert_true(dem_add_wall(s, &punch) >= 0);
    dem_set_domain(s, (double[3]){-0.005, -0.005, -0.001}, (double[3]){0.005, 0.005, 0.011});
    dem_set_dt(s, 1e-6);
    return s;
}

static void check_density(dem_sim *s, const backend_case *bc, void *ctx)
{
    double vs = 5 * 4.0 / 3.0 * M_PI * 1e-9, z = 0.01, p[3];
    long want = -1;
    for (long k = 1; want < 0; k++) { /* the first step after which the punch sees 0.2 */
        z = 0.01 - (double)k * 1e-6;
        if (vs / (M_PI * DENS_R * DENS_R * z) >= 0.2)
            want = k;
    }
    step_or_fail(s, 9000);
    dem_wall_position(s, 2, p);
    printf("  %s: the punch stopped at %.9f m (relative density %.5f), the first step at 0.2 is %ld (%.9f m)\n",
           bc->name, p[2], vs / (M_PI * DENS_R * DENS_R * p[2]), want, z);
    assert_true(fabs(p[2] - z) < 1e-12);
    assert_true(p[2] > 0.002); /* above the spheres: geometry alone ended it */
}

static void test_stage_ends_density(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    backend_run(bc, build_density, 0, check_density, NULL);
    FOR_EACH_BACKEND(bc)
    { /* a restart in the middle of the density-ended stage, and one after it ended */
        dem_config c = cfg_of(bc->backend, bc->precision);
        for (long at = 6000; at <= 6400; at += 400) {
            dem_sim *a = build_density(NULL), *b = build_density(NULL);
            restart_check(a, b, &c, at, 600, bc->name);
            dem_destroy(a);
            dem_destroy(b);
        }
    }
    int no_die = 0; /* no die: refused at the start, naming what is missing */
    dem_sim *s = build_density(&no_die);
    dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    assert_int_equal(dem_start(s, &c), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "until_density"));
    assert_non_null(strstr(dem_error(s), "no such cylinder"));
    dem_destroy(s);
    s = dem_create();
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0.4});
    dem_wall pl = {DEM_WALL_PLANE, m, {0, 0, 0}, {0, 0, 1}, 0, 1, {{.duration = 1e-3, .until_density = 1.5}}};
    assert_int_equal(dem_add_wall(s, &pl), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "until_density is a relative density in [0, 1]"));
    dem_destroy(s);
}

/* The walls' sums two ways: a run that keeps each particle's wall forces (dem_config.contacts: the sums add what
 * contact_forces kept) and one that does not (the sums evaluate the wall contacts again, before contact_forces).
 * Same bits, every backend and precision and contact model (MC-stress and MC-strain feed the wall law their own
 * terms), over settling beads in the die; only the first can give the contact network, whose wall contacts then
 * add up to what each wall received. */
static void test_kept_wall_forces(void **st)
{
    (void)st;
    static const char *models[] = {"classical", "mc_stress", "mc_strain lagged", "mc_strain iterated"};
    for (int model = 0; model < 4; model++)
    FOR_EACH_BACKEND(bc)
    {
        dem_sim *a = die_model(model), *b = die_model(model);
        dem_config ca = cfg_of(bc->backend, bc->precision), cb = ca;
        cb.contacts = 1;
        start_or_fail(a, &ca);
        start_or_fail(b, &cb);
        char msg[256];
        for (int chunk = 0; chunk < 20; chunk++) { /* the sums are due at the end of each call */
            step_or_fail(a, 397);
            step_or_fail(b, 397);
            if (state_diff(a, b, msg, sizeof msg))
                fail_msg("%s, %s, after %d steps: wall forces evaluated again vs kept: %s", bc->name, models[model],
                         397 * (chunk + 1), msg);
        }
        dem_contact *cs;
        long count, npairs;
        assert_int_equal(dem_contacts_get(a, &cs, &count, &npairs), DEM_ERR_STATE);
        assert_non_null(strstr(dem_error(a), "dem_config.contacts"));
        assert_int_equal(dem_contacts_get(b, &cs, &count, &npairs), 0);
        double sum[3] = {0, 0, 0}, fw[3], big = 0;
        for (long k = npairs; k < count; k++) /* particle-wall contacts: j = -1 - wall */
            if (cs[k].j == -1 - 1) /* wall 1, the floor */
                for (int d = 0; d < 3; d++)
                    sum[d] -= cs[k].fn[d] + cs[k].ft[d], big = fmax(big, fabs(cs[k].fn[d]));
        dem_wall_force(b, 1, fw);
        printf("  %s, %s: floor receives %.6g N; its contacts in the network add up to %.6g N\n", bc->name,
               models[model], fw[2], sum[2]);
        assert_true(count > npairs && big > 0);
        for (int d = 0; d < 3; d++)
            assert_true(fabs(sum[d] - fw[d]) <= 1e-4 * big);
        free(cs);
        dem_destroy(a);
        dem_destroy(b);
    }
}

/* The walls' sum as a tree of three levels (dem_layout.h) with more than one group: 40 000 spheres at rest on a floor,
 * each pressed into it by its own overlap, the 12 000 of lowest id larger and also touching a ceiling; one step. Each
 * wall receives the sum of the Hertz forces of its contacts, 4/3 E* sqrt(r) delta^(3/2), added here in long double;
 * 157 blocks of 256 in 3 groups of 64, so a group dropped, counted twice or given to the other wall is 1/157 or more
 * of the sum. The series row finishes the same tree on the host: its wall forces are dem_wall_force's bits. OpenCL
 * bitwise = reference. */
#define TREE_N 40000
#define TREE_BIG 12000
static void tree_forces(double floor_f[3], double ceil_f[3], double ceil_z, double E, double nu)
{
    long double fz = 0, cz = 0, estar = E / (2 * (1 - nu * nu));
    for (int i = 0; i < TREE_N; i++) {
        double r = i < TREE_BIG ? 0.0015 : 0.001, d = 1e-6 * (1 + (i % 97) / 97.0);
        fz += 4.0L / 3 * estar * sqrtl(r) * d * sqrtl(d);
        double z = r - d, dc = z + r - ceil_z; /* the ceiling's overlap */
        if (dc > 0)
            cz -= 4.0L / 3 * estar * sqrtl(r) * dc * sqrtl(dc);
    }
    floor_f[0] = floor_f[1] = ceil_f[0] = ceil_f[1] = 0;
    floor_f[2] = -(double)fz, ceil_f[2] = -(double)cz; /* what each wall receives: minus the force on the spheres */
}

/* ctx: NULL, or an int stride: sphere k is then added k-th in the order i = k * stride mod TREE_N, so it gets
 * another id and storage place (a stride prime to TREE_N makes it a permutation) */
static dem_sim *build_tree(void *ctx)
{
    int stride = ctx ? *(const int *)ctx : 1;
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0, 0, 0});
    for (int k = 0; k < TREE_N; k++) {
        int i = (int)((long)k * stride % TREE_N);
        double r = i < TREE_BIG ? 0.0015 : 0.001, d = 1e-6 * (1 + (i % 97) / 97.0);
        double x[3] = {0.0032 * (i % 200), 0.0032 * (i / 200), r - d};
        dem_add_particle(s, x, NULL, r, m);
    }
    dem_wall w = {.kind = DEM_WALL_PLANE, .material = m, .point = {0, 0, 0}, .normal = {0, 0, 1}};
    assert_true(dem_add_wall(s, &w) >= 0);
    w.point[2] = 0.0029975, w.normal[2] = -1; /* the large spheres' tops reach 3 mm - delta: 0.5-1.5 um into it */
    assert_true(dem_add_wall(s, &w) >= 0);
    dem_set_domain(s, (double[3]){-0.01, -0.01, -0.01}, (double[3]){0.65, 0.65, 0.02});
    if (dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_WALLS))
        fail_msg("%s", dem_error(s));
    dem_set_dt(s, 1e-11); /* the start's forces move the spheres by (F/m) dt^2 / 2 in the first drift: 1e-21 m here */
    return s;
}

static void check_tree(dem_sim *s, const backend_case *bc, void *ctx)
{
    (void)ctx;
    double want_floor[3], want_ceil[3], f[3], c[3];
    tree_forces(want_floor, want_ceil, 0.0029975, 1e7, 0.3);
    unsigned char want = 1;
    dem_sample row;
    assert_int_equal(dem_step_sampled(s, 1, &want, &row), 0); /* the first step: the spheres have not moved yet */
    dem_wall_force(s, 0, f);
    dem_wall_force(s, 1, c);
    /* fp32: a position of 3 mm carries 2.3e-10 m, 2e-4 to 5e-4 of these overlaps; a group lost is 1/157 of a sum */
    double tol = bc->precision == DEM_FP64 ? 1e-12 : 1e-3;
    printf("  %s: floor %.10g N (sum %.10g), ceiling %.10g N (sum %.10g)\n", bc->name, f[2], want_floor[2], c[2],
           want_ceil[2]);
    assert_true(want_ceil[2] > 0 && want_floor[2] < 0); /* the ceiling is pushed up, the floor down */
    assert_true(fabs(f[2] / want_floor[2] - 1) < tol && fabs(c[2] / want_ceil[2] - 1) < tol);
    assert_true(fabs(f[0]) + fabs(f[1]) < tol * fabs(f[2]) && fabs(c[0]) + fabs(c[1]) < tol * fabs(c[2]));
    assert_memory_equal(row.wall_force, f, sizeof f);
    assert_memory_equal(row.wall_force + 3, c, sizeof c);
}

static void test_wall_tree(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc) backend_run(bc, build_tree, 0, check_tree, NULL);
}

/* The walls' sums do not depend on which sphere has which id or is stored where (what a run split over several
 * devices needs: docs/design.md "Sums that do not depend on the decomposition"): the tree scene built in id order and
 * twice permuted (another id and storage place for every sphere; no two spheres touch, so each one's wall forces are
 * the same numbers), one sampled step each: the same bits of every wall's force and normal force. And they are the
 * correctly rounded sums of the forces in the contact network (each wall receives minus each contact's force, and its
 * normal force is the contacts' force along the normal, here +-z): in fp64 bit for bit equal to fsum_ref (test_util.c) of those
 * terms; in fp32 (each term a float, the sum rounded once to float) within half a float ulp and half a double ulp of
 * fsum_ref's double (both lie within half an ulp of their format of the exact sum). The same bits again without the
 * contact network (the sums then evaluate the wall contacts themselves, before contact_forces). */
static void test_wall_sum_any_order(void **st)
{
    (void)st;
    static int strides[] = {1, 7919, 39999}; /* in order; a scatter; reversed */
    FOR_EACH_BACKEND(bc)
    {
        double f0[2][3], n0[2];
        for (int v = 0; v < 3; v++) {
            dem_sim *s = build_tree(&strides[v]);
            dem_config c = cfg_of(bc->backend, bc->precision);
            c.contacts = 1;
            start_or_fail(s, &c);
            unsigned char want = 1;
            dem_sample row;
            assert_int_equal(dem_step_sampled(s, 1, &want, &row), 0);
            dem_contact *cs;
            long count, npairs;
            assert_int_equal(dem_contacts_get(s, &cs, &count, &npairs), 0);
            double *t = malloc(sizeof(double) * (size_t)(count + 1));
            assert_non_null(t);
            for (int w = 0; w < 2; w++) {
                double f[3];
                dem_wall_force(s, w, f);
                assert_memory_equal(row.wall_force + 3 * w, f, sizeof f);
                double want_f[4];
                for (int d = 0; d < 4; d++) { /* x, y, z; then the normal force */
                    long m = 0;
                    for (long k = npairs; k < count; k++)
                        if (cs[k].j == -1 - w)
                            t[m++] = d < 3 ? -cs[k].fn[d] : (w == 0 ? cs[k].fn[2] : -cs[k].fn[2]);
                    assert_true(m > 10000);
                    want_f[d] = fsum_ref(t, m);
                }
                double got[4] = {f[0], f[1], f[2], row.wall_normal[w]};
                for (int d = 0; d < 4; d++) {
                    if (bc->precision == DEM_FP64) /* (a zero sum: +0 here, the sign of fsum_ref's may differ) */
                        assert_true(got[d] == want_f[d] && (want_f[d] == 0 || !memcmp(&got[d], &want_f[d], 8)));
                    else if (want_f[d] != 0) /* both within half an ulp of the exact sum, each of its format */
                        assert_true(fabs(got[d] - want_f[d]) <=
                                    ldexp(1, ilogb(want_f[d]) - 24) + ldexp(1, ilogb(want_f[d]) - 53));
                    else
                        assert_true(got[d] == 0);
                }
                if (v == 0)
                    memcpy(f0[w], f, sizeof f), n0[w] = row.wall_normal[w];
                else {
                    assert_memory_equal(f0[w], f, sizeof f);
                    assert_memory_equal(&n0[w], &row.wall_normal[w], sizeof(double));
                }
                if (w == 0)
                    printf("  %s, stride %d: floor %.17g N, the terms' fsum %.17g N\n", bc->name, strides[v], f[2],
                           want_f[2]);
            }
            free(t);
            free(cs);
            /* the same without kept forces: wall_reduce_block evaluates the wall contacts itself, the same terms */
            dem_sim *u = build_tree(&strides[v]);
            dem_config cu = cfg_of(bc->backend, bc->precision);
            start_or_fail(u, &cu);
            dem_sample urow;
            assert_int_equal(dem_step_sampled(u, 1, &want, &urow), 0);
            assert_memory_equal(urow.wall_force, row.wall_force, sizeof(double) * 6);
            assert_memory_equal(urow.wall_normal, row.wall_normal, sizeof(double) * 2);
            dem_destroy(u);
            dem_destroy(s);
        }
    }
}

/* A finite cylinder (dem_wall.height: a die a tablet can leave): its side inside its length, its rim (an edge) in the
 * bore beyond either end, its end faces (the die table) outside the bore. One sphere (r = 1 mm) at rest against a die of radius 5 mm and height 10 mm, one step each:
 * what the wall receives points the way the geometry says, and an endless cylinder still touches where the finite
 * one does not. PoCL bitwise = reference (backend_run). */
typedef struct {
    double x[3], height;
    int expect; /* 0: no contact; 1: the side (along +x); 2: the rim, along (0.3, 0, -0.5) or (0.3, 0, +0.5);
                 * 3, 4: an end face, along -z or +z; 5: pushed out of the die's body into the bore (+x) */
} die_case;
static const die_case die_cases[] = {
    {{0.00401, 0, 0.005}, 0.01, 1},    /* inside, against the side */
    {{0.00401, 0, 0.0115}, 0.01, 0},   /* above the top, clear of the rim */
    {{0.00401, 0, 0.0115}, 0, 1},      /* the same place in an endless cylinder: the side */
    {{0.0047, 0, 0.0105}, 0.01, 2},    /* straddling the top rim: 0.3 mm inside it, 0.5 mm above */
    {{0.0047, 0, -0.0005}, 0.01, 2},   /* the same below the bottom rim */
    {{0.0020, 0, 0.0105}, 0.01, 0},    /* above the top near the axis: nothing */
    {{0.0060, 0, 0.0105}, 0.01, 3},    /* outside the bore, on the die table (the top face): 0.5 mm down */
    {{0.0060, 0, -0.0005}, 0.01, 4},   /* under the bottom face: 0.5 mm up */
    {{0.0052, 0, 0.006}, 0.01, 5},     /* a centre in the die's body, 0.2 mm from the bore: pushed back into it */
};
/* One sphere (r = 1 mm, at rest) against wall w, material 0 (e = 1: no damping, the bare law), dt 1e-7 s */
static dem_sim *one_sphere_against(const double x[3], dem_wall w)
{
    dem_sim *s = dem_create();
    w.material = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 1.0, 0.4});
    dem_add_particle(s, x, NULL, 0.001, w.material);
    assert_int_equal(dem_add_wall(s, &w), 0);
    dem_set_domain(s, (double[3]){-0.01, -0.01, -0.01}, (double[3]){0.01, 0.01, 0.03});
    dem_set_dt(s, 1e-7);
    return s;
}
/* the Hertz force of that sphere on a wall at overlap delta */
static double bare_hertz(double delta)
{
    return 4.0 / 3.0 * (1e7 / (2 * (1 - 0.3 * 0.3))) * sqrt(0.001) * delta * sqrt(delta);
}
static dem_sim *build_die_case(void *ctx)
{
    const die_case *c = ctx;
    return one_sphere_against(c->x, (dem_wall){.kind = DEM_WALL_CYLINDER, .normal = {0, 0, 1}, .radius = 0.005,
                                               .height = c->height});
}
static void check_die_case(dem_sim *s, const backend_case *bc, void *ctx)
{
    const die_case *c = ctx;
    double f[3];
    dem_wall_force(s, 0, f);
    double mag = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    if (c->expect == 0) {
        assert_true(mag == 0);
        assert_true(dem_wall_overlap(&(dem_wall){.kind = DEM_WALL_CYLINDER, .normal = {0, 0, 1}, .radius = 0.005,
                                                 .height = c->height},
                                     (double[3]){0, 0, 0}, c->x, 0.001, NULL) <= 0);
        return;
    }
    /* the Hertz force of the overlap: 0.01 mm at the side, 1 - sqrt(0.3^2 + 0.5^2) = 0.417 mm at the rim */
    double delta = c->expect == 1   ? 1e-5
                   : c->expect == 2 ? 0.001 - sqrt(0.0003 * 0.0003 + 0.0005 * 0.0005)
                   : c->expect == 5 ? 0.0012
                                    : 0.0005;
    double fh = bare_hertz(delta);
    printf("  %s: sphere at (%.4g, %.4g) mm, height %g mm: wall receives (%.6g, %.6g, %.6g) N (Hertz %.6g N)\n", bc->name,
           1e3 * c->x[0], 1e3 * c->x[2], 1e3 * c->height, f[0], f[1], f[2], fh);
    /* within the one step's drift (5e-6 at the rim) and the rounding of the side's overlap (3 digits cancel) */
    assert_true(fabs(mag / fh - 1) < 1e-5 + 2000 * bc->eps);
    /* one contact, frictionless here: its normal force (DEM_FIELD_WALL_NORMAL_FORCE) is the whole force's magnitude */
    double fn;
    assert_int_equal(dem_wall_normal_force(s, 0, &fn), 0);
    assert_true(fabs(fn / mag - 1) < 1e-6 * (1 + 1e6 * bc->eps));
    assert_true(fabs(f[1]) <= 1e-9 * mag);
    /* the host's view of the same contact (dem_wall_overlap: the contact network, energies, start-up checks) */
    double nh[3], dw = dem_wall_overlap(&(dem_wall){.kind = DEM_WALL_CYLINDER, .normal = {0, 0, 1}, .radius = 0.005,
                                                    .height = c->height},
                                        (double[3]){0, 0, 0}, c->x, 0.001, nh);
    assert_true(fabs(dw / delta - 1) < 1e-9);
    assert_true(fabs(nh[0] * f[0] + nh[2] * f[2] + mag) < 1e-6 * mag); /* the wall receives minus n */
    if (c->expect == 1 || c->expect == 5) {
        assert_true(f[0] > 0 && fabs(f[2]) <= 1e-9 * mag);
    } else if (c->expect >= 3) {
        assert_true(fabs(f[0]) <= 1e-9 * mag && (c->expect == 3 ? f[2] < 0 : f[2] > 0));
    } else { /* from the rim towards the centre: (-0.3, 0, +-0.5) on the sphere, the opposite on the wall */
        double sz = c->x[2] > 0 ? -1 : 1;
        assert_true(fabs(f[0] / mag - 0.3 / sqrt(0.34)) < 1e-6 * (1 + 1e6 * bc->eps));
        assert_true(fabs(f[2] / mag - sz * 0.5 / sqrt(0.34)) < 1e-6 * (1 + 1e6 * bc->eps));
    }
}
static void test_finite_die(void **st)
{
    (void)st;
    FOR_EACH_BACKEND(bc)
    for (size_t k = 0; k < sizeof die_cases / sizeof die_cases[0]; k++)
        backend_run(bc, build_die_case, 1, check_die_case, (void *)&die_cases[k]);
    dem_sim *s = dem_create(); /* a negative or non-finite height is refused */
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0.4});
    dem_wall bad = {.kind = DEM_WALL_CYLINDER, .material = m, .normal = {0, 0, 1}, .radius = 0.005, .height = -1};
    assert_int_equal(dem_add_wall(s, &bad), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "cylinder height must be >= 0 m"));
    dem_destroy(s);
}

/* The distance from x to a concave punch's face (normal +z through the origin; a cup of radius rp at the face and depth
 * c), by brute force: the face is a surface of revolution, so its nearest point lies in the half-plane through the
 * axis and x; there it is the land (z = 0, radial >= rp) and the cap's arc, sampled finely. */
static double cup_distance_brute(const double x[3], double rp, double c)
{
    double rc = (rp * rp + c * c) / (2 * c), hc = rc - c, rho = hypot(x[0], x[1]), z = x[2];
    double best = rho >= rp ? fabs(z) : hypot(rho - rp, z), amax = asin(rp / rc);
    enum { N = 20000 };
    for (int k = 0; k <= N; k++) { /* the arc: polar angle a from the cup's bottom */
        double a = amax * k / N, pr = rc * sin(a), pz = hc - rc * cos(a);
        best = fmin(best, hypot(rho - pr, z - pz));
    }
    return best;
}

/* A random centre over a 12 mm square and heights from -0.9 mm over a range zspan [m], about a concave face of cup
 * radius rp and depth c at the origin (normal +z); *rho its distance from the axis, *rc the cup sphere's radius.
 * 0 when it lies behind the face (inside the punch). */
static int cup_random_centre(unsigned *seed, double rp, double c, double zspan, double x[3], double *rho, double *rc)
{
    for (int d = 0; d < 3; d++)
        x[d] = d < 2 ? -0.006 + 0.012 * rand_r(seed) / (double)RAND_MAX : -0.0009 + zspan * rand_r(seed) / (double)RAND_MAX;
    *rho = hypot(x[0], x[1]), *rc = (rp * rp + c * c) / (2 * c);
    return !(*rho < rp ? hypot(*rho, x[2] - (*rc - c)) > *rc : x[2] < 0);
}

/* A concave punch's face (dem_wall.cup_radius, cup_depth) as the kernels see it (dem_wall_overlap compiles their
 * wall_geometry in double): against a brute-force distance at 6000 random centres over the cup, its rim and the land
 * (r = 0.5 mm, a cup of radius 4 mm and depth 0.8 mm with a land beyond it): every contact found has the overlap r -
 * distance, its normal is a unit vector whose contact point (at r - overlap along it) lies on the face, and no contact
 * is missed. Then a plane
 * is refused a cup deeper than a hemisphere, and a cylinder any cup. */
static void test_cup_geometry(void **st)
{
    (void)st;
    const double rp = 0.004, c = 0.0008, r = 0.0005;
    dem_wall w = {.kind = DEM_WALL_PLANE, .normal = {0, 0, 1}, .cup_radius = rp, .cup_depth = c};
    const double origin[3] = {0, 0, 0};
    unsigned seed = 7;
    int hits[3] = {0, 0, 0}, missed = 0;
    double worst = 0, worst_n = 0;
    for (int k = 0; k < 6000; k++) {
        double x[3], rho, rc;
        if (!cup_random_centre(&seed, rp, c, 0.0016, x, &rho, &rc))
            continue; /* behind the face: inside the punch */
        double n[3], delta = dem_wall_overlap(&w, origin, x, r, n), dist = cup_distance_brute(x, rp, c);
        if (!(delta > 0)) {
            missed += dist < r - 1e-9;
            continue;
        }
        hits[rho >= rp ? 0 : fabs(dist - hypot(rho - rp, x[2])) < 1e-12 ? 2 : 1]++;
        /* the sampled arc's error: a chord of s = rc asin(rp / rc) / N seen from a centre at distance dist */
        double s = rc * asin(rp / rc) / 20000;
        worst = fmax(worst, fabs((r - delta) - dist) / (1e-12 + s * s / (4 * dist)));
        double p[3] = {x[0] - n[0] * (r - delta), x[1] - n[1] * (r - delta), x[2] - n[2] * (r - delta)};
        double prho = hypot(p[0], p[1]), off = prho >= rp ? fabs(p[2]) : fabs(hypot(prho, p[2] - (rc - c)) - rc);
        assert_true(prho >= rp || p[2] <= 1e-12); /* on the cup, not on the rest of its sphere */
        worst_n = fmax(worst_n, fmax(fabs(sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]) - 1), off));
    }
    printf("  concave face: %d contacts over the land, %d in the cup, %d on the rim; largest |r - overlap - distance| "
           "%.2g of the sampling's bound, contact point off the face by at most %.2g m; missed %d\n", hits[0], hits[1],
           hits[2], worst, worst_n, missed);
    assert_true(hits[0] > 50 && hits[1] > 200 && hits[2] > 20);
    assert_true(worst < 1 && worst_n < 1e-15);
    assert_int_equal(missed, 0);
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0.4});
    w.material = m;
    w.cup_depth = 0.005;
    assert_int_equal(dem_add_wall(s, &w), DEM_ERR_ARG);
    assert_non_null(strstr(dem_error(s), "a cup is a plane's, with radius / 1000 <= depth <= radius"));
    w.cup_depth = 1e-7; /* shallower than a thousandth of its radius: a flat punch */
    assert_int_equal(dem_add_wall(s, &w), DEM_ERR_ARG);
    dem_wall cyl = {.kind = DEM_WALL_CYLINDER, .material = m, .normal = {0, 0, 1}, .radius = 0.005, .cup_radius = 0.001,
                    .cup_depth = 0.0005};
    assert_int_equal(dem_add_wall(s, &cyl), DEM_ERR_ARG);
    w.cup_depth = c;
    assert_int_equal(dem_add_wall(s, &w), 0);
    dem_destroy(s);
    /* the relative density between a concave lower punch and a flat upper one in a die counts the cup; a cup off
     * the die's axis, reaching out of the bore, is refused */
    for (int off = 0; off < 2; off++) {
        s = dem_create();
        m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0.4});
        dem_add_particle(s, (double[3]){0, 0, 0.006}, NULL, 0.001, m);
        dem_wall die = {.kind = DEM_WALL_CYLINDER, .material = m, .normal = {0, 0, 1}, .radius = rp, .height = 0.012};
        dem_wall lower = {.kind = DEM_WALL_PLANE, .material = m, .point = {off ? 0.0005 : 0, 0, 0.002},
                          .normal = {0, 0, 1}, .cup_radius = rp, .cup_depth = c};
        dem_wall upper = {.kind = DEM_WALL_PLANE, .material = m, .point = {0, 0, 0.0125}, .normal = {0, 0, -1}};
        assert_int_equal(dem_add_wall(s, &die), 0);
        assert_int_equal(dem_add_wall(s, &lower), 1);
        assert_int_equal(dem_add_wall(s, &upper), 2);
        double rho = -1, hand = 4.0 / 3.0 * M_PI * 1e-9 / (M_PI * rp * rp * 0.0105 + M_PI * c * (3 * rp * rp + c * c) / 6);
        assert_int_equal(dem_cup_in_bore(s, 1, 0), !off);
        assert_int_equal(dem_relative_density(s, 2, &rho), off ? DEM_ERR_ARG : DEM_OK);
        if (!off)
            assert_true(fabs(rho / hand - 1) < 1e-14);
        dem_destroy(s);
    }
}

/* A wall's reach across a gap (wall_geometry_gap: a JKR contact held to its release, laws/thornton_ning.h), in double
 * as the host compiles it, gap = r: at 6000 random centres over a concave punch face (its land, cup and rim) against
 * the brute-force distance, a contact is found exactly where distance < r + gap, with the overlap r - distance
 * (negative across the gap); where the sphere overlaps, the gap's result is the plain geometry's bit for bit. On a
 * finite die (a cylinder of radius 6 mm and length 10 mm): its side from inside and its top rim as an edge against
 * their closed-form distances. */
static void test_gap_geometry(void **st)
{
    (void)st;
    const double rp = 0.004, c = 0.0008, r = 0.0005, gap = r;
    real cup[W_STRIDE] = {0};
    cup[W_NZ] = 1, cup[W_RADIUS] = rp, cup[W_HEIGHT] = c;
    unsigned seed = 11;
    int across = 0, bad = 0, same = 0;
    double worst = 0;
    for (int k = 0; k < 6000; k++) {
        double x[3], rho, rc;
        if (!cup_random_centre(&seed, rp, c, 0.0026, x, &rho, &rc))
            continue; /* behind the face */
        double dist = cup_distance_brute(x, rp, c), s = rc * asin(rp / rc) / 20000, tol = 1e-12 + s * s / (4 * dist);
        wall_geom g = wall_geometry_gap(WALL_PLANE_CUP, cup, v3(x[0], x[1], x[2]), r, gap);
        wall_geom g0 = wall_geometry(WALL_PLANE_CUP, cup, v3(x[0], x[1], x[2]), r);
        if (fabs(dist - (r + gap)) > tol) /* away from the reach's edge: active exactly within it */
            bad += g.active != (dist < r + gap);
        if (!g.active)
            continue;
        across += !(g.delta > 0);
        worst = fmax(worst, fabs((r - g.delta) - dist) / tol);
        if (g0.active) {
            assert_true(g.delta == g0.delta && g.n.x == g0.n.x && g.n.y == g0.n.y && g.n.z == g0.n.z);
            same++;
        }
    }
    /* the die: the side seen from inside (distance R - rho), and the top rim (an edge: distance to the circle) */
    const double rd = 0.006, len = 0.01;
    real die[W_STRIDE] = {0};
    die[W_NZ] = 1, die[W_RADIUS] = rd, die[W_HEIGHT] = len;
    double side_worst = 0, rim_worst = 0;
    int side_found = 0, rim_found = 0;
    for (int k = 1; k < 200; k++) {
        double q = 2.2 * r * k / 200; /* the gap out to 2.2 r: found up to 2 r */
        wall_geom gs = wall_geometry_gap(WALL_CYLINDER_INSIDE, die, v3(rd - q, 0, 0.5 * len), r, gap);
        side_found += gs.active;
        bad += gs.active != (q < r + gap);
        if (gs.active)
            side_worst = fmax(side_worst, fabs(gs.delta - (r - q)));
        double a = 0.7 * q, b = sqrt(q * q - a * a); /* centre above the bore's end, inside: q from the rim circle */
        wall_geom ge = wall_geometry_gap(WALL_CYLINDER_INSIDE, die, v3(rd - b, 0, len + a), r, gap);
        rim_found += ge.active;
        bad += ge.active != (q < r + gap);
        if (ge.active)
            rim_worst = fmax(rim_worst, fmax(fabs(ge.delta - (r - q)), /* n from the rim towards the centre */
                                             fmax(fabs(ge.n.x * q + b), fabs(ge.n.z * q - a))));
    }
    printf("  a wall's reach across a gap of r: concave face %d contacts across the gap, %d overlapping (bitwise the "
           "plain geometry's), largest |r - overlap - distance| %.2g of the sampling's bound; die side %d and rim %d "
           "of 199 found, overlap off by %.2g and %.2g m; %d misjudged\n",
           across, same, worst, side_found, rim_found, side_worst, rim_worst, bad);
    assert_int_equal(bad, 0);
    assert_true(across > 100 && same > 100 && worst < 1);
    assert_true(side_worst < 1e-15 && rim_worst < 1e-15);
}

/* A sphere (r = 1 mm) at rest against a concave punch face (cup radius 4 mm, depth 0.8 mm, normal +z) with an overlap
 * of 2 um: on the axis at the cup's bottom, in the cup 0.2 rad off the axis (seen from the cup sphere's centre), and
 * over the land. One step on every backend and precision (backend_run: PoCL bitwise = reference): the wall receives
 * the Hertz force of that overlap (r* = r: walls are taken locally flat) along the face's normal there - in fp32
 * too, where the overlap in the cup is a difference of lengths of 10 mm (contact_geometry.h computes it without
 * the cancellation). */
typedef struct {
    double x[3], u[3]; /* centre; unit vector along which the wall receives the force */
} cup_case;
#define CUP_RP 0.004
#define CUP_C 0.0008
#define CUP_DELTA 2e-6
static cup_case cup_cases[3];
static void cup_cases_make(void)
{
    double rc = (CUP_RP * CUP_RP + CUP_C * CUP_C) / (2 * CUP_C), hc = rc - CUP_C, a = 0.2, r = 0.001;
    cup_cases[0] = (cup_case){{0, 0, -CUP_C + r - CUP_DELTA}, {0, 0, -1}};
    /* from the cup sphere's centre along u = (sin a, 0, -cos a): the face at rc, the centre at rc - r + delta */
    double u[3] = {sin(a), 0, -cos(a)}, d = rc - r + CUP_DELTA;
    cup_cases[1] = (cup_case){{d * u[0], 0, hc + d * u[2]}, {u[0], 0, u[2]}};
    cup_cases[2] = (cup_case){{0.0045, 0.0002, r - CUP_DELTA}, {0, 0, -1}};
}
static dem_sim *build_cup_case(void *ctx)
{
    const cup_case *c = ctx;
    return one_sphere_against(c->x, (dem_wall){.kind = DEM_WALL_PLANE, .normal = {0, 0, 1}, .cup_radius = CUP_RP,
                                               .cup_depth = CUP_C});
}
static void check_cup_case(dem_sim *s, const backend_case *bc, void *ctx)
{
    const cup_case *c = ctx;
    double f[3];
    dem_wall_force(s, 0, f);
    double mag = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    double fh = bare_hertz(CUP_DELTA);
    printf("  %s: sphere at (%.4g, %.4g, %.4g) mm: wall receives (%.6g, %.6g, %.6g) N (Hertz %.6g N)\n", bc->name,
           1e3 * c->x[0], 1e3 * c->x[1], 1e3 * c->x[2], f[0], f[1], f[2], fh);
    assert_true(fabs(mag / fh - 1) < 1e-5 + 2000 * bc->eps);
    assert_true(fabs((f[0] * c->u[0] + f[1] * c->u[1] + f[2] * c->u[2]) / mag - 1) < 1e-9 + 100 * bc->eps);
}
static void test_cup_forces(void **st)
{
    (void)st;
    cup_cases_make();
    FOR_EACH_BACKEND(bc)
    for (size_t k = 0; k < sizeof cup_cases / sizeof cup_cases[0]; k++)
        backend_run(bc, build_cup_case, 1, check_cup_case, &cup_cases[k]);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_die), cmocka_unit_test(test_wall_tree),
                                       cmocka_unit_test(test_wall_sum_any_order), cmocka_unit_test(test_servo), cmocka_unit_test(test_stage_ends),
                                       cmocka_unit_test(test_stage_ends_density), cmocka_unit_test(test_stage_ramp_after),
                                       cmocka_unit_test(test_kept_wall_forces), cmocka_unit_test(test_finite_die),
                                       cmocka_unit_test(test_cup_geometry), cmocka_unit_test(test_gap_geometry),
                                       cmocka_unit_test(test_cup_forces)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
