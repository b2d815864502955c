/* test_tablet.c - a tablet press cycle at small scale (tests/scenes/tablet_small.yaml): 600 spheres poured
 * into a finite die (dem_wall.height), compacted by the upper punch under a servo to 1 N, held, decompressed, and
 * ejected by the lower punch. Checks the signs and balances a press must show, and that PoCL has the reference's
 * bits after the whole cycle:
 *   - no sphere leaves the die before ejection (inside the bore, between the punches);
 *   - the relative density rises monotonically during compaction;
 *   - in the dwell, force balance on the compact: upper punch + weight = lower punch + die-wall friction (averaged
 *     over the dwell's steps), each force with its sign (the punches pushed apart, the die dragged down);
 *   - after ejection every sphere is above the die, whose wall then carries nothing. */
#include "test_util.h"
#include "scene.h"
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SCENE DEM_DEFAULT_SOURCE_DIR "/tests/scenes/tablet_small.yaml"
enum { DIE = 0, LOWER = 1, UPPER = 2 };
#define R_DIE 0.004
#define H_DIE 0.012

static dem_sim *load_file(const char *path, dem_backend_kind be, scene **sc, scene_run *run)
{
    char err[2048];
    *sc = scene_load(path, err, sizeof err);
    if (!*sc)
        fail_msg("%s", err);
    dem_sim *s = scene_build(*sc, run, err, sizeof err);
    if (!s)
        fail_msg("%s", err);
    run->cfg.backend = be;
    start_or_fail(s, &run->cfg);
    return s;
}

static dem_sim *load(dem_backend_kind be, scene **sc, scene_run *run) { return load_file(SCENE, be, sc, run); }

static double zpos(dem_sim *s, int wall)
{
    double p[3];
    dem_wall_position(s, wall, p);
    return p[2];
}

/* every sphere's centre inside the bore and between the punches (a sphere pressed against the die overlaps it) */
static int inside_die(dem_sim *s, const double *x, int n)
{
    double zl = zpos(s, LOWER), zu = zpos(s, UPPER);
    for (int i = 0; i < n; i++)
        if (!(hypot(x[3 * i], x[3 * i + 1]) < R_DIE && x[3 * i + 2] > zl && x[3 * i + 2] < fmin(zu, H_DIE)))
            return 0;
    return 1;
}

