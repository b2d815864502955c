/* bench.c - `make bench`: particle-steps per second of a dense Hertz-Mindlin packing (frictional, damped, gravity,
 * box of 6 walls), for the reference and every OpenCL device, fp32 and fp64, at N ~ 1e3, 1e4, 1e5, with the time
 * spent in each kernel. Prints markdown tables. Not a test: nothing here passes or fails on speed.
 *   DEM_BENCH_SIZES="8 17 37"   lattice sides (n = side^3 + (side-1)^3), default as shown
 *   DEM_BENCH_QUICK=1           fewer steps
 *   DEM_BENCH_ONLY=models       only the contact model cost table (or: bed, effects, series, sizes, membranes)
 *   DEM_BENCH_BED=FILE.csv      the poured bed of the bed table (default out/peer/bed.csv, made by make bench-peer)
 *   DEM_BENCH_JSON=FILE         where the bed table's figures go as JSON (default out/bench_bed.json)
 *   DEM_BENCH_TRIAXIAL_MS=2     simulated milliseconds of each triaxial run in the membrane cost table
 *   DEM_BENCH_SKIN=1.8e-4       a fixed neighbour skin [m] for the bed table (default: the automatic one)
 *   DEM_BENCH_CONFORM=FILE      `dem conform`'s output on device 0, whose summary the bed table's JSON records
 * Then more tables: what an effect that is off costs (effects_table), what each contact model costs on seed 000's
 * compression scenes (model_cost_table, the paper's Table 2), what the time series cost (series_cost_table) and what
 * each membrane model costs in seed 001's triaxial test (membrane_cost_table, the paper's Table 4). */
#include "dem.h"
#include "dem_debug.h" /* kernel times, sequence, bytes, build info */
#include "cl_util.h"
#include <math.h>
#include <stdio.h>
#include <sys/resource.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

/* Large spheres (r 0.97-1 mm) on a cubic lattice of spacing 1.96 mm, so that each presses on its 6 neighbours,
 * held by the box walls; small ones (0.45-0.5 mm) rattle in the body centres. Solid fraction ~0.6, radius ratio
 * > 2, a steady contact network from the first step (the table reports contacts per particle). Glass-like density,
 * E = 10 MPa, mu 0.4, e 0.6, gravity. */
static double bench_mu = 0.4;
static unsigned bench_effects = DEM_EFFECT_CLASSICAL;

static dem_sim *packing(int side)
{
    dem_sim *s = dem_create();
    dem_set_effects(s, bench_effects);
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.6, bench_mu});
    double a = 1.96e-3, L = side * a;
    unsigned st = 1;
    for (int layer = 0; layer < 2; layer++) {
        int q = side - layer;
        for (int i = 0; i < q * q * q; i++) {
            double off = layer ? 1.0 : 0.5;
            double x[3] = {(i % q + off) * a, (i / q % q + off) * a, (i / (q * q) + off) * a}, v[3];
            for (int d = 0; d < 3; d++) {
                st = st * 1664525u + 1013904223u;
                v[d] = 0.1 * ((st >> 8) / 8388608.0 - 1);
            }
            st = st * 1664525u + 1013904223u;
            double u = (st >> 8) / 16777216.0;
            dem_add_particle(s, x, v, layer ? 0.45e-3 + 0.05e-3 * u : 0.97e-3 + 0.03e-3 * u, m);
        }
    }
    dem_add_box(s, (double[3]){0, 0, 0}, (double[3]){L, L, L}, m);
    dem_set_gravity(s, (double[3]){0, 0, -9.81});
    dem_set_domain(s, (double[3]){-0.1 * L, -0.1 * L, -0.1 * L}, (double[3]){1.1 * L, 1.1 * L, 1.1 * L});
    dem_time_scales ts;
    dem_time_scales_get(s, 0, &ts);
    dem_set_dt(s, ts.recommended_dt);
    return s;
}

typedef struct {
    double rate, contacts; /* contacts per particle at the end, walls included */
    char desc[256];
    char kernels[1024];
} result;

static int run(int side, dem_backend_kind kind, int device, dem_precision prec, long steps, int profile, result *r)
{
    if (profile)
        setenv("DEM_PROFILE", "1", 1);
    else
        unsetenv("DEM_PROFILE");
    dem_sim *s = packing(side);
    dem_config c;
    dem_config_default(&c);
    c.backend = kind;
    c.device = device;
    c.precision = prec;
    if (getenv("DEM_LOCAL_SIZE")) /* default: dem_config_default's */
        c.local_size = (size_t)atol(getenv("DEM_LOCAL_SIZE"));
    if (dem_start(s, &c) || dem_step(s, 20)) { /* warm-up: the first steps settle the lattice */
        snprintf(r->desc, sizeof r->desc, "%s", dem_error(s));
        dem_destroy(s);
        return 1;
    }
    const char **names;
    const double *secs0;
    int cnt;
    double before[64] = {0};
    dem_kernel_times(s, &names, &secs0, &cnt);
    for (int k = 0; k < cnt && k < 64; k++)
        before[k] = secs0[k];
    long rb = dem_rebuild_count(s);
    double t0 = now();
    int e = dem_step(s, steps);
    double t = now() - t0;
    if (e) {
        snprintf(r->desc, sizeof r->desc, "%s", dem_error(s));
        dem_destroy(s);
        return 1;
    }
    r->rate = (double)dem_count(s) * steps / t;
    dem_energy_t en;
    dem_energy(s, &en);
    r->contacts = (2.0 * en.contacts + en.wall_contacts) / dem_count(s);
    snprintf(r->desc, sizeof r->desc, "%s", dem_describe(s));
    r->kernels[0] = 0;
    dem_kernel_times(s, &names, &secs0, &cnt);
    size_t len = 0;
    for (int k = 0; k < cnt && k < 64; k++) {
        double us = 1e6 * (secs0[k] - before[k]) / steps;
        if (us >= 0.05)
            len += (size_t)snprintf(r->kernels + len, sizeof r->kernels - len, "%s%s %.1f", len ? ", " : "", names[k],
                                    us);
        if (len >= sizeof r->kernels)
            break;
    }
    fprintf(stderr, "  n %d: %ld steps in %.2f s, %ld rebuilds\n", dem_count(s), steps, t, dem_rebuild_count(s) - rb);
    dem_destroy(s);
    return 0;
}

/* What an effect that is off costs: friction on at mu = 0.4, on at mu = 0 (its code runs, to no effect), and off
 * (DEM_EFFECT_FRICTION not in the mask: its code is not compiled into the kernels and its history not allocated).
 * The three are interleaved and repeated; the best rate of each is reported (this VM's timings are noisy). */
