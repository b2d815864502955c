/* test_stability.c - hard cases that need a whole packing (the short versions; test_hard_cases.c has the
 * two-particle ones).
 *
 * Size ratio 20:1 (hard case 2): 60 coarse spheres (r 2 mm) and 4000 fines (r 0.1 mm) placed at random in a box and
 * set flying at 0.5 m/s, so that fines hit coarse spheres, fines and walls. The binning cells are sized by the coarse
 * spheres, so each holds hundreds of fines: after 1500 steps every touching pair the library counts from its
 * neighbour rows (dem_energy) must be one a brute-force search over all pairs finds, and none missing, on every
 * backend and precision, and OpenCL has the reference's bits. (Its cost against a monodisperse packing belongs to
 * `make bench`, not to a timed test.)
 *
 * Stiffness contrast 1e6 (hard case 1): glass beads (65 GPa, seed 000 Table 1) dropped onto a bed of hydrogel spheres
 * (23.3 kPa, seed 000's hydrogel with water's density) in a box under gravity, at the time step the library
 * recommends for that mix (0.2 of the smallest Rayleigh time: the glass's). Every position stays finite, the total
 * energy (kinetic + elastic + potential) never rises above where it started by more than a thousandth of the beads'
 * drop energy, no bead sinks below the top layer's mid-plane (the beads are larger than the lattice's holes), and
 * OpenCL has the reference's bits.
 *
 * Elastic gas (hard case 5): 1000 spheres at 6.5 % solid, restitution 1, no friction, no gravity, in a closed box:
 * the total energy (kinetic + elastic) drifts by less than 1e-4 in fp64 over the run at 0.05 of the Rayleigh time;
 * the drift at the recommended 0.2 and fp32's are reported.
 * The time step at the stability bound (hard case 9): a dense frictional packing (855 spheres, 58 %, damping,
 * gravity) at 0.5 of the Rayleigh time, the bound the library accepts: its total energy never rises above its
 * start.
 *
 * A resting column (hard case 4): 50 spheres stacked on a floor under gravity settle; after that the top sphere's
 * height stays put to 1e-9 m (no creep), the kinetic energy decays below 1e-15 J, and no sphere leaves the axis.
 *
 * Lagged MC-strain on stiff glass (hard case 6): the glass die's whole cycle under classical, lagged and iterated
 * MC-strain: lagged rings (kinetic energy above 5x the classical run's), iterated does not (below 2x), and the
 * contacts' mean overlap passed the overlap where the lag's loop gain reaches 1 (app/run.c); the 514 hydrogels stay
 * below it and lagged does not ring; `dem check --model mc_strain` warns for the glass die, not when iterated. The
 * ringing state runs 2000 steps on OpenCL with the reference's bits. Both scenes run their whole cycle here and in
 * `make stability` (the glass die's 1e6 steps take about 5 s per model on the reference).
 *
 * Compaction to relative density 0.9 (hard case 7): 300 spheres in a die under each model (test_compaction_09).
 *
 * The step's stability at the overlaps reached (dem_stability_get, host/physics/stability.c): 64 MCC-like spheres on a
 * simple cubic lattice pressed 10 % into each other and into a box, nudged off their places. The estimate matches
 * its closed form for an inner sphere (six like contacts), is the same on every backend, and it tells apart a step
 * at which the lattice comes to rest (0.7 of the advice) from one at which it stays stirred (2x): the kinetic energy
 * falls below 1e-20 of the elastic one at the first and stays above 1e-9 of it at the second. A lone sphere has no
 * contact, so no estimate.
 *
 * Every case is checked bit for bit between OpenCL and the reference: the whole run, or (the resting column's first
 * 20 000 steps, the glass die's ringing 2000) a stretch of it.
 *
 * Short versions here; DEM_STABILITY_LONG=1 (`make stability`) runs the full lengths: 1e5 steps each. */
#include "test_util.h"
#include "scene.h"
#include "run.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char size_ratio_scene[] =
    "name: size ratio 20\n"
    "precision: fp64\n"
    "effects: [hertz, damping, friction, walls]\n"
    "materials:\n"
    "  - {name: grain, density: 2500, young: 1.0e7, poisson: 0.3, restitution: 0.5, friction: 0.4}\n"
    "particles:\n"
    "  - material: grain\n"
    "    generate: {kind: random, shape: box, region: {lo: [0, 0, 0], hi: [0.02, 0.02, 0.02]}, radius: 0.002, "
    "count: 60, speed: 0.5, seed: 1}\n"
    "  - material: grain\n"
    "    generate: {kind: random, shape: box, region: {lo: [0, 0, 0], hi: [0.02, 0.02, 0.02]}, radius: 0.0001, "
    "count: 4000, speed: 0.5, seed: 2}\n"
    "walls:\n"
    "  - {type: box, material: grain, lo: [0, 0, 0], hi: [0.02, 0.02, 0.02]}\n"
    "time: {dt_rayleigh: 0.2, duration: 1.0}\n";

static dem_sim *size_ratio_build(dem_precision p)
{
    char err[4096];
    scene *sc = scene_load_text("size_ratio.yaml", size_ratio_scene, sizeof size_ratio_scene - 1, err, sizeof err);
    if (!sc)
        fail_msg("%s", err);
    scene_run run;
    dem_sim *s = scene_build(sc, &run, err, sizeof err);
    if (!s)
        fail_msg("%s", err);
    scene_free(sc);
    (void)p;
    return s;
}