static void test_press_cycle(void **st)
{
    (void)st;
    scene *sc, *scr;
    scene_run run, runr;
    dem_sim *s = load(DEM_BACKEND_OPENCL, &sc, &run);
    int n = dem_count(s);
    double dt = dem_dt(s), vs = 0, weight = 0;
    for (int i = 0; i < n; i++) {
        double r = dem_particle_radius(s, i), v = 4.0 / 3.0 * M_PI * r * r * r;
        vs += v;
        weight += 1500 * v * 9.81;
    }
    double *x = malloc(sizeof(double) * 3 * (size_t)n);
    /* time line (the scene): settle 0.08 s; servo 0.08-0.16 s; slow lift to 0.22 s, fast to 0.32 s; ejection
     * from 0.32 s to the end at 0.385 s */
    long settle = lround(0.08 / dt), servo_end = lround(0.16 / dt), eject = lround(0.32 / dt), end = run.steps;
    step_or_fail(s, settle);
    dem_get_field(s, DEM_FIELD_X, x);
    assert_true(inside_die(s, x, n));
    /* compaction and dwell, one step at a time (the servo sums the walls every step anyway) */
    double prev_density = 0, fu_sum = 0, fl_sum = 0, fd_sum = 0, f[3], peak = 0;
    long dwell_steps = 0, touched = -1, reached = -1;
    for (long k = settle; k < servo_end; k++) {
        step_or_fail(s, 1);
        dem_wall_force(s, UPPER, f);
        double fu = f[2]; /* the upper punch is pushed up: positive */
        if (touched < 0 && fu > 0.05)
            touched = k;
        if (reached < 0 && fu >= 0.9)
            reached = k;
        if (touched >= 0 && reached < 0) { /* compaction: the gap only closes */
            double density = vs / (M_PI * R_DIE * R_DIE * (zpos(s, UPPER) - zpos(s, LOWER)));
            assert_true(density >= prev_density);
            prev_density = density;
        }
        if (k >= servo_end - lround(0.03 / dt)) { /* the dwell's last 30 ms */
            fu_sum += fu;
            dem_wall_force(s, LOWER, f);
            fl_sum += -f[2]; /* pushed down */
            dem_wall_force(s, DIE, f);
            fd_sum += -f[2]; /* dragged down by friction */
            dwell_steps++;
        }
        if (k % 500 == 0) {
            dem_get_field(s, DEM_FIELD_X, x);
            assert_true(inside_die(s, x, n));
        }
    }
    assert_true(touched > 0 && reached > touched);
    double fu = fu_sum / dwell_steps, fl = fl_sum / dwell_steps, fd = fd_sum / dwell_steps;
    double density = vs / (M_PI * R_DIE * R_DIE * (zpos(s, UPPER) - zpos(s, LOWER)));
    printf("  compaction: punch met the powder at %.4f s, 0.9 N at %.4f s; relative density %.3f (spheres' volume over "
           "the die's between the punches, overlaps counted twice)\n", touched * dt, reached * dt, density);
    printf("  dwell: upper punch %.5f N, lower %.5f N, die wall friction %.5f N, weight %.5f N: upper + weight - lower - "
           "die = %.2g N; transmission %.3f\n", fu, fl, fd, weight, fu + weight - fl - fd, fl / fu);
    assert_true(fabs(fu - 1.0) < 0.05);                        /* the servo holds its target */
    assert_true(fl > 0 && fl <= fu + weight);                   /* the lower punch carries what friction leaves */
    assert_true(fd > -0.01 * fu);                               /* the die is dragged down, not up */
    assert_true(fabs(fu + weight - fl - fd) < 0.02 * fu);       /* the compact is in equilibrium */
    /* decompression: still in the die until the ejection starts */
    for (long k = servo_end; k < eject; k += 500) {
        step_or_fail(s, k + 500 <= eject ? 500 : eject - k);
        dem_get_field(s, DEM_FIELD_X, x);
        if (!inside_die(s, x, n))
            fail_msg("a sphere left the die at %.4f s, before the ejection", (k + 500) * dt);
    }
    /* ejection: the lower punch pushes the compact up and out */
    for (long k = eject; k < end; k += 100) {
        step_or_fail(s, k + 100 <= end ? 100 : end - k);
        dem_wall_force(s, LOWER, f);
        peak = fmax(peak, -f[2]);
    }
    dem_get_field(s, DEM_FIELD_X, x);
    double zmin = INFINITY;
    for (int i = 0; i < n; i++)
        zmin = fmin(zmin, x[3 * i + 2] - dem_particle_radius(s, i));
    dem_wall_force(s, DIE, f);
    printf("  ejection: largest lower-punch force %.4g N; afterwards the lowest sphere bottom at %.5f m (die top %.3f m), "
           "die force %.2g N\n", peak, zmin, H_DIE, hypot(hypot(f[0], f[1]), f[2]));
    assert_true(peak > 0);
    assert_true(zmin > H_DIE - 1e-6);
    assert_true(hypot(hypot(f[0], f[1]), f[2]) == 0);
    /* the same cycle on the reference: the same bits */
    dem_sim *r = load(DEM_BACKEND_REFERENCE, &scr, &runr);
    step_or_fail(r, settle);
    for (long k = settle; k < servo_end; k++) /* the same calls: a dem_step call's end sums the walls */
        step_or_fail(r, 1);
    for (long k = servo_end; k < eject; k += 500)
        step_or_fail(r, k + 500 <= eject ? 500 : eject - k);
    for (long k = eject; k < end; k += 100)
        step_or_fail(r, k + 100 <= end ? 100 : end - k);
    char msg[256];
    if (state_diff(s, r, msg, sizeof msg))
        fail_msg("after the press cycle, PoCL vs reference: %s", msg);
    free(x);
    dem_destroy(s);
    dem_destroy(r);
    scene_free(sc);
    scene_free(scr);
}

/* Concave punches (dem_wall.cup_radius, cup_depth; tests/scenes/tablet_concave.yaml): the powder settles into the
 * lower punch's cup, which carries its weight with the die; no sphere gets behind either punch's face or out of the
 * bore; the upper punch's stage ends at the relative density that counts both cups; PoCL has the reference's bits. */