static void effects_table(int quick)
{
    int side = quick ? 12 : 17, n = side * side * side + (side - 1) * (side - 1) * (side - 1);
    long steps = quick ? 200 : 1000;
    struct {
        const char *name;
        double mu;
        unsigned fx;
        double best;
    } v[3] = {{"friction on, mu 0.4", 0.4, DEM_EFFECT_CLASSICAL, 0},
              {"friction on, mu 0 (code present)", 0, DEM_EFFECT_CLASSICAL, 0},
              {"friction off (code compiled out)", 0, DEM_EFFECT_CLASSICAL & ~(unsigned)DEM_EFFECT_FRICTION, 0}};
    for (int rep = 0; rep < 3; rep++)
        for (int k = 0; k < 3; k++) {
            result r;
            bench_mu = v[k].mu;
            bench_effects = v[k].fx;
            if (run(side, DEM_BACKEND_OPENCL, 0, DEM_FP64, steps, 0, &r) == 0 && r.rate > v[k].best)
                v[k].best = r.rate;
        }
    bench_mu = 0.4;
    bench_effects = DEM_EFFECT_CLASSICAL;
    printf("\n## Effects on demand (n = %d, OpenCL device 0, fp64, best of 3 interleaved runs)\n\n"
           "| variant | particle-steps/s | relative to friction off |\n|---|---|---|\n", n);
    for (int k = 0; k < 3; k++)
        printf("| %s | %.3g | %.3f |\n", v[k].name, v[k].best, v[k].best / v[2].best);
}

/* Seed 000's Table 2, side by side in one run: wall time of whole `dem run` scenes (set-up, output and checkpoints
 * included, as the paper's figures are whole runs) per contact model, and the ratio to classical DEM. The models
 * are interleaved; the best of `reps` runs of each is kept (this VM's timings vary by tens of percent from run to
 * run), except for the slow iterated MC-strain, run once. */
static double time_run(const char *scene, const char *model)
{
    char cmd[2048];
    snprintf(cmd, sizeof cmd, "%s/build/dem run %s/scenes/%s.yaml --model %s -o /tmp/dem-bench-%s.h5 --quiet",
             DEM_DEFAULT_SOURCE_DIR, DEM_DEFAULT_SOURCE_DIR, scene, model, model);
    double t0 = now();
    int rc = system(cmd);
    return rc == 0 ? now() - t0 : NAN;
}

/* A scene's time step and particle count, as `dem check` prints them */
static double scene_dt(const char *yaml, long *n)
{
    char cmd[1024], line[512];
    double dt = NAN;
    snprintf(cmd, sizeof cmd, "%s/build/dem check %s 2>/dev/null", DEM_DEFAULT_SOURCE_DIR, yaml);
    FILE *fp = popen(cmd, "r");
    while (fp && fgets(line, sizeof line, fp)) {
        if (!strncmp(line, "time step", 9))
            sscanf(line, "time step %lf", &dt);
        if (!strncmp(line, "particles", 9))
            sscanf(line, "particles %ld", n);
    }
    if (fp)
        pclose(fp);
    return dt;
}

/* The cost of the time series: 514 hydrogel spheres, 5000 steps of their compression, a row every 100
 * steps against a row every step, and a row every 100 steps each the mean of those 100 (series_average). */