/* touching pairs by brute force over all pairs (overlap > 0, as dem_energy counts them), coarse-fine ones apart */
static long brute_pairs(dem_sim *s, long *mixed)
{
    int n = dem_count(s);
    double *x = malloc(sizeof(double) * 3 * n);
    assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
    long c = 0;
    *mixed = 0;
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++) {
            double d[3] = {x[3 * i] - x[3 * j], x[3 * i + 1] - x[3 * j + 1], x[3 * i + 2] - x[3 * j + 2]};
            double rs = dem_particle_radius(s, i) + dem_particle_radius(s, j);
            if (rs - sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]) > 0) {
                c++;
                *mixed += dem_particle_radius(s, i) != dem_particle_radius(s, j);
            }
        }
    free(x);
    return c;
}

static void test_size_ratio(void **st)
{
    (void)st;
    for (int p = 0; p < 2; p++) {
        dem_precision prec = p ? DEM_FP64 : DEM_FP32;
        dem_sim *cl = size_ratio_build(prec), *ref = size_ratio_build(prec);
        dem_config c = cfg_of(DEM_BACKEND_OPENCL, prec), rc = cfg_of(DEM_BACKEND_REFERENCE, prec);
        start_or_fail(cl, &c);
        start_or_fail(ref, &rc);
        long seen = 0;
        for (int k = 0; k < 3; k++) {
            step_or_fail(cl, 500);
            dem_energy_t e;
            assert_int_equal(dem_energy(cl, &e), 0);
            long mixed, brute = brute_pairs(cl, &mixed);
            printf("  %s, step %ld: %ld touching pairs from the rows, %ld by brute force (%ld coarse-fine), %ld wall "
                   "contacts, %d rebuilds so far, %d cells\n",
                   p ? "fp64" : "fp32", dem_step_index(cl), e.contacts, brute, mixed, e.wall_contacts,
                   (int)dem_rebuild_count(cl), dem_cell_count(cl));
            assert_int_equal(e.contacts, brute);
            seen += mixed;
        }
        assert_true(seen > 0); /* fines did meet coarse spheres */
        step_or_fail(ref, 1500);
        char msg[256];
        if (state_diff(cl, ref, msg, sizeof msg))
            fail_msg("OpenCL vs reference: %s", msg);
        dem_destroy(cl);
        dem_destroy(ref);
    }
}

/* The end of every builder here: the binning domain, and the time step as a fraction of the smallest Rayleigh time
 * (0.2: the library's recommendation) */
static dem_sim *finish(dem_sim *s, const double lo[3], const double hi[3], double dt_frac)
{
    dem_set_domain(s, lo, hi);
    dem_time_scales ts;
    dem_time_scales_get(s, 0, &ts);
    dem_set_dt(s, dt_frac * ts.rayleigh_time);
    return s;
}

#define GEL_R 0.004
#define BEAD_R 0.003
#define DROP 0.002
/* 4 x 4 x 3 hydrogel spheres on a simple cubic lattice (spacing 2 r + 0.1 mm) in a box, three glass beads above the
 * top layer's hollows, DROP clear of it */
static dem_sim *contrast_build(double *top_z)
{
    dem_sim *s = dem_create();
    int gel = dem_add_material(s, &(dem_material){1000, 23.3e3, 0.5, 0.95, 0.03});
    int glass = dem_add_material(s, &(dem_material){2500, 65e9, 0.24, 0.98, 0.2});
    const double a = 2 * GEL_R + 1e-4, L = 4 * a;
    for (int k = 0; k < 3; k++)
        for (int j = 0; j < 4; j++)
            for (int i = 0; i < 4; i++)
                dem_add_particle(s, (double[3]){a / 2 + i * a, a / 2 + j * a, GEL_R + k * a}, NULL, GEL_R, gel);
    *top_z = GEL_R + 2 * a;
    for (int b = 0; b < 3; b++) /* over hollows of the top layer, where the bead rests on four gel spheres */
        dem_add_particle(s, (double[3]){(1 + b) * a, (1 + b % 2) * a, *top_z + GEL_R + BEAD_R + DROP}, NULL, BEAD_R,
                         glass);
    dem_add_box(s, (double[3]){0, 0, 0}, (double[3]){L, L, 0.06}, glass);
    dem_set_gravity(s, (double[3]){0, 0, -9.81});
    return finish(s, (double[3]){-0.005, -0.005, -0.005}, (double[3]){L + 0.005, L + 0.005, 0.065}, 0.2);
}