static dem_sim *concave_run(dem_backend_kind be, scene **sc, scene_run *run, int check)
{
    dem_sim *s = load_file(DEM_DEFAULT_SOURCE_DIR "/tests/scenes/tablet_concave.yaml", be, sc, run);
    int n = dem_count(s);
    double dt = dem_dt(s), weight = 0, f[3], fd[3];
    long settle = lround(0.08 / dt);
    step_or_fail(s, settle);
    if (!check) {
        for (long k = settle; k < run->steps; k += 100)
            step_or_fail(s, k + 100 <= run->steps ? 100 : run->steps - k);
        return s;
    }
    dem_wall lower, upper;
    dem_wall_get(s, LOWER, &lower);
    dem_wall_get(s, UPPER, &upper);
    assert_true(lower.cup_depth == 0.0008 && upper.cup_radius == 0.004);
    double *x = malloc(sizeof(double) * 3 * (size_t)n), pl[3], pu[3];
    for (int i = 0; i < n; i++)
        weight += 1500 * 4.0 / 3.0 * M_PI * pow(dem_particle_radius(s, i), 3) * 9.81;
    dem_wall_force(s, LOWER, f);
    dem_wall_force(s, DIE, fd);
    dem_get_field(s, DEM_FIELD_X, x);
    int in_cup = 0;
    for (int i = 0; i < n; i++)
        in_cup += x[3 * i + 2] < 0.002;
    printf("  settled: lower punch and die carry %.6g N of the weight %.6g N; %d of %d spheres below the lower punch's "
           "land, in its cup\n", -(f[2] + fd[2]), weight, in_cup, n);
    assert_true(fabs(-(f[2] + fd[2]) / weight - 1) < 0.02);
    assert_true(in_cup > 20);
    double rho = 0, prev = 0, zu = zpos(s, UPPER);
    long stopped = -1;
    for (long k = settle; k < run->steps; k += 100) {
        step_or_fail(s, k + 100 <= run->steps ? 100 : run->steps - k);
        dem_get_field(s, DEM_FIELD_X, x);
        dem_wall_position(s, LOWER, pl);
        dem_wall_position(s, UPPER, pu);
        for (int i = 0; i < n; i++) { /* every centre in the bore, in front of both faces */
            double r = dem_particle_radius(s, i);
            if (!(hypot(x[3 * i], x[3 * i + 1]) < R_DIE && dem_wall_overlap(&lower, pl, x + 3 * i, r, NULL) < r &&
                  dem_wall_overlap(&upper, pu, x + 3 * i, r, NULL) < r))
                fail_msg("sphere %d at (%g, %g, %g) m left the space between the punches", i, x[3 * i], x[3 * i + 1],
                         x[3 * i + 2]);
        }
        assert_int_equal(dem_relative_density(s, UPPER, &rho), 0);
        if (stopped < 0 && zpos(s, UPPER) == zu)
            stopped = k;
        if (stopped < 0)
            assert_true(rho >= prev); /* compaction: it only rises */
        prev = rho, zu = zpos(s, UPPER);
    }
    /* the bore between the lands and the two caps, pi c (3 r^2 + c^2) / 6 each */
    double vs = 0, gap = zpos(s, UPPER) - zpos(s, LOWER);
    double cup = M_PI * 0.0008 * (3 * 0.004 * 0.004 + 0.0008 * 0.0008) / 6;
    for (int i = 0; i < n; i++)
        vs += 4.0 / 3.0 * M_PI * pow(dem_particle_radius(s, i), 3);
    dem_wall_force(s, UPPER, f);
    printf("  pressed: the upper punch stopped at %.4f s, gap %.4f mm between the lands, relative density %.5f (hand: "
           "%.5f), upper punch force %.4g N\n", stopped * dt, 1e3 * gap, rho, vs / (M_PI * R_DIE * R_DIE * gap + 2 * cup),
           f[2]);
    assert_true(stopped > 0);
    assert_true(rho >= 0.62 && rho < 0.6205); /* the stage's step moves the punch 0.57 um: about 1.3e-4 of density */
    assert_true(fabs(rho / (vs / (M_PI * R_DIE * R_DIE * gap + 2 * cup)) - 1) < 1e-12);
    assert_true(f[2] > 0); /* the powder pushes the upper punch back up */
    free(x);
    return s;
}

static void test_concave_press(void **st)
{
    (void)st;
    scene *sc, *scr;
    scene_run run, runr;
    dem_sim *s = concave_run(DEM_BACKEND_OPENCL, &sc, &run, 1), *r = concave_run(DEM_BACKEND_REFERENCE, &scr, &runr, 0);
    char msg[256];
    if (state_diff(s, r, msg, sizeof msg))
        fail_msg("concave punches, PoCL vs reference: %s", msg);
    dem_destroy(s);
    dem_destroy(r);
    scene_free(sc);
    scene_free(scr);
}