/* the CPU seconds of the children waited for so far (user + system) */
static double children_cpu(void)
{
    struct rusage u;
    getrusage(RUSAGE_CHILDREN, &u);
    return (double)u.ru_utime.tv_sec + (double)u.ru_stime.tv_sec + 1e-6 * (double)(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

/* wall and CPU time of a 5000-step run of the hydrogel compression with the given series settings */
static double time_series_run(const char *series_every, const char *extra, double *cpu)
{
    char cmd[4096];
    snprintf(cmd, sizeof cmd,
             "sed -e 's|csv: data/|csv: %s/scenes/data/|' -e 's|^  series_every:.*|  series_every: %s%s|' "
             "%s/scenes/hydrogel_514.yaml > /tmp/dem-bench-series.yaml && %s/build/dem run /tmp/dem-bench-series.yaml "
             "-o /tmp/dem-bench-series.h5 --quiet --stop-after 5000 2>/dev/null",
             DEM_DEFAULT_SOURCE_DIR, series_every, extra, DEM_DEFAULT_SOURCE_DIR, DEM_DEFAULT_SOURCE_DIR);
    double t0 = now(), c0 = children_cpu();
    int rc = system(cmd);
    *cpu = rc == 0 ? children_cpu() - c0 : NAN;
    return rc == 0 ? now() - t0 : NAN;
}

static int cmp_double(const void *a, const void *b) /* a failed run's NaN sorts last */
{
    double x = *(const double *)a, y = *(const double *)b;
    if (isnan(x) || isnan(y))
        return isnan(x) - isnan(y);
    return (x > y) - (x < y);
}

static void series_cost_table(int quick)
{
    const char *every[3] = {"1.0e-9", "1.0e-9", "1.0e-9"}, *extra[3] = {"", "", "\\n  series_average: 100"};
    const char *names[3] = {"a row every 100 steps", "a row every step", "a row every 100 steps, each the mean of 100"};
    /* series_every in steps: 1e-9 s rounds up to every step; 100 steps from the scene's own dt (dem check) */
    char hundred[64];
    long n;
    double dt = scene_dt(DEM_DEFAULT_SOURCE_DIR "/scenes/hydrogel_514.yaml", &n);
    snprintf(hundred, sizeof hundred, "%.17g", 100 * dt);
    every[0] = every[2] = hundred;
    /* interleaved rounds: this kind of machine's wall times vary by 10-20 % from run to run, and a slow spell can
     * last a whole round of the best-of times; each round's runs against that round's first run, the median of those
     * ratios, are steadier */
    enum { MAXREPS = 11 };
    int reps = quick ? 1 : MAXREPS;
    double best[3] = {INFINITY, INFINITY, INFINITY}, cbest[3] = {INFINITY, INFINITY, INFINITY};
    double ratio[3][MAXREPS], cratio[3][MAXREPS], t0 = 0, c0 = 0;
    for (int r = 0; r < reps; r++)
        for (int k = 0; k < 3; k++) {
            double c, t = time_series_run(every[k], extra[k], &c);
            best[k] = t < best[k] ? t : best[k];
            cbest[k] = c < cbest[k] ? c : cbest[k];
            if (k == 0)
                t0 = t, c0 = c;
            ratio[k][r] = t / t0;
            cratio[k][r] = c / c0;
        }
    printf("\n## Time-series cost (hydrogel_514, 5000 steps of its compression on OpenCL device 0, whole `dem run`s, "
           "%d interleaved rounds: the best times, and the median over the rounds of each run against the same round's "
           "run with a row every 100 steps; target: a row every step within 10 %% of a row every 100)\n\n| series | wall "
           "time [s] | over every 100 steps | CPU time [s] | over every 100 steps |\n|---|---|---|---|---|\n",
           reps);
    for (int k = 0; k < 3; k++) {
        qsort(ratio[k], (size_t)reps, sizeof(double), cmp_double);
        qsort(cratio[k], (size_t)reps, sizeof(double), cmp_double);
        printf("| %s | %.2f | %+.0f %% | %.2f | %+.0f %% |\n", names[k], best[k], 100 * (ratio[k][reps / 2] - 1), cbest[k],
               100 * (cratio[k][reps / 2] - 1));
    }
}

/* Hard case: a size ratio of 20:1 against equal spheres, particle-steps/s on OpenCL device 0 in fp64. The
 * mix: 64 coarse spheres (r 2 mm) on a 5 mm lattice in a 20 mm box and 4000 fines (r 0.1 mm) on the free sites of
 * a 0.5 mm lattice, taken in a scrambled order; the equal case: 4064 fines alone on those sites. Both fly at up to
 * 0.5 m/s per component in the closed box, no gravity, for 2000 steps at the mix's own time step. The binning cells
 * are sized by the largest spheres, so in the mix each fine looks at every fine within a coarse cell. */
static double size_ratio_rate(int mixed, long *rebuilds)
{
    dem_sim *s = dem_create();
    int m = dem_add_material(s, &(dem_material){2500, 1e7, 0.3, 0.5, 0.4});
    unsigned st = 7;
    int nc = 0;
    if (mixed)
        for (int i = 0; i < 64; i++, nc++)
            dem_add_particle(s, (double[3]){2.5e-3 + 5e-3 * (i % 4), 2.5e-3 + 5e-3 * (i / 4 % 4), 2.5e-3 + 5e-3 * (i / 16)},
                             NULL, 2e-3, m);
    int want = mixed ? 4000 : 4064, got = 0;
    for (long k = 0; got < want && k < 40L * 40 * 40 * 8; k++) {
        long site = (k * 40503L) % (40L * 40 * 40); /* a scrambled walk over the 0.5 mm lattice (40503 is odd) */
        double x[3] = {0.25e-3 + 0.5e-3 * (double)(site % 40), 0.25e-3 + 0.5e-3 * (double)(site / 40 % 40),
                       0.25e-3 + 0.5e-3 * (double)(site / 1600)};
        int clear = 1;
        for (int c = 0; mixed && clear && c < nc; c++) {
            double dx = x[0] - (2.5e-3 + 5e-3 * (c % 4)), dy = x[1] - (2.5e-3 + 5e-3 * (c / 4 % 4)),
                   dz = x[2] - (2.5e-3 + 5e-3 * (c / 16));
            clear = dx * dx + dy * dy + dz * dz > 2.2e-3 * 2.2e-3;
        }
        if (!clear || k >= 40L * 40 * 40)
            continue;
        double v[3];
        for (int d = 0; d < 3; d++) {
            st = st * 1664525u + 1013904223u;
            v[d] = 0.5 * ((double)(st >> 8) / 16777216.0 * 2 - 1);
        }
        dem_add_particle(s, x, v, 1e-4, m);
        got++;
    }
    dem_add_box(s, (double[3]){0, 0, 0}, (double[3]){0.02, 0.02, 0.02}, m);
    dem_set_domain(s, (double[3]){-0.001, -0.001, -0.001}, (double[3]){0.021, 0.021, 0.021});
    dem_time_scales ts;
    dem_time_scales_get(s, 0, &ts);
    dem_set_dt(s, ts.recommended_dt);
    dem_config c;
    dem_config_default(&c);
    double rate = NAN;
    if (!dem_start(s, &c) && !dem_step(s, 10)) {
        double t0 = now();
        if (!dem_step(s, 2000))
            rate = 2000.0 * dem_count(s) / (now() - t0);
    }
    *rebuilds = dem_rebuild_count(s);
    dem_destroy(s);
    return rate;
}

static void size_ratio_table(void)
{
    long rb[2];
    double mix = size_ratio_rate(1, &rb[0]), equal = size_ratio_rate(0, &rb[1]);
    printf("\n## Size ratio 20:1 (hard case 2; 2000 steps on OpenCL device 0, fp64; target: within 2x of "
           "equal spheres)\n\n| packing | particles | particle-steps/s | rebuilds |\n|---|---|---|---|\n"
           "| 64 coarse (2 mm) + 4000 fines (0.1 mm) | 4064 | %.3g | %ld |\n| 4064 fines alone | 4064 | %.3g | %ld |\n"
           "\nthe mix costs %.1fx per particle-step\n", mix, rb[0], equal, rb[1], equal / mix);
}

static void model_cost_table(int quick)
{
    static const char *scenes[] = {"hydrogel_514", "glass_die"};
    static const char *models[] = {"classical", "mc_stress", "mc_strain", "mc_strain_iterated"};
    int reps = quick ? 1 : 5;
    double best[2][4];
    for (int s = 0; s < 2; s++)
        for (int m = 0; m < 4; m++)
            best[s][m] = INFINITY;
    for (int rep = 0; rep < reps; rep++)
        for (int s = 0; s < 2; s++)
            for (int m = 0; m < 4; m++) {
                if (m == 3 && rep > 0)
                    continue;
                double t = time_run(scenes[s], models[m]);
                fprintf(stderr, "  %s %s: %.2f s\n", scenes[s], models[m], t);
                if (t < best[s][m])
                    best[s][m] = t;
            }
    printf("\n## Contact model cost (seed 000 Table 2; whole dem run, best of %d; hydrogel_514 on OpenCL device 0, "
           "glass_die on the reference backend as its scene says; MC-strain iterated to 1e-6, at most 20, run once)\n\n"
           "| model | hydrogel_514 [s] | ratio | glass_die [s] | ratio | paper (LIGGGHTS) hydrogel / glass ratio |\n"
           "|---|---|---|---|---|---|\n", reps);
    static const char *paper[] = {"1 / 1", "5.7 / 1.3", "17.6 / 2.0 (one pass)", "(not in the paper)"};
    for (int m = 0; m < 4; m++)
        printf("| %s | %.2f | %.2f | %.2f | %.2f | %s |\n", models[m], best[0][m], best[0][m] / best[0][0], best[1][m],
               best[1][m] / best[1][0], paper[m]);
}

/* Seed 001's Table 4: the wall time of 20 ms of simulated time of the triaxial test, both membrane models, both
 * cases, on OpenCL device 0 and on the reference. Whole `dem run`s of scenes/seed001/triaxial_case*_*.yaml (set-up
 * included) cut by --stop-after to `ms` milliseconds of their time step, and a run of one step for the set-up; the
 * table gives the set-up plus 20 ms of steps at the cost per step measured (steady: the packing is dense from the
 * first step). DEM_BENCH_TRIAXIAL_MS sets `ms` (default 2, quick 0.5; 20 runs the whole 20 ms: about an hour on 2
 * cores). */
static void membrane_cost_table(int quick)
{
    const char *env = getenv("DEM_BENCH_TRIAXIAL_MS");
    double ms = env ? atof(env) : quick ? 0.5 : 2;
    static const char *models[2] = {"particle", "patch"};
    static const double paper[2][2] = {{32, 96}, {5, 17}}; /* MercuryDPM [min]: [model][case] */
    double t[2][2][2]; /* [case][model][reference] [s] for 20 ms */
    long n[2][2] = {{0, 0}, {0, 0}}, steps[2][2];
    double dts[2][2];
    for (int c = 0; c < 2; c++)
        for (int m = 0; m < 2; m++) {
            char yaml[1024], cmd[4096];
            snprintf(yaml, sizeof yaml, "/tmp/dem-bench-tri-%d-%s.yaml", c + 1, models[m]);
            snprintf(cmd, sizeof cmd, "sed 's|csv: ../data/|csv: %s/scenes/data/|' %s/scenes/seed001/triaxial_case%d_%s.yaml "
                     "> %s", DEM_DEFAULT_SOURCE_DIR, DEM_DEFAULT_SOURCE_DIR, c + 1, models[m], yaml);
            double dt = system(cmd) == 0 ? scene_dt(yaml, &n[c][m]) : NAN;
            steps[c][m] = isfinite(dt) ? lround(ms * 1e-3 / dt) : 0;
            for (int r = 0; r < 2; r++) {
                t[c][m][r] = NAN;
                if (steps[c][m] < 2)
                    continue;
                double took[2] = {NAN, NAN}; /* one step (the set-up), then all */
                for (int q = 0; q < 2; q++) {
                    snprintf(cmd, sizeof cmd, "%s%s && %s/build/dem run %s -o /tmp/dem-bench-tri.h5 --quiet "
                             "--stop-after %ld", r && !q ? "echo 'backend: reference' >> " : "true", r && !q ? yaml : "",
                             DEM_DEFAULT_SOURCE_DIR, yaml, q ? steps[c][m] : 1);
                    double t0 = now();
                    if (system(cmd) == 0)
                        took[q] = now() - t0;
                }
                /* the set-up, and the steps of 20 ms at the measured cost per step */
                t[c][m][r] = took[0] + (took[1] - took[0]) / (double)(steps[c][m] - 1) * (lround(0.02 / dt) - 1);
                fprintf(stderr, "  triaxial case %d %s %s: set-up and a step %.1f s, %ld steps %.1f s: %.1f s for 20 ms\n",
                        c + 1, models[m], r ? "reference" : "opencl", took[0], steps[c][m], took[1], t[c][m][r]);
            }
            dts[c][m] = dt;
        }
    printf("\n## Membrane cost (seed 001 Table 4: wall time of 20 ms of the triaxial test; measured over %g ms of "
           "simulated time%s; OpenCL device 0 and the reference)\n\n"
           "| case | model | particles | time step [s] | OpenCL [min] | reference [min] | paper, MercuryDPM [min] |\n"
           "|---|---|---|---|---|---|---|\n", ms, ms < 20 ? ": the set-up (a run of one step) plus 20 ms of steps at the cost per step measured" : "");
    for (int c = 0; c < 2; c++)
        for (int m = 0; m < 2; m++)
            printf("| %d | MSS_%s | %ld | %.3g | %.2f | %.2f | %g |\n", c + 1, models[m], n[c][m],
                   dts[c][m], t[c][m][0] / 60, t[c][m][1] / 60, paper[m][c]);
    for (int c = 0; c < 2; c++)
        printf("| %d | ratio MSS_particle / MSS_patch | | | %.1f | %.1f | %.1f |\n", c + 1, t[c][0][0] / t[c][1][0],
               t[c][0][1] / t[c][1][1], paper[0][c] / paper[1][c]);
}

/* ---- Throughput on a poured polydisperse bed, the input users have ----
 * make bench-peer pours 100 000 spheres (r 0.6 / 0.8 / 1.0 mm at 30 / 40 / 30 %) into a 0.1 x 0.1 m box and saves
 * them as out/peer/bed.csv in the order the pour generated them (random placement: spatially random, as data from
 * another code arrives). The sizes below are that bed cut to a smaller square (the spheres wholly inside it, walls on
 * its sides) and, for 1e6, tiled 5 x 2 times (copies side by side; the small overlaps where the copies meet are of
 * the order of the wall contacts'). Physics of the peer comparison: rho 2500, E 5 MPa, nu 0.3, e 0.3, mu 0.5, walls
 * of the same material, gravity, dt 2e-6 s. Each size as poured and sorted along a Morton curve (dem_sort_particles,
 * a scene's particle_order: spatial). Per size: particle-steps/s of PoCL (fp64, fp32) and the reference, the
 * device memory per particle, the time per kernel, and the state after the timed steps hashed on each backend: the
 * OpenCL hash must equal the reference's (checked up to 1e5 particles; the reference is too slow beyond). */
typedef struct {
    double *p; /* x, y, z, r per sphere */
    long n;
} bed_t;

static int bed_read(const char *path, bed_t *b)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return 1;
    char line[1024];
    int col[4] = {-1, -1, -1, -1}, hdr = 0;
    long cap = 0;
    b->p = NULL, b->n = 0;
    while (fgets(line, sizeof line, f)) {
        if (line[0] == '#' || line[0] == '\n')
            continue;
        char *tok, *save;
        if (!hdr) { /* header: column names */
            int c = 0;
            for (tok = strtok_r(line, ", \t\r\n", &save); tok; tok = strtok_r(NULL, ", \t\r\n", &save), c++) {
                const char *names[4] = {"x", "y", "z", "radius"};
                for (int k = 0; k < 4; k++)
                    if (!strcmp(tok, names[k]))
                        col[k] = c;
            }
            hdr = 1;
            if (col[0] < 0 || col[1] < 0 || col[2] < 0 || col[3] < 0)
                break;
            continue;
        }
        double v[4] = {0};
        int c = 0;
        for (tok = strtok_r(line, ", \t\r\n", &save); tok; tok = strtok_r(NULL, ", \t\r\n", &save), c++)
            for (int k = 0; k < 4; k++)
                if (c == col[k])
                    v[k] = atof(tok);
        if (b->n == cap) {
            cap = cap ? 2 * cap : 4096;
            double *np = realloc(b->p, sizeof(double) * 4 * (size_t)cap);
            if (!np) {
                free(b->p), fclose(f);
                b->p = NULL, b->n = 0;
                return 1;
            }
            b->p = np;
        }
        memcpy(b->p + 4 * b->n++, v, sizeof v);
    }
    fclose(f);
    return b->n == 0;
}

/* The bed cut to [0, side]^2 (side <= 0.1 m) or tiled tx x ty times (side 0); sorted along a Morton curve when
 * `sorted` (dem_sort_particles, a scene's particle_order: spatial) */
static dem_sim *bed_sim(const bed_t *b, double side, int tx, int ty, int sorted)
{
    dem_sim *s = dem_create();
    dem_set_effects(s, DEM_EFFECT_CLASSICAL);
    int m = dem_add_material(s, &(dem_material){2500, 5e6, 0.3, 0.3, 0.5});
    double lx = side > 0 ? side : 0.1 * tx, ly = side > 0 ? side : 0.1 * ty, top = 0;
    for (int a = 0; a < (side > 0 ? 1 : tx); a++)
        for (int c = 0; c < (side > 0 ? 1 : ty); c++)
            for (long k = 0; k < b->n; k++) {
                const double *q = b->p + 4 * k;
                if (side > 0 && (q[0] + q[3] > side || q[1] + q[3] > side))
                    continue;
                double x[3] = {q[0] + 0.1 * a, q[1] + 0.1 * c, q[2]};
                dem_add_particle(s, x, NULL, q[3], m);
                if (q[2] + q[3] > top)
                    top = q[2] + q[3];
            }
    double pts[5][3] = {{0, 0, 0}, {0, 0, 0}, {lx, 0, 0}, {0, 0, 0}, {0, ly, 0}};
    double nrm[5][3] = {{0, 0, 1}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}};
    for (int k = 0; k < 5; k++) {
        dem_wall w;
        memset(&w, 0, sizeof w);
        w.kind = DEM_WALL_PLANE;
        w.material = m;
        memcpy(w.point, pts[k], sizeof w.point);
        memcpy(w.normal, nrm[k], sizeof w.normal);
        dem_add_wall(s, &w);
    }
    dem_set_gravity(s, (double[3]){0, 0, -9.81});
    dem_set_domain(s, (double[3]){-0.005, -0.005, -0.005}, (double[3]){lx + 0.005, ly + 0.005, top + 0.02});
    dem_set_dt(s, 2e-6);
    if (sorted)
        dem_sort_particles(s);
    return s;
}