static void test_stiffness_contrast(void **st)
{
    (void)st;
    double top;
    dem_sim *cl = contrast_build(&top), *ref = contrast_build(&top);
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, DEM_FP64), rc = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    start_or_fail(cl, &c);
    start_or_fail(ref, &rc);
    int n = dem_count(cl);
    double bead_m = dem_particle_mass(cl, n - 1), drop_e = 3 * bead_m * 9.81 * DROP;
    dem_energy_t e;
    assert_int_equal(dem_energy(cl, &e), 0);
    double e0 = e.total, worst_rise = -INFINITY, lowest = INFINITY;
    const long chunk = 500, steps = (long)(0.04 / dem_dt(cl)) / chunk * chunk; /* 40 ms: fall, impact, rest */
    double *x = malloc(sizeof(double) * 3 * n);
    for (long k = 0; k < steps; k += chunk) {
        step_or_fail(cl, chunk);
        assert_int_equal(dem_energy(cl, &e), 0);
        worst_rise = fmax(worst_rise, e.total - e0);
        assert_int_equal(dem_get_field(cl, DEM_FIELD_X, x), 0);
        for (int i = 0; i < 3 * n; i++)
            assert_true(isfinite(x[i]));
        for (int b = n - 3; b < n; b++)
            lowest = fmin(lowest, x[3 * b + 2]);
    }
    printf("  dt %.3g s (0.2 of the glass's Rayleigh time), %ld steps: total energy rose at most %.3g J over its start "
           "(%.3g of the beads' drop energy %.3g J); lowest bead centre %.3f mm, the top layer's mid-plane at %.3f mm\n",
           dem_dt(cl), steps, worst_rise, worst_rise / drop_e, drop_e, 1e3 * lowest, 1e3 * top);
    assert_true(worst_rise < 1e-3 * drop_e);
    assert_true(lowest > top);
    step_or_fail(ref, steps);
    char msg[256];
    if (state_diff(cl, ref, msg, sizeof msg))
        fail_msg("OpenCL vs reference: %s", msg);
    free(x);
    dem_destroy(cl);
    dem_destroy(ref);
}

static long run_length(long short_steps, long long_steps)
{
    return getenv("DEM_STABILITY_LONG") ? long_steps : short_steps;
}

/* the largest |total - start| / start (rise: the largest total - start, unscaled) over samples every `every` steps */
static double energy_excursion(dem_sim *s, long steps, long every, double *rise)
{
    dem_energy_t e;
    assert_int_equal(dem_energy(s, &e), 0);
    double e0 = e.total, worst = 0;
    *rise = -INFINITY;
    for (long k = 0; k < steps; k += every) {
        step_or_fail(s, every);
        assert_int_equal(dem_energy(s, &e), 0);
        assert_true(isfinite(e.total));
        worst = fmax(worst, fabs(e.total - e0) / fabs(e0));
        *rise = fmax(*rise, e.total - e0);
    }
    return worst;
}

/* 1000 spheres (r 1 mm) on a lattice of 4 mm in a closed box, 6.5 % solid, random velocities of 0.5 m/s per
 * component at most, restitution 1, no friction, no gravity */
static dem_sim *gas_build(double dt_frac)
{
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 1.0, 0.0});
    unsigned seed = 99;
    const double a = 0.004, L = 10 * a;
    for (int i = 0; i < 1000; i++) {
        double x[3] = {(i % 10 + 0.5) * a, (i / 10 % 10 + 0.5) * a, (i / 100 + 0.5) * a}, v[3];
        for (int d = 0; d < 3; d++)
            v[d] = 0.5 * (2 * uniform01(&seed) - 1);
        dem_add_particle(s, x, v, 0.001, m);
    }
    dem_add_box(s, (double[3]){0, 0, 0}, (double[3]){L, L, L}, m);
    dem_set_effects(s, DEM_EFFECT_HERTZ | DEM_EFFECT_WALLS);
    return finish(s, (double[3]){-0.005, -0.005, -0.005}, (double[3]){L + 0.005, L + 0.005, L + 0.005}, dt_frac);
}

static void test_elastic_gas(void **st)
{
    (void)st;
    long steps = run_length(10000, 100000), every = 100, ns = steps / every;
    double *tot = malloc(sizeof(double) * (size_t)(ns + 1));
    for (int q = 0; q < 4; q++) {
        int p = q % 2;
        double frac = q < 2 ? 0.2 : 0.05;
        dem_sim *s = gas_build(frac);
        dem_config c = cfg_of(DEM_BACKEND_OPENCL, p ? DEM_FP64 : DEM_FP32);
        start_or_fail(s, &c);
        dem_energy_t e;
        double worst = 0;
        long contacts = 0;
        for (long k = 0; k <= ns; k++) {
            if (k)
                step_or_fail(s, every);
            assert_int_equal(dem_energy(s, &e), 0);
            tot[k] = e.total;
            worst = fmax(worst, fabs(e.total - tot[0]) / tot[0]);
            contacts += e.contacts + e.wall_contacts;
        }
        /* the drift: the mean of the last tenth of the samples against the first tenth's (inside a contact the
         * energy of velocity Verlet is off by O(dt^2) and comes back when it ends; a drift is what does not) */
        double head = 0, tail = 0;
        long m = ns / 10;
        for (long k = 0; k < m; k++)
            head += tot[k] / m, tail += tot[ns - k] / m;
        double drift = fabs(tail - head) / head;
        printf("  elastic gas, 1000 spheres at 6.5 %%, %s, %ld steps at %.2g of the Rayleigh time (%.2g contacts per "
               "sample): total energy drift %.3g, largest excursion %.3g\n",
               p ? "fp64" : "fp32", steps, frac, (double)contacts / (double)(ns + 1), drift, worst);
        assert_true(contacts > ns); /* it collides */
        /* each collision's entry and exit leave an energy error of order (dt / contact time)^2 of its energy that
         * does not cancel, and those add up as a random walk: at 0.2 t_R 4e-4 over 1e5 steps in fp64 (measured),
         * at 0.05 t_R the 1e-4 asked; fp32 is reported, and bounded so that a blow-up fails */
        if (p && frac < 0.1)
            assert_true(drift < 1e-4);
        else
            assert_true(drift < 1e-2);
        if (frac > 0.1) { /* the reference, the same steps: the same bits */
            dem_sim *r = gas_build(frac);
            dem_config rc = cfg_of(DEM_BACKEND_REFERENCE, c.precision);
            start_or_fail(r, &rc);
            step_or_fail(r, steps);
            char msg[512];
            if (state_diff(s, r, msg, sizeof msg))
                fail_msg("elastic gas, %s, OpenCL against the reference: %s", p ? "fp64" : "fp32", msg);
            dem_destroy(r);
        }
        dem_destroy(s);
    }
    free(tot);
}