/* The tablet report (tools/plot_tablet.py) of the same cycle run by `dem run`: it draws its PNG and its numbers are
 * the press's - the largest upper punch pressure is the servo's 1 N over the bore, the density there the dwell's,
 * the lower punch carries nearly what the upper one does, the die wall is pressed outwards, the compact springs back
 * once unloaded, the ejection needs a force. */
static void test_tablet_report(void **st)
{
    (void)st;
    char dir[256], err[8192], line[1024] = {0};
    assert_int_equal(test_tmpdir_make(dir, sizeof dir, "dem-test-tablet"), 0);
    assert_int_equal(test_sh(dir, err, sizeof err, "%s/build/dem run %s -o %s/t.h5 > %s/t.log 2>&1 || { cat %s/t.log "
                             ">&2; exit 1; }", DEM_DEFAULT_SOURCE_DIR, SCENE, dir, dir, dir), 0);
    const char *py = test_python_plots(); /* the reports draw PNGs */
    if (test_sh(dir, err, sizeof err, "{ %s %s/tools/plot_tablet.py %s/t.h5 > %s/report.txt; }", py,
                DEM_DEFAULT_SOURCE_DIR, dir, dir))
        fail_msg("plot_tablet.py: %s", err);
    char path[300];
    snprintf(path, sizeof path, "%s/report.txt", dir);
    FILE *fp = fopen(path, "r");
    assert_non_null(fp);
    assert_non_null(fgets(line, sizeof line, fp));
    fclose(fp);
    printf("  %s", line);
    double pmax, dens, ratio, prad, rrad, rec, recmin, yld, ejf, ejp; /* pressures in MPa */
    const char *at = strstr(line, "max_upper_mpa=");
    assert_non_null(at);
    assert_int_equal(sscanf(at, "max_upper_mpa=%lf density_at_max=%lf yield_mpa=%lf transmission=%lf radial_mpa=%lf "
                                "radial_ratio=%lf elastic_recovery=%lf elastic_recovery_min=%lf "
                                "max_ejection_friction_n=%lf max_ejection_punch_n=%lf",
                            &pmax, &dens, &yld, &ratio, &prad, &rrad, &rec, &recmin, &ejf, &ejp), 10);
    assert_true(recmin == rec); /* the punch let go: the lower bound is the recovery itself */
    /* the die wall is pressed outwards, less than the punch presses down (friction carries part of the load) */
    assert_true(prad > 0 && rrad > 0.2 && rrad < 1);
    double target = 1e-6 / (M_PI * R_DIE * R_DIE);
    assert_true(fabs(pmax / target - 1) < 0.05);
    assert_true(dens > 0.55 && dens < 0.72);
    /* friction in the die carries part of the load: the lower punch feels less (a compact stirred by too long a step
     * did not: 1.00, docs/tableting.md) */
    assert_true(ratio > 0.7 && ratio < 0.95);
    assert_true(rec > 0 && rec < 0.5);
    assert_true(yld > 0 && isfinite(yld));
    /* the die's friction holds the compact back as it leaves; the lower punch carries that and the compact's inertia
     * and weight */
    assert_true(ejf > 0 && ejp >= ejf);
    /* and the numbers docs/tableting.md reports for this cycle, to the digits it prints (the bits are every device's:
     * a change that moves one must re-measure and re-record the table) */
    assert_true(fabs(dens - 0.598) <= 0.0005 && fabs(yld - 0.179) <= 0.0005 && fabs(ratio - 0.831) <= 0.0005);
    assert_true(fabs(prad - 0.00830) <= 0.000005 && fabs(rrad - 0.417) <= 0.0005 && fabs(rec - 0.112) <= 0.0005);
    assert_true(fabs(ejf - 0.0065) <= 0.00005 && fabs(ejp - 0.014) <= 0.0005);
    snprintf(path, sizeof path, "%s/t_tablet.png", dir);
    fp = fopen(path, "rb");
    assert_non_null(fp);
    fclose(fp);
    /* the models' comparison (tools/plot_tablet_models.py, make tablet-models) of this one run: its PNG, and a table
     * row with the report's density and dem run's own numbers from the log beside the run */
    if (test_sh(dir, err, sizeof err, "echo 't 0 12.5' > %s/times.txt && %s %s/tools/plot_tablet_models.py "
                "%s/t.h5 --times %s/times.txt -o %s/m.png --table %s/m.md > /dev/null", dir, py, DEM_DEFAULT_SOURCE_DIR,
                dir, dir, dir, dir))
        fail_msg("plot_tablet_models.py: %s", err);
    snprintf(path, sizeof path, "%s/m.md", dir);
    fp = fopen(path, "r");
    assert_non_null(fp);
    char row[1024] = {0};
    for (int k = 0; k < 3 && fgets(row, sizeof row, fp); k++) /* the header, its rule, the run */
        ;
    fclose(fp);
    printf("  %s", row);
    double wall, d_max, p_mpa, largest, mean, stab;
    assert_int_equal(sscanf(row, "| t | %lf | %*s | %lf | %lf | %*s | %*s | %*s | %*s %% | %*s | %lf %% | %lf %% | %lf |",
                            &wall, &d_max, &p_mpa, &largest, &mean, &stab), 6);
    assert_true(wall == 12.5 && fabs(d_max - dens) < 1e-4 && fabs(p_mpa - pmax) < 0.01);
    assert_true(largest > 0 && mean > 0 && largest > mean);
    assert_true(stab > 0 && stab < DEM_STABILITY_LIMIT); /* at 0.07 Rayleigh times (at 0.2 it was 2.3: stirred) */
    snprintf(path, sizeof path, "%s/m.png", dir);
    fp = fopen(path, "rb");
    assert_non_null(fp);
    fclose(fp);
    /* the same cycle run in three parts, each a --restart of the one before (a long press continued across
     * sittings): the first stopped by SIGTERM (raised at step 70001 through DEM_TEST_SIGNAL: app/run.c's handler
     * ends the run one step later with its output complete, its checkpoint and exit status 128 + 15), the second by
     * --stop-after. The report of the parts, given in order, is the whole run's, number for number - the series are
     * joined by step, the restart's first row repeating the part before's last - and a missing part or parts out of
     * order are refused by name */
    assert_int_equal(test_sh(dir, err, sizeof err, "cd %s && DEM_TEST_SIGNAL='70001 15' %s/build/dem run %s -o p1.h5 "
                             "--quiet", dir, DEM_DEFAULT_SOURCE_DIR, SCENE), 128 + 15);
    assert_non_null(strstr(err, "stopped by signal 15"));
    assert_non_null(strstr(err, "at step 70002 of"));
    assert_int_equal(test_sh(dir, err, sizeof err, "cd %s && test -f p1.h5 && test ! -e p1.h5.part && "
                             "%s/build/dem run --restart p1.ckpt.h5 --stop-after 60000 -o p2.h5 --quiet 2>/dev/null && "
                             "%s/build/dem run --restart p2.ckpt.h5 -o p3.h5 --quiet 2>/dev/null", dir,
                             DEM_DEFAULT_SOURCE_DIR, DEM_DEFAULT_SOURCE_DIR), 0);
    if (test_sh(dir, err, sizeof err, "cd %s && %s %s/tools/plot_tablet.py p1.h5 p2.h5 p3.h5 -o p.png "
                "> parts.txt", dir, py, DEM_DEFAULT_SOURCE_DIR))
        fail_msg("plot_tablet.py of the parts: %s", err);
    char parts[1024] = {0};
    snprintf(path, sizeof path, "%s/parts.txt", dir);
    fp = fopen(path, "r");
    assert_non_null(fp);
    assert_non_null(fgets(parts, sizeof parts, fp));
    fclose(fp);
    const char *numbers = strstr(parts, " bore_area_m2="), *whole = strstr(line, " bore_area_m2=");
    assert_non_null(numbers);
    assert_non_null(whole);
    if (strcmp(numbers, whole))
        fail_msg("the report of the run in parts differs from the whole run's:\n%s%s", parts, line);
    assert_int_not_equal(test_sh(dir, err, sizeof err, "cd %s && %s %s/tools/plot_tablet.py p1.h5 p3.h5 "
                                 "-o p.png", dir, py, DEM_DEFAULT_SOURCE_DIR), 0);
    assert_non_null(strstr(err, "missing"));
    assert_int_not_equal(test_sh(dir, err, sizeof err, "cd %s && %s %s/tools/plot_tablet.py p2.h5 p1.h5 "
                                 "-o p.png", dir, py, DEM_DEFAULT_SOURCE_DIR), 0);
    assert_non_null(strstr(err, "order they ran"));
    /* the models' comparison takes such a run as its parts joined by '+' */
    if (test_sh(dir, err, sizeof err, "cd %s && %s %s/tools/plot_tablet_models.py p1.h5+p2.h5+p3.h5 "
                "-o pm.png --table pm.md > /dev/null", dir, py, DEM_DEFAULT_SOURCE_DIR))
        fail_msg("plot_tablet_models.py of the parts: %s", err);
    snprintf(path, sizeof path, "%s/pm.md", dir);
    fp = fopen(path, "r");
    assert_non_null(fp);
    for (int k = 0; k < 3 && fgets(row, sizeof row, fp); k++) /* the header, its rule, the run */
        ;
    fclose(fp);
    double d_parts;
    assert_int_equal(sscanf(row, "| p1 | %*s | %*s | %lf |", &d_parts), 1);
    assert_true(fabs(d_parts - dens) < 1e-4);
    /* a signal from outside (Ctrl-C) while PoCL compiles the kernels at their first launches (an empty PoCL
     * cache): libLLVM, which compiles them in-process, installs its own SIGINT and SIGTERM handlers - in CI a Ctrl-C
     * 3 s in killed the run and left i.h5.part and no checkpoint. dem takes the stop signals in one thread (sigwait)
     * and blocks them in every other, the runtime's threads included: each thread's SIGHUP, SIGINT, SIGUSR1, SIGUSR2
     * and SIGTERM mask bits (0x4A03) are read while the run steps (the last four hex digits of SigBlk: dash's arithmetic stops at 2^63) - the
     * main thread, which took them before (PoCL's threads block them), must block them, and one thread at most, the
     * one in sigwait (which unblocks them while it waits), may take them - then SIGINT: exit status 130 and a
     * readable output and checkpoint at the step it stopped. The background job gets the signals' default actions
     * back (a script's background job starts with SIGINT ignored); dem is killed if it outlives 60 s after the
     * SIGINT or the snippet ends early; the braces send the whole list's stderr to test_sh's file */
    int rc = test_sh(dir, err, sizeof err, "{ cd %s && mkdir -p pocl || exit 1; "
                     "POCL_CACHE_DIR=$PWD/pocl env --default-signal=HUP,INT,TERM %s/build/dem run %s -o i.h5 "
                     "--quiet 2>i.txt & p=$!; trap 'kill -KILL $p 2>/dev/null' EXIT; "
                     "k=0; while [ ! -e i.h5.part ] && [ $k -lt 1200 ]; do sleep 0.05; k=$((k + 1)); done; "
                     "n=0; open=0; main=open; for t in /proc/$p/task/*; do "
                     "  m=$(awk '/^SigBlk/ { print $2 }' $t/status 2>/dev/null); [ -n \"$m\" ] || continue; "
                     "  m=${m#????????????}; n=$((n + 1)); "
                     "  if [ $((0x$m & 0x4A03)) -eq $((0x4A03)) ]; then [ $t = /proc/$p/task/$p ] && main=blocked; "
                     "  else open=$((open + 1)); fi; done; "
                     "kill -INT $p; k=0; while kill -0 $p 2>/dev/null && [ $k -lt 600 ]; do sleep 0.1; "
                     "k=$((k + 1)); done; kill -KILL $p 2>/dev/null; wait $p; r=$?; cat i.txt >&2; "
                     "echo \"threads $n, taking a stop signal $open, the main thread's $main, status $r\" >&2; "
                     "[ $n -ge 2 ] && [ $open -le 1 ] && [ $main = blocked ] && [ $r -eq 130 ]; }", dir,
                     DEM_DEFAULT_SOURCE_DIR, SCENE);
    if (rc)
        fail_msg("SIGINT while the kernels compile: %s", err);
    if (!strstr(err, "stopped by signal 2") || strstr(err, "before the first step"))
        fail_msg("SIGINT while the kernels compile, after the output was opened: %s", err);
    if (test_sh(dir, err, sizeof err, "cd %s && test ! -e i.h5.part && %s -c \"import h5py, sys; "
                "s = h5py.File('i.h5')['series/step'][-1]; c = h5py.File('i.ckpt.h5')['state'].attrs['step']; "
                "sys.exit(0 if s == c and s > 0 else 'series ends at %%d, checkpoint at %%d' %% (s, c))\"",
                dir, py))
        fail_msg("the interrupted run's output: %s", err);
    test_tmpdir_remove(dir);
}

int main(void)
{
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_press_cycle), cmocka_unit_test(test_concave_press), cmocka_unit_test(test_tablet_report)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