/* FNV-1a of positions, velocities and spins; 0 when they cannot be read (bed_table counts 0 as unequal) */
static unsigned long long state_hash(dem_sim *s)
{
    size_t n = 3 * (size_t)dem_count(s);
    double *buf = malloc(sizeof(double) * n);
    unsigned long long h = 1469598103934665603ull;
    dem_field f[3] = {DEM_FIELD_X, DEM_FIELD_V, DEM_FIELD_W};
    if (!buf)
        return 0;
    for (int k = 0; k < 3; k++) {
        if (dem_get_field(s, f[k], buf)) {
            free(buf);
            return 0;
        }
        const unsigned char *c = (const unsigned char *)buf;
        for (size_t q = 0; q < n * sizeof(double); q++)
            h = (h ^ c[q]) * 1099511628211ull;
    }
    free(buf);
    return h;
}

/* The device's copy rate [GB/s, bytes read + written]: clEnqueueCopyBuffer of 256 MiB (or an eighth of the device's
 * memory), best of 5 after a warm-up. The device as dem numbers it (cl_device_get). 0 when it fails. */
static double copy_gbs(int device)
{
    cl_device_info_t info;
    char err[512];
    if (cl_device_get(device, &info, err, sizeof err))
        return 0;
    cl_device_id dev = info.device;
    cl_ulong mem = info.global_mem;
    size_t bytes = (size_t)256 << 20;
    if (mem / 8 < bytes)
        bytes = (size_t)(mem / 8);
    cl_int e;
    cl_context ctx = clCreateContext(NULL, 1, &dev, NULL, NULL, &e);
    if (e != CL_SUCCESS)
        return 0;
    cl_command_queue q = clCreateCommandQueue(ctx, dev, 0, &e);
    cl_mem a = clCreateBuffer(ctx, CL_MEM_READ_WRITE, bytes, NULL, &e), b = clCreateBuffer(ctx, CL_MEM_READ_WRITE, bytes, NULL, &e);
    double best = 0;
    unsigned char zero = 0;
    if (q && a && b && clEnqueueFillBuffer(q, a, &zero, 1, 0, bytes, 0, NULL, NULL) == CL_SUCCESS &&
        clEnqueueCopyBuffer(q, a, b, 0, 0, bytes, 0, NULL, NULL) == CL_SUCCESS && clFinish(q) == CL_SUCCESS)
        for (int r = 0; r < 5; r++) {
            double t0 = now();
            if (clEnqueueCopyBuffer(q, a, b, 0, 0, bytes, 0, NULL, NULL) != CL_SUCCESS || clFinish(q) != CL_SUCCESS)
                break;
            double g = 2.0 * (double)bytes / (now() - t0) / 1e9;
            best = g > best ? g : best;
        }
    if (a)
        clReleaseMemObject(a);
    if (b)
        clReleaseMemObject(b);
    if (q)
        clReleaseCommandQueue(q);
    clReleaseContext(ctx);
    return best;
}