static void test_dt_at_bound(void **st)
{
    (void)st;
    long steps = run_length(10000, 100000);
    packing_opts o;
    packing_defaults(&o);
    o.side = 8, o.lid_speed = 0;
    dem_sim *s = packing_build(&o);
    dem_time_scales ts;
    dem_time_scales_get(s, 0, &ts);
    assert_int_equal(dem_set_dt(s, ts.max_dt), 0);
    dem_config c = cfg_of(DEM_BACKEND_OPENCL, DEM_FP64);
    start_or_fail(s, &c);
    dem_energy_t e;
    dem_energy(s, &e);
    double e0 = e.total, rise, drift = energy_excursion(s, steps, 500, &rise);
    printf("  frictional packing, %d spheres, dt = 0.5 of the Rayleigh time, %ld steps: total energy at most %.3g J "
           "above its start (%.3g of it), at most %.3g away\n", dem_count(s), steps, rise, rise / e0, drift);
    assert_true(rise <= 1e-9 * fabs(e0));
    dem_sim *r = packing_build(&o); /* the reference, the same steps: the same bits */
    assert_int_equal(dem_set_dt(r, ts.max_dt), 0);
    dem_config rc = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    start_or_fail(r, &rc);
    step_or_fail(r, steps);
    char msg[512];
    if (state_diff(s, r, msg, sizeof msg))
        fail_msg("packing at the stability bound, OpenCL against the reference: %s", msg);
    dem_destroy(r);
    dem_destroy(s);
}

/* 50 spheres (r 1 mm, E 10 MPa, restitution 0.1) stacked on a floor, each touching the next at zero overlap. With
 * restitution 0.5 the column still moved after 2e5 steps (kinetic energy 1e-11 J, falling about tenfold per 6e4
 * steps): a damper between neighbours damps the column's lowest mode, whose neighbours move nearly together, less and
 * less as the column gets longer. That is physics, not jitter; 0.1 brings it to rest within the short version. */
static dem_sim *column_build(void)
{
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.1, 0.4});
    for (int k = 0; k < 50; k++)
        dem_add_particle(s, (double[3]){0, 0, 0.001 + 0.002 * k}, NULL, 0.001, m);
    dem_add_wall(s, &(dem_wall){DEM_WALL_PLANE, m, {0, 0, 0}, {0, 0, 1}});
    dem_set_gravity(s, (double[3]){0, 0, -9.81});
    return finish(s, (double[3]){-0.01, -0.01, -0.01}, (double[3]){0.01, 0.01, 0.11}, 0.2);
}

static void test_resting_column(void **st)
{
    (void)st;
    /* the short version on the reference (50 particles: a step is a few microseconds there, launches cost more) */
    int lng = getenv("DEM_STABILITY_LONG") != NULL;
    long steps = lng ? 1000000 : 200000, half = lng ? steps / 2 : 140000;
    dem_sim *s = column_build();
    dem_config c = cfg_of(lng ? DEM_BACKEND_OPENCL : DEM_BACKEND_REFERENCE, DEM_FP64);
    start_or_fail(s, &c);
    double x[150], top0, top = 0, creep = 0, lateral = 0;
    step_or_fail(s, half); /* settling */
    assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
    top0 = x[149];
    for (long k = half; k < steps; k += (steps - half) / 10) { /* then ten looks at the height */
        step_or_fail(s, (steps - half) / 10);
        assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
        top = x[149];
        creep = fmax(creep, fabs(top - top0));
        for (int i = 0; i < 50; i++)
            lateral = fmax(lateral, fmax(fabs(x[3 * i]), fabs(x[3 * i + 1])));
    }
    dem_energy_t e;
    assert_int_equal(dem_energy(s, &e), 0);
    printf("  column of 50 on a floor, %s, %ld steps of %.3g s: top at %.9f m after %ld steps, moved at most %.3g m "
           "after that; kinetic energy %.3g J at the end; farthest off the axis %.3g m\n",
           lng ? "OpenCL" : "reference", steps, dem_dt(s), top0, half, creep, e.kinetic, lateral);
    assert_true(creep < 1e-9);
    assert_true(e.kinetic < 1e-15);
    assert_true(lateral == 0); /* nothing pushes sideways: the column stays on its axis exactly */
    assert_true(top0 < 0.099); /* the column did compress under its weight */
    dem_destroy(s);
    /* the other backend for its first 20 000 steps (the fall and the settling's start): the same bits */
    dem_sim *a = column_build(), *b = column_build();
    dem_config ca = cfg_of(DEM_BACKEND_OPENCL, DEM_FP64), cb = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    start_or_fail(a, &ca);
    start_or_fail(b, &cb);
    step_or_fail(a, 20000);
    step_or_fail(b, 20000);
    char msg[512];
    if (state_diff(a, b, msg, sizeof msg))
        fail_msg("resting column, OpenCL against the reference: %s", msg);
    dem_destroy(a);
    dem_destroy(b);
}