typedef struct {
    long n;
    double rate, bytes_per_particle, contacts;
    double step_bytes; /* the bytes of the buffers given to the kernels launched every step (with DEM_PROFILE) */
    unsigned long long hash;
    char kernels[1024];
    char narrow[512]; /* kernels of every step with fewer work-groups of BED_GROUP items than compute units */
    char buffers[2048]; /* step_bytes buffer by buffer: "kernel: name B, name B, ...; kernel: ..." [bytes / n] */
} bed_result;

typedef struct {
    const char *name;
    double bytes;
} buffer_bytes;

static int by_bytes_down(const void *a, const void *b)
{
    double x = ((const buffer_bytes *)a)->bytes, y = ((const buffer_bytes *)b)->bytes;
    return x < y ? 1 : x > y ? -1 : strcmp(((const buffer_bytes *)a)->name, ((const buffer_bytes *)b)->name);
}

/* kernel k's buffers of at least half a byte per particle, the largest first, as "kernel: name B, name B" after what
 * buf holds (len of it) */
static size_t buffer_list(dem_sim *s, int k, const char *kernel, long n, char *buf, size_t size, size_t len)
{
    const char *names[DEM_KERNEL_BUFFERS_MAX];
    double bytes[DEM_KERNEL_BUFFERS_MAX];
    int count = dem_kernel_buffers(s, k, names, bytes, DEM_KERNEL_BUFFERS_MAX);
    buffer_bytes b[DEM_KERNEL_BUFFERS_MAX];
    int m = 0;
    for (int a = 0; a < count && a < DEM_KERNEL_BUFFERS_MAX; a++) /* (count is all of them) */
        if (bytes[a] / (double)n >= 0.5)
            b[m++] = (buffer_bytes){names[a], bytes[a] / (double)n};
    qsort(b, (size_t)m, sizeof *b, by_bytes_down);
    if (len < size)
        len += (size_t)snprintf(buf + len, size - len, "%s%s:", len ? "; " : "", kernel);
    for (int a = 0; a < m && len < size; a++)
        len += (size_t)snprintf(buf + len, size - len, "%s %s %.0f", a ? "," : "", b[a].name, b[a].bytes);
    return len;
}

/* The work-group size the bench counts groups in (a GPU's usual choice; the runtime picks its own) */
#define BED_GROUP 64

static int bed_run(const bed_t *b, double side, int tx, int ty, int sorted, int one_pass, dem_backend_kind kind,
                   dem_precision prec, long steps, int profile, bed_result *r)
{
    if (profile)
        setenv("DEM_PROFILE", "1", 1);
    else
        unsetenv("DEM_PROFILE");
    dem_sim *s = bed_sim(b, side, tx, ty, sorted);
    dem_config c;
    dem_config_default(&c);
    c.backend = kind;
    c.precision = prec;
    c.one_pass = one_pass; /* dem_config.one_pass: contact_rows on every step but the last of the call */
    if (getenv("DEM_BENCH_SKIN"))
        c.skin = atof(getenv("DEM_BENCH_SKIN"));
    memset(r, 0, sizeof *r);
    if (dem_start(s, &c) || dem_step(s, 5)) {
        fprintf(stderr, "bench bed: %s\n", dem_error(s));
        dem_destroy(s);
        return 1;
    }
    const char **names;
    const double *secs;
    int cnt;
    double before[64] = {0};
    dem_kernel_times(s, &names, &secs, &cnt);
    for (int k = 0; k < cnt && k < 64; k++)
        before[k] = secs[k];
    double t0 = now();
    int e = dem_step(s, steps);
    double t = now() - t0;
    if (e) {
        fprintf(stderr, "bench bed: %s\n", dem_error(s));
        dem_destroy(s);
        return 1;
    }
    r->n = dem_count(s);
    r->rate = (double)r->n * steps / t;
    r->bytes_per_particle = kind == DEM_BACKEND_OPENCL ? (double)dem_device_bytes(s) / r->n : 0;
    dem_energy_t en;
    dem_energy(s, &en);
    r->contacts = (2.0 * en.contacts + en.wall_contacts) / r->n;
    r->hash = state_hash(s);
    dem_kernel_times(s, &names, &secs, &cnt);
    size_t len = 0;
    /* the kernels of every step: each launched once per step, so its bytes / its time is a rate. The walls' sums and
     * integrate_kick are in the last step's sequence but run only on the last step of a dem_step call (the other
     * steps' second kick is joined to the next step's first: integrate_kick_kick_drift; host/core/step_loop.c): left
     * out */
    int cu = 0; /* the device's compute units, from its description */
    char what[512];
    if (kind == DEM_BACKEND_OPENCL && !dem_device_describe(0, what, sizeof what))
        sscanf(what, "%d compute units", &cu);
    size_t nl = 0;
    r->narrow[0] = 0;
    for (int k = 0; k < cnt && cu > 0; k++) { /* every kernel of the step's sequence, walls' sums included */
        const char *nm = names[k];
        int in_step = dem_kernel_launched(s, 0, nm);
        long items = dem_kernel_item_count(s, k);
        if (in_step && items > 0 && (items + BED_GROUP - 1) / BED_GROUP < cu)
            nl += (size_t)snprintf(r->narrow + nl, sizeof r->narrow - nl, "%s%s %ld", nl ? ", " : "", nm, items);
        if (nl >= sizeof r->narrow)
            break;
    }
    size_t blen = 0;
    for (int k = 0; k < cnt && k < 64 && profile; k++) {
        double us = 1e6 * (secs[k] - before[k]) / steps;
        int each_step = dem_kernel_launched(s, 0, names[k]) && strncmp(names[k], "wall_reduce", 11) &&
                        strcmp(names[k], "integrate_kick");
        if (one_pass) /* the two contact passes ran on the call's last step alone, contact_rows on every other */
            each_step = (!strcmp(names[k], "contact_rows") && secs[k] > before[k]) ||
                        (each_step && strcmp(names[k], "contact_pairs") && strcmp(names[k], "contact_forces"));
        if (each_step) {
            r->step_bytes += dem_kernel_bytes(s, k);
            blen = buffer_list(s, k, names[k], r->n, r->buffers, sizeof r->buffers, blen);
        }
        if (us >= 1 && each_step)
            len += (size_t)snprintf(r->kernels + len, sizeof r->kernels - len, "%s%s %.0f (%.1f GB/s)", len ? ", " : "",
                                    names[k], us, dem_kernel_bytes(s, k) / (us * 1e-6) / 1e9);
        else if (us >= 1)
            len += (size_t)snprintf(r->kernels + len, sizeof r->kernels - len, "%s%s %.0f", len ? ", " : "", names[k], us);
        if (len >= sizeof r->kernels)
            break;
    }
    dem_destroy(s);
    return 0;
}

/* The summary line of `dem conform` on this device, from the file DEM_BENCH_CONFORM names (make bench runs it
 * first), for the bed table's JSON: whether the device reproduces the reference; "not run" without it. */
static const char *conform_summary(void)
{
    static char line[512];
    snprintf(line, sizeof line, "not run");
    const char *p = getenv("DEM_BENCH_CONFORM");
    FILE *f = p ? fopen(p, "r") : NULL;
    char buf[1024];
    int rows = 0, header = 0;
    while (f && fgets(buf, sizeof buf, f)) {
        header |= !strncmp(buf, "dem conform: ", 13) && strstr(buf, " runs of 150 steps on ");
        rows += strstr(buf, "  equal  ") || strstr(buf, " DIFFERS") || strstr(buf, " MISSING");
        if (header && !strncmp(buf, "dem conform: ", 13) && !strstr(buf, " runs of 150 steps on ")) {
            buf[strcspn(buf, "\n")] = 0;
            for (char *c = buf; *c; c++) /* a JSON string */
                if (*c == '"' || *c == '\\')
                    *c = '\'';
            snprintf(line, sizeof line, "%s", buf + 13);
            header = 2; /* the summary seen */
        }
    }
    if (header == 1) /* stopped before its summary (a time limit) */
        snprintf(line, sizeof line, "incomplete: %d runs compared, no summary", rows);
    if (f)
        fclose(f);
    return line;
}