/* Lagged MC-strain on stiff glass (hard case 6). A scene under a model, on the reference in fp64, stepped through its
 * whole piston cycle (after the settling), sampled every 100 steps: the largest kinetic energy and when, and the
 * largest particle-pair overlap / smaller radius at the end of the compression stage. */
typedef struct {
    double ke_max, t_max, overlap, mean_overlap, t_end_compress;
    long steps;
    dem_state mid; /* the state where the kinetic energy peaked (for the bitwise check on PoCL) */
} lag_run;

static dem_sim *scene_model(const char *file, const char *model, scene **sc_out, scene_run *run)
{
    char err[4096], path[1024];
    snprintf(path, sizeof path, "%s/scenes/%s", DEM_DEFAULT_SOURCE_DIR, file);
    scene *sc = scene_load(path, err, sizeof err);
    if (!sc)
        fail_msg("%s", err);
    dem_sim *s = scene_build(sc, run, err, sizeof err);
    if (!s || scene_apply_model(sc, s, run, model, err, sizeof err))
        fail_msg("%s", err);
    *sc_out = sc;
    return s;
}

/* the largest pair overlap / smaller radius; *mean: its mean over the touching pairs */
static double largest_overlap(dem_sim *s, double *mean)
{
    int n = dem_count(s);
    double *x = malloc(sizeof(double) * 3 * (size_t)n), worst = 0, sum = 0;
    long touching = 0;
    assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n; j++) {
            double d[3] = {x[3 * j] - x[3 * i], x[3 * j + 1] - x[3 * i + 1], x[3 * j + 2] - x[3 * i + 2]};
            double ri = dem_particle_radius(s, i), rj = dem_particle_radius(s, j);
            double ov = (ri + rj - sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2])) / fmin(ri, rj);
            worst = fmax(worst, ov);
            if (ov > 0)
                sum += ov, touching++;
        }
    free(x);
    *mean = touching ? sum / touching : 0;
    return worst;
}

static lag_run lag_measure(const char *file, const char *model, int keep_state)
{
    scene *sc;
    scene_run run;
    dem_sim *s = scene_model(file, model, &sc, &run);
    dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    start_or_fail(s, &c);
    dem_wall w;
    dem_wall_get(s, run.piston, &w);
    long settle = lround(w.stages[0].duration / run.dt), compressed = settle + lround(w.stages[1].duration / run.dt);
    step_or_fail(s, settle);
    lag_run r = {0};
    for (long k = settle; k < run.steps;) {
        long n = k + 100 <= run.steps ? 100 : run.steps - k;
        if (k < compressed && k + n > compressed)
            n = compressed - k;
        step_or_fail(s, n);
        k += n;
        if (k == compressed) {
            r.overlap = largest_overlap(s, &r.mean_overlap);
            r.t_end_compress = compressed * run.dt;
        }
        dem_energy_t e;
        assert_int_equal(dem_energy(s, &e), 0);
        assert_true(isfinite(e.kinetic) && isfinite(e.elastic));
        if (e.kinetic > r.ke_max) {
            r.ke_max = e.kinetic, r.t_max = k * run.dt;
            if (keep_state) {
                if (r.mid.n)
                    dem_state_free(&r.mid);
                assert_int_equal(dem_state_get(s, &r.mid), 0);
            }
        }
    }
    r.steps = run.steps;
    dem_destroy(s);
    scene_free(sc);
    return r;
}