static void bed_table(int quick)
{
    char path[4096];
    snprintf(path, sizeof path, "%s", getenv("DEM_BENCH_BED") ? getenv("DEM_BENCH_BED") : DEM_DEFAULT_SOURCE_DIR "/out/peer/bed.csv");
    bed_t b;
    if (bed_read(path, &b)) {
        printf("\n(no poured bed at %s: `make bench-peer` pours it once, or set DEM_BENCH_BED)\n", path);
        return;
    }
    /* sides giving ~1e3, 1e4 and the whole bed, then 1e6 by tiling (not in quick mode) */
    struct { double side; int tx, ty; } sizes[4] = {{0.01, 0, 0}, {0.032, 0, 0}, {0.1, 0, 0}, {0, 5, 2}};
    int nsizes = quick ? 3 : 4;
    const char *json = getenv("DEM_BENCH_JSON") ? getenv("DEM_BENCH_JSON") : DEM_DEFAULT_SOURCE_DIR "/out/bench_bed.json";
    char json_tmp[4200]; /* written whole, then renamed: a bench stopped at a time limit leaves no half a file */
    snprintf(json_tmp, sizeof json_tmp, "%s.part", json);
    FILE *js = fopen(json_tmp, "w");
    char dev[256] = "";
    dem_device_name(0, dev, sizeof dev);
    double gbs = copy_gbs(0);
    printf("\n### Throughput on a poured polydisperse bed\n\n%s: %ld spheres as poured (random order), cut or "
           "tiled; Hertz-Mindlin with friction, damping, gravity, 5 walls; dt 2e-6 s. OpenCL device 0: %s. The state "
           "after the timed steps is hashed on each backend. The device copies %.1f GB/s (clEnqueueCopyBuffer, bytes read "
           "+ written); beside each kernel launched every step, the bytes of the buffers it is given over its time: the "
           "rate if it moved each of them once (gathers that hit the cache make it higher, rows and records it skips "
           "lower). bytes/particle-step: those bytes summed over the kernels of every step, over n - the traffic of a "
           "step by that count, the same proxy on every device (goal: 400 in fp32). \"sorted, one pass\": the "
           "contacts in one kernel (dem_config.one_pass) on every step of the timed call but its last (the two passes), "
           "its hash against the two passes' row.\n\n"
           "| n | order | contacts/particle | backend | precision | particle-steps/s | device bytes/particle | bytes/particle-step | state hash = reference | us per step by kernel |\n"
           "|---|---|---|---|---|---|---|---|---|---|\n", path, b.n, dev, gbs);
    if (js)
        fprintf(js, "{\n  \"bench\": \"poured bed\", \"bed\": \"%s\", \"device\": \"%s\", \"copy_gb_per_s\": %.2f,\n  \"rows\": [",
                path, dev, gbs);
    double lnN[8], lnT[8];
    int nfit = 0, first = 1, narrow_said[4] = {0}, narrow_rows = 0;
    char narrow[4][600] = {"", "", "", ""}, buffers[2][2][2200] = {{"", ""}, {"", ""}}; /* [one pass][fp64, fp32] */
    unsigned long long sorted_hash[2] = {0, 0}, sorted_ref[2] = {0, 0}; /* this size's two-pass sorted rows' */
    const char *only_sizes = getenv("DEM_BENCH_BED_SIZES"); /* e.g. "3": the 1e6 rows only (0..3: 1e3 .. 1e6) */
    for (int z = 0; z < nsizes; z++)
        for (int q = 0; q < 6; q++) { /* as poured, sorted, sorted in one pass (dem_config.one_pass); fp64, fp32 */
            if (only_sizes && !strchr(only_sizes, '0' + z))
                break;
            int p = q & 1, sorted = q >= 2, onep = q >= 4;
            if (q == 0)
                sorted_hash[0] = sorted_hash[1] = sorted_ref[0] = sorted_ref[1] = 0;
            dem_precision prec = p ? DEM_FP32 : DEM_FP64;
            bed_result ro, rp, rr;
            long n_est = z == 3 ? 10 * b.n : (long)(b.n * sizes[z].side * sizes[z].side / 0.01);
            long steps = (long)((quick ? 5e6 : 4e7) / (double)(n_est > 0 ? n_est : 1));
            steps = steps < 20 ? 20 : steps > 2000 ? 2000 : steps;
            const char *order = onep ? "sorted, one pass" : sorted ? "sorted" : "as poured";
            if (bed_run(&b, sizes[z].side, sizes[z].tx, sizes[z].ty, sorted, onep, DEM_BACKEND_OPENCL, prec, steps, 0, &ro) ||
                bed_run(&b, sizes[z].side, sizes[z].tx, sizes[z].ty, sorted, onep, DEM_BACKEND_OPENCL, prec, steps, 1, &rp)) {
                printf("| %ld | %s | | opencl | %s | failed | | | | |\n", n_est, order, p ? "fp32" : "fp64");
                continue;
            }
            /* one pass has the two passes' bits: its rows are checked against the sorted rows' hashes (the reference's
             * where it ran), not run on the reference again */
            int have_ref = z < 3 && !onep && !bed_run(&b, sizes[z].side, sizes[z].tx, sizes[z].ty, sorted, 0,
                                                      DEM_BACKEND_REFERENCE, prec, steps, 0, &rr);
            const char *eq = !have_ref ? "not checked" : ro.hash && rr.hash == ro.hash && rp.hash == ro.hash ? "yes" : "NO";
            if (sorted && !onep)
                sorted_hash[p] = ro.hash, sorted_ref[p] = have_ref ? rr.hash : 0;
            if (onep) /* "yes": the two passes' hash, which equalled the reference's */
                eq = !sorted_hash[p] ? "not checked (no two-pass row)"
                     : !ro.hash || ro.hash != sorted_hash[p] || rp.hash != ro.hash ? "NO (not the two passes')"
                     : sorted_ref[p] == sorted_hash[p] ? "yes (= two passes)" : "= two passes";
            printf("| %ld | %s | %.2f | opencl | %s | %.3g | %.0f | %.0f | %s | %s |\n", ro.n, order, ro.contacts,
                   p ? "fp32" : "fp64", ro.rate, ro.bytes_per_particle, rp.step_bytes / (double)rp.n, eq, rp.kernels);
            narrow_rows += ro.n >= 50000;
            if (ro.n >= 50000 && rp.narrow[0] && !narrow_said[z] && !onep) { /* (one pass: its last step's two) */
                snprintf(narrow[z], sizeof narrow[z], "n = %ld: %s", ro.n, rp.narrow);
                narrow_said[z] = 1;
            }
            if (ro.n >= 50000 && sorted && rp.buffers[0]) /* the largest sorted rows' (the last seen) */
                snprintf(buffers[onep][p], sizeof buffers[onep][p], "n = %ld, %s%s: %s", ro.n, p ? "fp32" : "fp64",
                         onep ? ", one pass" : "", rp.buffers);
            if (have_ref)
                printf("| %ld | %s | | reference | %s | %.3g | | | | |\n", rr.n, order, p ? "fp32" : "fp64", rr.rate);
            fflush(stdout);
            if (!p && sorted && !onep && ro.n >= 5000) {
                lnN[nfit] = log((double)ro.n);
                lnT[nfit++] = log((double)ro.n / ro.rate);
            }
            if (js) {
                char refrate[32] = "null";
                if (have_ref)
                    snprintf(refrate, sizeof refrate, "%.4g", rr.rate);
                fprintf(js, "%s\n    {\"n\": %ld, \"order\": \"%s\", \"one_pass\": %s, \"precision\": \"%s\", \"steps\": %ld, \"contacts_per_particle\": %.3f, "
                        "\"opencl_particle_steps_per_s\": %.4g, \"device_bytes_per_particle\": %.0f, \"bytes_per_particle_step\": %.0f, "
                        "\"reference_particle_steps_per_s\": %s, \"hash_opencl\": \"%016llx\", \"hash_equal\": \"%s\"}",
                        first ? "" : ",", ro.n, sorted ? "sorted" : "as poured", onep ? "true" : "false", p ? "fp32" : "fp64",
                        steps, ro.contacts, ro.rate, ro.bytes_per_particle,
                        rp.step_bytes / (double)rp.n,
                        refrate, ro.hash, eq);
                first = 0;
            }
        }
    /* the kernels of a step too narrow to give every compute unit a work-group (docs/design.md "The walls' sum as a
     * tree": the tree's upper levels are latency, not throughput) */
    char cuw[512] = "";
    dem_device_describe(0, cuw, sizeof cuw);
    printf("\nKernels of a step with fewer work-groups of %d items than the device's compute units (%.*s), n >= 5e4: ",
           BED_GROUP, (int)strcspn(cuw, ","), cuw);
    int any = 0;
    for (int z = 0; z < 4; z++)
        if (narrow[z][0])
            printf("%s%s", any++ ? "; " : "", narrow[z]);
    printf("%s\n", any ? " (items per launch)" : narrow_rows ? "none" : "not measured (no row of 5e4 spheres or more)");
    /* where bytes/particle-step comes from: the buffers of each kernel of every step (docs/design.md "Bytes per
     * particle-step") */
    printf("\nBytes per particle-step by buffer (sorted, the largest n of 5e4 or more; each kernel of every step, its "
           "buffers of at least 0.5 byte a particle, largest first): ");
    int said = 0;
    for (int o = 0; o < 2; o++)
        for (int p = 1; p >= 0; p--)
            if (buffers[o][p][0])
                printf("%s%s", said++ ? ". " : "", buffers[o][p]);
    printf("%s\n", said ? "" : "not measured (no row of 5e4 spheres or more)");
    if (js) {
        fprintf(js, "\n  ],\n  \"narrow_kernels\": \"");
        for (int z = 0, a = 0; z < 4; z++)
            if (narrow[z][0])
                fprintf(js, "%s%s", a++ ? "; " : "", narrow[z]);
        fprintf(js, "\",\n  \"step_buffers_fp32\": \"%s\",\n  \"step_buffers_fp64\": \"%s\",\n"
                "  \"step_buffers_one_pass_fp32\": \"%s\",\n  \"step_buffers_one_pass_fp64\": \"%s\",\n  \"conform\": \"%s\",\n",
                buffers[0][1], buffers[0][0], buffers[1][1], buffers[1][0], conform_summary());
    }
    if (nfit >= 2) { /* least squares slope of ln(time per step) on ln n, fp64 OpenCL, n >= 5000 */
        double sx = 0, sy = 0, sxx = 0, sxy = 0;
        for (int k = 0; k < nfit; k++)
            sx += lnN[k], sy += lnT[k], sxx += lnN[k] * lnN[k], sxy += lnN[k] * lnT[k];
        double slope = (nfit * sxy - sx * sy) / (nfit * sxx - sx * sx);
        printf("\nCost per step grows as n^%.3f (fp64 OpenCL, sorted, %d sizes from 1e4 up; goal <= 1.05).\n", slope, nfit);
        if (js && isfinite(slope))
            fprintf(js, "  \"cost_exponent_fp64\": %.4f\n}\n", slope);
        else if (js)
            fprintf(js, "  \"cost_exponent_fp64\": null\n}\n");
    } else if (js)
        fprintf(js, "  \"cost_exponent_fp64\": null\n}\n");
    if (js)
        fclose(js), rename(json_tmp, json), printf("(JSON: %s)\n", json);
    free(b.p);
}