static void test_mc_lag(void **st)
{
    (void)st;
    /* the glass die (17 beads, gamma 4.5): where dem check warns */
    lag_run cl = lag_measure("glass_die.yaml", "classical", 0), lag = lag_measure("glass_die.yaml", "mc_strain", 1),
            it = lag_measure("glass_die.yaml", "mc_strain_iterated", 0);
    printf("  glass die, whole cycle (%ld steps, compression ends at %.4f s): largest kinetic energy classical %.3g J "
           "(at %.4f s), MC-strain lagged %.3g J (%.1fx, at %.4f s), iterated %.3g J (%.2fx); largest overlap at the "
           "end of the compression %.2f %% / %.2f %% / %.2f %% of a radius, mean %.2f %% / %.2f %% / %.2f %% (dem "
           "check: the lag's gain reaches 1 at 1.42 %%)\n", cl.steps, cl.t_end_compress, cl.ke_max, cl.t_max,
           lag.ke_max, lag.ke_max / cl.ke_max, lag.t_max, it.ke_max, it.ke_max / cl.ke_max, 100 * cl.overlap,
           100 * lag.overlap, 100 * it.overlap, 100 * cl.mean_overlap, 100 * lag.mean_overlap, 100 * it.mean_overlap);
    assert_true(lag.ke_max > 5 * cl.ke_max); /* lagged rings: what the warning says */
    assert_true(it.ke_max < 2 * cl.ke_max);  /* iterated does not */
    /* the criterion: the mean overlap passes the overlap where the lag's gain reaches 1 (run_mc_lag_advice) */
    assert_true(lag.mean_overlap > 0.0142 && it.mean_overlap > 0.0142 && lag.overlap < 0.1 && it.overlap < 0.1);
    /* the ringing state on PoCL: 2000 steps from the lagged run's state at its kinetic-energy peak, the reference's
     * bits */
    scene *sc;
    scene_run run;
    dem_sim *a = scene_model("glass_die.yaml", "mc_strain", &sc, &run), *b;
    scene_free(sc);
    b = scene_model("glass_die.yaml", "mc_strain", &sc, &run);
    scene_free(sc);
    dem_config ca = cfg_of(DEM_BACKEND_OPENCL, DEM_FP64), cb = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    start_or_fail(a, &ca);
    start_or_fail(b, &cb);
    assert_int_equal(dem_state_set(a, &lag.mid), 0);
    assert_int_equal(dem_state_set(b, &lag.mid), 0);
    step_or_fail(a, 2000);
    step_or_fail(b, 2000);
    char msg[512];
    if (state_diff(a, b, msg, sizeof msg))
        fail_msg("lagged MC-strain, glass die, OpenCL against the reference: %s", msg);
    dem_destroy(a);
    dem_destroy(b);
    dem_state_free(&lag.mid);
    /* the 514 hydrogels (gamma 1.12): no warning (the gain reaches 1 at 15.7 %), and lagged does not ring */
    lag_run hc = lag_measure("hydrogel_514.yaml", "classical", 0), hl = lag_measure("hydrogel_514.yaml", "mc_strain", 0);
    printf("  514 hydrogels, whole cycle (%ld steps): largest kinetic energy classical %.3g J, MC-strain lagged %.3g J "
           "(%.2fx); at 13.4 %% strain largest overlap %.2f %% / %.2f %% of a radius, mean %.2f %% / %.2f %% (the "
           "lag's gain reaches 1 at 15.7 %%)\n", hc.steps, hc.ke_max, hl.ke_max, hl.ke_max / hc.ke_max,
           100 * hc.overlap, 100 * hl.overlap, 100 * hc.mean_overlap, 100 * hl.mean_overlap);
    assert_true(hl.ke_max < 2 * hc.ke_max);
    assert_true(hl.mean_overlap < 0.157);
    /* dem check names delta_1 and warns for the glass die lagged, not iterated; an unknown model is a usage error */
    char dir[256], err[8192];
    assert_int_equal(test_tmpdir_make(dir, sizeof dir, "lag"), 0);
    const char *dem = DEM_DEFAULT_SOURCE_DIR "/build/dem", *glass = DEM_DEFAULT_SOURCE_DIR "/scenes/glass_die.yaml";
    assert_int_equal(test_sh(dir, err, sizeof err, "%s check %s --model mc_strain > %s/o.txt", dem, glass, dir), 0);
    assert_non_null(strstr(err, "lagged MC-strain on material 'glass'"));
    assert_non_null(strstr(err, "passes 1.42 % of a radius"));
    assert_int_equal(test_sh(dir, err, sizeof err, "{ grep -q 'at a mean overlap of 1.42 %%' %s/o.txt && %s check %s "
                                                   "--model mc_strain_iterated > /dev/null; }", dir, dem, glass), 0);
    assert_null(strstr(err, "warning"));
    assert_int_equal(test_sh(dir, err, sizeof err, "%s check %s --model lagged", dem, glass), 2);
    assert_non_null(strstr(err, "unknown model 'lagged'"));
    test_tmpdir_remove(dir);
}

/* Compaction to relative density 0.9 under each model (hard case 7). 300 soft spheres (r 0.3-0.4 mm, E 5 MPa,
 * prefactors beta 1.65 and gamma 1.12: seed 000's hydrogel calibration) placed at random in a die of radius 3 mm,
 * 32 % solid; the upper punch comes down at 0.1 m/s from the top of the fill without stopping. The run is stepped
 * until the spheres' volume over the die's volume between the punches (overlaps counted twice, as a press reports it)
 * passes 0.9. Every model must stay finite with every sphere inside the die between the punches and the kinetic
 * energy below the stored elastic energy; OpenCL has the reference's bits. Classical, MC-stress and iterated MC-strain
 * keep every pair overlap below the smaller radius all the way (no sphere's centre inside another); lagged MC-strain
 * does not (a pair at 105 % on the way): its contacts' mean overlap passes the overlap at which its loop gain reaches
 * 1, it rings, and dem check warns for this material (app/run.c, run_mc_lag_advice). */
static const char compaction_scene[] =
    "name: compaction to 0.9\n"
    "precision: fp64\n"
    "effects: [hertz, damping, friction, walls]\n"
    "materials:\n"
    "  - {name: powder, density: 1500, young: 5.0e6, poisson: 0.3, restitution: 0.2, friction: 0.3, beta: 1.65, "
    "gamma: 1.12}\n"
    "  - {name: steel, density: 7800, young: 2.0e11, poisson: 0.3, restitution: 0.5, friction: 0.3}\n"
    "particles:\n"
    "  - material: powder\n"
    "    generate: {kind: random, shape: cylinder, region: {base: [0, 0, 0], axis: [0, 0, 1], radius: 0.003, "
    "height: 0.006}, radius_min: 0.0003, radius_max: 0.0004, count: 300, seed: 5}\n"
    "walls:\n"
    "  - {type: cylinder, name: die, material: steel, point: [0, 0, -0.001], axis: [0, 0, 1], radius: 0.003}\n"
    "  - {type: plane, name: lower, material: steel, point: [0, 0, 0], normal: [0, 0, 1]}\n"
    "  - {type: plane, name: upper, material: steel, point: [0, 0, 0.006], normal: [0, 0, -1], "
    "motion: [{velocity: [0, 0, -0.1], duration: 0.06}]}\n"
    "domain: {lo: [-0.004, -0.004, -0.001], hi: [0.004, 0.004, 0.007]}\n"
    "time: {dt_rayleigh: 0.2, duration: 0.06}\n";

typedef struct {
    double density, overlap, mean_overlap, ke, elastic;
    long steps;
    int escaped;
} compaction_result;

static dem_sim *compaction_build(const char *model)
{
    char err[4096];
    scene *sc = scene_load_text("compaction.yaml", compaction_scene, sizeof compaction_scene - 1, err, sizeof err);
    if (!sc)
        fail_msg("%s", err);
    scene_run run;
    dem_sim *s = scene_build(sc, &run, err, sizeof err);
    if (!s || scene_apply_model(sc, s, &run, model, err, sizeof err))
        fail_msg("%s", err);
    scene_free(sc);
    return s;
}

static compaction_result compaction_run(dem_sim *s, long max_steps)
{
    int n = dem_count(s);
    double *x = malloc(sizeof(double) * 3 * (size_t)n), vs = 0;
    for (int i = 0; i < n; i++)
        vs += 4.0 / 3.0 * M_PI * pow(dem_particle_radius(s, i), 3);
    compaction_result r = {0};
    while (r.density < 0.9 && r.steps < max_steps) {
        step_or_fail(s, 20);
        r.steps += 20;
        double up[3], lo[3];
        dem_wall_position(s, 2, up);
        dem_wall_position(s, 1, lo);
        r.density = vs / (M_PI * 0.003 * 0.003 * (up[2] - lo[2]));
        assert_int_equal(dem_get_field(s, DEM_FIELD_X, x), 0);
        for (int i = 0; i < n; i++) {
            double rho = hypot(x[3 * i], x[3 * i + 1]);
            if (!isfinite(x[3 * i] + x[3 * i + 1] + x[3 * i + 2]) || rho > 0.003 || x[3 * i + 2] < lo[2] ||
                x[3 * i + 2] > up[2])
                r.escaped++;
        }
        r.overlap = fmax(r.overlap, largest_overlap(s, &r.mean_overlap));
    }
    dem_energy_t e;
    assert_int_equal(dem_energy(s, &e), 0);
    r.ke = e.kinetic, r.elastic = e.elastic;
    free(x);
    return r;
}

static void test_compaction_09(void **st)
{
    (void)st;
    static const char *const models[] = {"classical", "mc_stress", "mc_strain", "mc_strain_iterated"};
    for (int m = 0; m < 4; m++) {
        dem_sim *ref = compaction_build(models[m]), *cl = compaction_build(models[m]);
        dem_config rc = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64), c = cfg_of(DEM_BACKEND_OPENCL, DEM_FP64);
        start_or_fail(ref, &rc);
        compaction_result r = compaction_run(ref, 12000);
        printf("  compaction, %-18s: relative density %.3f after %ld steps; largest overlap %.1f %% of the smaller "
               "radius (mean %.1f %% at the end); kinetic %.3g J, elastic %.3g J; %d outside the die\n", models[m],
               r.density, r.steps, 100 * r.overlap, 100 * r.mean_overlap, r.ke, r.elastic, r.escaped);
        assert_true(r.density >= 0.9);
        assert_int_equal(r.escaped, 0);
        if (m == 2) /* lagged MC-strain rings here: the contacts' mean overlap passed where its gain reaches 1, and
                       dem check warns for this material (run_mc_lag_advice); its overlaps are not bounded */
            assert_true(r.mean_overlap > run_mc_lag_overlap(1.12, 0.3) && run_mc_lag_overlap(1.12, 0.3) < 0.25);
        else
            assert_true(r.overlap < 1);
        assert_true(isfinite(r.ke) && r.ke < r.elastic);
        start_or_fail(cl, &c);
        step_or_fail(cl, r.steps);
        char msg[512];
        if (state_diff(cl, ref, msg, sizeof msg))
            fail_msg("compaction, %s, OpenCL against the reference: %s", models[m], msg);
        dem_destroy(ref);
        dem_destroy(cl);
    }
}

#define LAT_R 5e-5
#define LAT_N 4
/* The lattice of the stability estimate: spacing 2 r (1 - ov / 2), the box 2^(-1/3) of that overlap from the outer
 * spheres (a Hertz wall contact, r* = r, carries the pairs' force there), positions nudged by 1e-3 ov r at random */
static dem_sim *lattice_build(double ov, double restitution, double *spacing)
{
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){1540, 2.87e9, 0.381, restitution, 0.719, 0, 0});
    double a = 2 * LAT_R * (1 - ov / 2), edge = LAT_R * (1 - ov / 2 * cbrt(0.5)), L = (LAT_N - 1) * a + 2 * edge;
    unsigned st = 7;
    for (int k = 0; k < LAT_N; k++)
        for (int j = 0; j < LAT_N; j++)
            for (int i = 0; i < LAT_N; i++) {
                double x[3] = {edge + i * a, edge + j * a, edge + k * a};
                for (int q = 0; q < 3; q++)
                    x[q] += 1e-3 * ov * LAT_R * (uniform01(&st) - 0.5);
                dem_add_particle(s, x, NULL, LAT_R, m);
            }
    dem_add_box(s, (double[3]){0, 0, 0}, (double[3]){L, L, L}, m);
    dem_set_domain(s, (double[3]){-LAT_R, -LAT_R, -LAT_R}, (double[3]){L + LAT_R, L + LAT_R, L + LAT_R});
    *spacing = a;
    return s;
}