int main(void)
{
    int sides[8] = {8, 17, 37}, nsides = 3;
    const char *env = getenv("DEM_BENCH_SIZES");
    if (env) {
        nsides = 0;
        for (char *p = (char *)env; *p && nsides < 8;) {
            char *end;
            long v = strtol(p, &end, 10);
            if (end == p)
                break;
            sides[nsides++] = (int)v;
            p = end;
        }
    }
    int quick = getenv("DEM_BENCH_QUICK") != NULL;
    const char *only = getenv("DEM_BENCH_ONLY");
    if (only && !strcmp(only, "models")) {
        model_cost_table(quick);
        return 0;
    }
    if (only && !strcmp(only, "series")) {
        series_cost_table(quick);
        return 0;
    }
    if (only && !strcmp(only, "sizes")) {
        size_ratio_table();
        return 0;
    }
    if (only && !strcmp(only, "membranes")) {
        membrane_cost_table(quick);
        return 0;
    }
    if (only && !strcmp(only, "effects")) {
        effects_table(quick);
        return 0;
    }
    if (only && !strcmp(only, "bed")) {
        bed_table(quick);
        return 0;
    }
    int ndev = dem_device_count();
    printf("# libdem %s benchmark: dense Hertz-Mindlin packing (friction, damping, gravity, 6 walls)\n\n", DEM_VERSION);
    for (int d = 0; d < ndev; d++) {
        char name[256];
        dem_device_name(d, name, sizeof name);
        printf("OpenCL device %d: %s\n", d, name);
    }
    { /* provenance: how each backend's code was built */
        for (int b = -1; b < ndev; b++) {
            dem_config c;
            dem_config_default(&c);
            c.backend = b < 0 ? DEM_BACKEND_REFERENCE : DEM_BACKEND_OPENCL;
            c.device = b < 0 ? 0 : b;
            dem_sim *t = dem_create();
            dem_add_material(t, &(dem_material){2500, 1e7, 0.3, 0.5, 0.4});
            dem_add_particle(t, (double[3]){0, 0, 0}, NULL, 0.001, 0);
            dem_set_dt(t, 1e-6);
            if (dem_start(t, &c) == 0)
                printf("build (%s): %s\n", b < 0 ? "reference" : "opencl", dem_build_info(t));
            dem_destroy(t);
        }
    }
    printf("\n| n | contacts/particle | backend | precision | particle-steps/s | us per step by kernel |\n"
           "|---|---|---|---|---|---|\n");
    for (int si = 0; si < nsides; si++) {
        int side = sides[si], n = side * side * side + (side - 1) * (side - 1) * (side - 1);
        long steps = (long)((quick ? 2e6 : 2e7) / n);
        if (steps < 20)
            steps = 20;
        if (steps > 2000)
            steps = 2000;
        for (int b = -1; b < ndev; b++)
            for (int p = 0; p < 2; p++) {
                dem_precision prec = p ? DEM_FP64 : DEM_FP32;
                result r, rp;
                dem_backend_kind kind = b < 0 ? DEM_BACKEND_REFERENCE : DEM_BACKEND_OPENCL;
                /* the rate from a run without profiling; the per-kernel split from a second, profiled run (an
                 * OpenCL profiled run waits for every kernel, so it is slower overall) */
                int e = run(side, kind, b < 0 ? 0 : b, prec, steps, 0, &r) ||
                        run(side, kind, b < 0 ? 0 : b, prec, steps, kind == DEM_BACKEND_OPENCL, &rp);
                memcpy(r.kernels, rp.kernels, sizeof r.kernels);
                if (e)
                    printf("| %d | | %s | %s | failed: %s | |\n", n, b < 0 ? "reference" : "opencl",
                           p ? "fp64" : "fp32", r.desc);
                else
                    printf("| %d | %.2f | %s | %s | %.3g | %s |\n", n, r.contacts, r.desc, p ? "fp64" : "fp32", r.rate,
                           r.kernels);
                fflush(stdout);
            }
    }
    bed_table(quick);
    effects_table(quick);
    model_cost_table(quick);
    series_cost_table(quick);
    size_ratio_table();
    membrane_cost_table(quick);
    return 0;
}