/* kinetic over elastic energy after `steps` steps of dt */
static double lattice_heat(double dt, long steps)
{
    double a;
    dem_sim *s = lattice_build(0.1, 0.1, &a);
    assert_int_equal(dem_set_dt(s, dt), 0);
    dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    start_or_fail(s, &c);
    step_or_fail(s, steps);
    dem_energy_t e;
    assert_int_equal(dem_energy(s, &e), 0);
    dem_destroy(s);
    return e.kinetic / e.elastic;
}

static void test_stability_estimate(void **st)
{
    (void)st;
    double a, ratio = 0;
    for (int b = 0; b < BACKEND_CASES; b++) {
        const backend_case *bc = &backend_cases[b];
        dem_sim *s = lattice_build(0.1, 0.1, &a);
        dem_time_scales ts;
        dem_time_scales_get(s, 0, &ts);
        assert_int_equal(dem_set_dt(s, 0.05 * ts.rayleigh_time), 0);
        dem_config c = cfg_of(bc->backend, bc->precision);
        start_or_fail(s, &c);
        step_or_fail(s, 1);
        dem_stability sb;
        assert_int_equal(dem_stability_get(s, &sb), 0);
        /* an inner sphere: six contacts at overlap 2 r - a, each of r* = r/2, m* = m/2, lever r - d/2 */
        double m = 1540 * 4.0 / 3 * M_PI * pow(LAT_R, 3), I = 0.4 * m * LAT_R * LAT_R, d = 2 * LAT_R - a;
        double gstar = 2.87e9 / (2 * 1.381) / (2 * (2 - 0.381));
        double srd = sqrt(LAT_R / 2 * d), kt = 8 * gstar * srd, arm = LAT_R - d / 2;
        double inv = 2 / m + 2 * arm * arm / I, w = sqrt(6 * kt * inv) * dem_dt(s);
        double zeta = dem_damping_for_restitution(0.1) / 2 * sqrt(inv / (2 / m));
        double want = w / (2 * (sqrt(1 + zeta * zeta) - zeta));
        printf("  lattice of %d spheres at 10 %% overlap, %s, 0.05 Rayleigh times: ratio %.4g (closed form %.4g), "
               "particle %d, %d contacts, omega dt %.4g, zeta %.4g; advice %.3g s\n", dem_count(s), bc->name,
               sb.ratio, want, sb.particle, sb.contacts, sb.omega_dt, sb.zeta, sb.dt_advice);
        assert_int_equal(sb.contacts, 6);
        assert_int_equal(sb.tangential, 1);
        assert_true(fabs(sb.ratio / want - 1) < 1e-2); /* the nudge moves it by about 1e-4 */
        assert_true(fabs(sb.dt_advice - dem_dt(s) * DEM_STABILITY_TARGET / sb.ratio) < 1e-12 * sb.dt_advice);
        if (b == 0)
            ratio = sb.ratio;
        else /* the same positions, so in fp64 the same estimate; fp32's positions differ by their rounding */
            assert_true(fabs(sb.ratio / ratio - 1) < (bc->precision == DEM_FP64 ? 1e-15 : 1e-5));
        dem_destroy(s);
    }
    dem_sim *s = lattice_build(0.1, 0.1, &a);
    dem_time_scales ts;
    dem_time_scales_get(s, 0, &ts);
    double advice = 0.05 * ts.rayleigh_time * DEM_STABILITY_TARGET / ratio;
    dem_destroy(s);
    double calm = lattice_heat(0.7 * advice, 3000), stirred = lattice_heat(2 * advice, 3000);
    printf("  kinetic / elastic energy after 3000 steps: %.3g at 0.7 of the advice, %.3g at twice it\n", calm, stirred);
    assert_true(calm < 1e-20);
    assert_true(stirred > 1e-9);

    s = dem_create(); /* a lone sphere: nothing to estimate */
    int mat = dem_add_material(s, &(dem_material){1540, 2.87e9, 0.381, 0.1, 0.719, 0, 0});
    dem_add_particle(s, (double[3]){0, 0, 0}, NULL, LAT_R, mat);
    dem_set_domain(s, (double[3]){-1e-3, -1e-3, -1e-3}, (double[3]){1e-3, 1e-3, 1e-3});
    dem_set_dt(s, 1e-8);
    dem_config c = cfg_of(DEM_BACKEND_REFERENCE, DEM_FP64);
    start_or_fail(s, &c);
    step_or_fail(s, 1);
    dem_stability sb;
    assert_int_equal(dem_stability_get(s, &sb), 0);
    assert_int_equal(sb.particle, -1);
    assert_true(sb.ratio == 0 && isinf(sb.dt_advice));
    dem_destroy(s);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_size_ratio), cmocka_unit_test(test_stiffness_contrast),
                                       cmocka_unit_test(test_elastic_gas), cmocka_unit_test(test_dt_at_bound),
                                       cmocka_unit_test(test_resting_column), cmocka_unit_test(test_mc_lag),
                                       cmocka_unit_test(test_compaction_09), cmocka_unit_test(test_stability_estimate)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
